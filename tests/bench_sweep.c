/* The tiny CI sweep: core.ssaa = 1 and 4 on the bare scene (scenes/basic.json) at 32x32 against the core's
 * declared reference (core.ssaa=8), through the real renderer. The higher-quality setting must
 * have the lower error on every metric; the reference is cached and reused; the outputs are
 * written and --auto-quality picks from them. */
#include "app.h"
#include "autoquality.h"
#include "bench.h"
#include "check.h"
#include "fileio.h"
#include "test_tmp.h"
#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>


static long file_size(const char *path) {
    struct stat st;
    return stat(path, &st) ? -1 : (long)st.st_size;
}

int main(void) {
    char dir[512], cache[600], path[700], err[4096];
    snprintf(dir, sizeof dir, "%s/bench-sweep", sl_test_dir());
    snprintf(cache, sizeof cache, "%s/cache", dir);
    CHECK(sl_bench_mkdirs(dir, err, sizeof err));
    const char *settings[] = {"core.ssaa=1", "core.ssaa=4"};
    /* the core's own supersampling, without the default antialiasing (plugins/aa) on top */
    const char *base[] = {"aa.enabled=false"};
    sl_bench_options o = {.plugin = "core", .scene_path = SL_TEST_DATA_DIR "/../../scenes/basic.json",
                          .width = 32, .height = 32, .frames = 3, .warmup = 1,
                          .settings = settings, .setting_count = 2, .cache_dir = cache,
                          .base_settings = base, .base_setting_count = 1};
    const char *b = getenv("SHADELAB_TEST_BACKEND");
    if (b && *b) sl_backend_parse(b, &o.backend);

    /* the knobs the core declares: core.ssaa 1..8 and core.render_scale 0.25..1 in 5 steps; one
     * at a time they are 8 + 5 settings, as a grid (automatic under 64) 8 × 5, the last fastest */
    sl_bench_options e = o;
    e.setting_count = 0;
    e.sweep = SL_SWEEP_ONE_AT_A_TIME;
    char **list = NULL;
    int count = 0;
    CHECK(sl_bench_enumerate(&e, &list, &count, err, sizeof err));
    CHECK_MSG(count == 13 && !strcmp(list[0], "core.ssaa=1") && !strcmp(list[7], "core.ssaa=8") &&
                  !strcmp(list[8], "core.render_scale=0.25") && !strcmp(list[12], "core.render_scale=1"),
              "%d settings, the first %s", count, count ? list[0] : "none");
    for (int i = 0; i < count; i++) free(list[i]);
    free(list);
    e.sweep = SL_SWEEP_AUTO;
    CHECK(sl_bench_enumerate(&e, &list, &count, err, sizeof err));
    CHECK_MSG(count == 40 && !strcmp(list[0], "core.ssaa=1 core.render_scale=0.25") &&
                  !strcmp(list[39], "core.ssaa=8 core.render_scale=1"),
              "%d settings, the first %s", count, count ? list[0] : "none");
    for (int i = 0; i < count; i++) free(list[i]);
    free(list);

    sl_bench_result r;
    bool ok = sl_bench_run(&o, &r, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return check_result();
    CHECK(r.row_count == 2 && r.rows[0].ok && r.rows[1].ok);
    CHECK(!r.reference.from_cache && r.reference.cache_path && r.reference.accumulate == 1);
    CHECK(!strcmp(r.reference.settings, "core.ssaa=8"));
    sl_bench_error *lo = &r.rows[0].error, *hi = &r.rows[1].error;
    printf("ssaa=1: rmse %.5f relmse %.5f psnr %.2f ssim %.5f %.3f ms\n", lo->rmse, lo->relmse, lo->psnr, lo->ssim,
           r.rows[0].frame_ms_median);
    printf("ssaa=4: rmse %.5f relmse %.5f psnr %.2f ssim %.5f %.3f ms\n", hi->rmse, hi->relmse, hi->psnr, hi->ssim,
           r.rows[1].frame_ms_median);
    /* aliasing at 32x32 is real: a do-nothing comparison (error 0) fails here */
    CHECK(lo->rmse > 5e-3);
    CHECK(hi->rmse < lo->rmse && hi->relmse < lo->relmse && hi->psnr > lo->psnr && hi->ssim > lo->ssim);
    CHECK(hi->rmse < 0.5 * lo->rmse);
    CHECK(lo->nonfinite == 0 && hi->nonfinite == 0);
    /* FLIP sees the aliasing too; supersampling is deterministic: its frames do not scatter */
    CHECK(lo->flip > 0.01 && hi->flip < lo->flip);
    CHECK(r.noise_samples == SL_NOISE_SAMPLES && lo->noise == 0.0 && hi->noise == 0.0);
    CHECK(!r.rows[0].noisy && !r.rows[1].noisy);
    for (int i = 0; i < 2; i++) {
        CHECK(isfinite(r.rows[i].frame_ms_median) && r.rows[i].frame_ms_median > 0 && r.rows[i].frames == 3);
        bool forward = false, resolve = false;
        for (int k = 0; k < r.rows[i].pass_count; k++) {
            forward |= !strcmp(r.rows[i].passes[k].name, "forward") && r.rows[i].passes[k].median_ms > 0;
            resolve |= !strcmp(r.rows[i].passes[k].name, "ssaa-resolve");
        }
        CHECK(forward);
        CHECK(resolve == (i == 1)); /* ssaa=1 runs no resolve pass: it costs nothing */
    }
    CHECK(!strcmp(r.timing_mode, o.backend == SL_BACKEND_EGL ? r.timing_mode : "glfinish"));

    /* outputs */
    snprintf(path, sizeof path, "%s/out.csv", dir);
    CHECK(sl_bench_write_csv(&r, path, SL_METRIC_RMSE, err, sizeof err));
    char *csv = sl_read_file(path, NULL, NULL, 0);
    CHECK_CONTAINS(csv, "settings,label,ok,frame_ms_median");
    CHECK_CONTAINS(csv, "\"core.ssaa=4\",\"ssaa=4\",1,");
    free(csv);
    char json_path[700];
    snprintf(json_path, sizeof json_path, "%s/out.json", dir);
    CHECK(sl_bench_write_json(&r, json_path, SL_METRIC_RMSE, err, sizeof err));
    snprintf(path, sizeof path, "%s/out.png", dir);
    int chart = sl_bench_write_chart(&r, path, SL_METRIC_RMSE, err, sizeof err);
    CHECK_MSG(chart == 1 || (chart == 0 && strstr(err, "gnuplot not found")), "%d: %s", chart, err);
    if (chart == 1) CHECK(file_size(path) > 1000);
    if (chart == 0) printf("note: %s\n", err);

    /* --auto-quality from that JSON: a budget only ssaa=4 meets picks it */
    char *text = sl_read_file(json_path, NULL, NULL, 0);
    sl_aq_choice c;
    double mid = sqrt(lo->rmse * hi->rmse);
    CHECK(sl_autoquality_choose(text, NULL, mid, &c, err, sizeof err));
    CHECK(!strcmp(c.settings, "core.ssaa=4") && c.within_budget);
    free(text);
    sl_app app;
    sl_app_options ao = {.scene_text = sl_basic_scene_json, .backend = SL_BACKEND_OSMESA};
    CHECK(sl_app_init(&app, &ao, err, sizeof err));
    char spec[900];
    snprintf(spec, sizeof spec, "rmse=%g@%s", mid, json_path);
    CHECK_MSG(sl_autoquality_apply(&app, spec, err, sizeof err), "%s", err);
    CHECK(sl_params_find(&app.params, "core.ssaa")->value.i == 4);
    sl_app_shutdown(&app);
    /* an explicit --set wins over the automatic choice */
    ao.settings[0] = "core.ssaa=2";
    ao.setting_count = 1;
    CHECK(sl_app_init(&app, &ao, err, sizeof err));
    CHECK(sl_autoquality_apply(&app, spec, err, sizeof err));
    CHECK(sl_params_find(&app.params, "core.ssaa")->value.i == 2);
    CHECK(!sl_autoquality_apply(&app, "rmse=abc", err, sizeof err));
    CHECK_CONTAINS(err, "expected [METRIC=]BUDGET");
    CHECK(!sl_autoquality_apply(&app, "0.1@/nonexistent/front.json", err, sizeof err));
    CHECK_CONTAINS(err, "does not exist");
    sl_app_shutdown(&app);

    /* the second run takes the reference from the cache and measures the same errors */
    sl_bench_result r2;
    CHECK(sl_bench_run(&o, &r2, err, sizeof err));
    CHECK(r2.reference.from_cache && !strcmp(r2.reference.key, r.reference.key));
    CHECK(r2.row_count == 2 && r2.rows[1].error.rmse == hi->rmse && r2.rows[0].error.ssim == lo->ssim);
    sl_bench_result_free(&r2);
    /* With TAA (aa's default) on, the still's frames are jittered, but each frame of the noise
     * measure is a fresh start, so a deterministic method still measures exactly 0 noise. */
    sl_bench_options taa = o;
    taa.base_setting_count = 0;
    taa.setting_count = 1;
    CHECK(sl_bench_run(&taa, &r2, err, sizeof err));
    CHECK_MSG(r2.row_count == 1 && r2.rows[0].ok && r2.rows[0].error.noise == 0.0, "noise %g", r2.rows[0].error.noise);
    sl_bench_result_free(&r2);
    /* a different size is a different reference */
    sl_bench_options o3 = o;
    o3.width = 24;
    o3.setting_count = 1;
    CHECK(sl_bench_run(&o3, &r2, err, sizeof err));
    CHECK(!r2.reference.from_cache && strcmp(r2.reference.key, r.reference.key));
    sl_bench_result_free(&r2);
    sl_bench_result_free(&r);

    /* a plugin that does not exist is an error naming it */
    sl_bench_options bad = o;
    bad.plugin = "no-such-plugin";
    CHECK(!sl_bench_run(&bad, &r2, err, sizeof err));
    CHECK_CONTAINS(err, "no-such-plugin");
    sl_bench_result_free(&r2);

    char cmd[800];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return check_result();
}
