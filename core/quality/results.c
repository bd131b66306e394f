/* What shadelab-bench's results and the --auto-quality chooser share (see autoquality.h): metric
 * names, the cache directory, the scene hash. */
#include "autoquality.h"
#include "app.h"
#include "fileio.h"
#include "render/composer.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const metric_names[SL_METRIC_COUNT] = {"rmse", "relmse", "dssim", "psnr", "flip", "noise"};
const char *sl_metric_name(sl_metric m) { return m >= 0 && m < SL_METRIC_COUNT ? metric_names[m] : "?"; }
bool sl_metric_parse(const char *name, sl_metric *out) {
    for (int i = 0; i < SL_METRIC_COUNT; i++)
        if (!strcmp(name, metric_names[i])) { *out = (sl_metric)i; return true; }
    return false;
}

const char *sl_bench_default_cache_dir(char *buf, size_t n) {
    const char *e = getenv("SHADELAB_CACHE");
    if (e && *e) snprintf(buf, n, "%s", e);
    else if ((e = getenv("XDG_CACHE_HOME")) && *e) snprintf(buf, n, "%s/shadelab", e);
    else if ((e = getenv("HOME")) && *e) snprintf(buf, n, "%s/.cache/shadelab", e);
    else snprintf(buf, n, "shadelab-cache");
    return buf;
}

uint64_t sl_bench_scene_hash(const char *scene_path) {
    if (!scene_path) return sl_hash64(sl_default_scene_json, strlen(sl_default_scene_json), 0);
    size_t len;
    char *text = sl_read_file(scene_path, &len, NULL, 0);
    if (!text) return 0;
    uint64_t h = sl_hash64(text, len, 0);
    free(text);
    return h;
}
