/* Every input in tests/data/fuzz/ (inputs the scene fuzzer found, and hand-made edge cases)
 * loads through sl_scene_load_text without crashing: either a scene or an error message that
 * names the source, and the scene is always safe to free. Run instrumented by the `sanitize`
 * test, this is where a fixed fuzzer crash stays fixed. */
#include "check.h"
#include "fileio.h"
#include "log.h"
#include "scene/scene.h"
#include <dirent.h>
#include <stdlib.h>


int main(void) {
    const char *dir = SL_TEST_DATA_DIR "/fuzz";
    DIR *d = opendir(dir);
    CHECK_MSG(d != NULL, "cannot open %s", dir);
    if (!d) return check_result();
    sl_log_threshold = SL_LOG_ERROR + 1;
    int files = 0, loaded = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.' || strstr(e->d_name, "README")) continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        size_t n;
        char *text = sl_read_file(path, &n, NULL, 0);
        if (!text) continue;
        files++;
        /* the parser sees text up to the first NUL, as with a file */
        sl_scene scene;
        memset(&scene, 0, sizeof scene);
        char err[4096] = "";
        sl_scene_load_opts opts = {0};
        bool ok = sl_scene_load_text(&scene, text, e->d_name, NULL, &opts, err, sizeof err);
        if (ok) {
            loaded++;
            sl_scene_update_transforms(&scene);
        } else {
            CHECK_MSG(err[0] != 0, "%s: failed without a message", e->d_name);
        }
        sl_scene_free(&scene);
        sl_scene_free(&scene); /* documented: safe twice */
        printf("%-40s %s%s\n", e->d_name, ok ? "loaded" : "error: ", ok ? "" : err);
        free(text);
    }
    closedir(d);
    printf("%d inputs, %d loaded, %d rejected with a message\n", files, loaded, files - loaded);
    CHECK(files > 0);
    return check_result();
}
