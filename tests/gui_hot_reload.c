/* Hot reload, headless (OSMesa): shaders are edited on disk while the app runs.
 *   - a compile error keeps the last good program (the image does not change) and the error
 *     names the file and line; the reload reports the failure
 *   - fixing the file (picked up by modification time, as the viewer's poll does) rebuilds the
 *     program and the image changes accordingly
 *   - covered: a plugin's SURFACE chunk (composed material programs), a plugin's stand-alone
 *     POST-pass program, and a core shader (SHADELAB_SHADER_DIR pointed at a copy)
 * Uses a copy of the SDK example plugin (built in tree for this test) in a temporary directory. */
#include "check.h"
#include "app.h"
#include "fileio.h"
#include "log.h"
#include "render/renderer.h"
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

bool sl_renderer_poll_reload(sl_app *app);

static char tmp[256], logbuf[1 << 16], err[8192];

static void sh(const char *fmt, const char *a, const char *b) {
    char cmd[4096];
    snprintf(cmd, sizeof cmd, fmt, a, b);
    if (system(cmd) != 0) { fprintf(stderr, "failed: %s\n", cmd); exit(2); }
}

/* Writes text to dir/name and moves its mtime forward (reloads compare whole seconds). */
static void write_file(const char *dir, const char *name, const char *text) {
    static int bump = 10;
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    fputs(text, f);
    fclose(f);
    struct timeval now;
    gettimeofday(&now, NULL);
    struct timeval tv[2] = {{now.tv_sec + bump, 0}, {now.tv_sec + bump, 0}};
    bump += 10;
    utimes(path, tv);
}


#define W 48
#define H 32
static float img[W * H * 4];
static void render(sl_app *app, float *out) {
    app->opt.keep_color = true; /* the final linear "color" is read */
    CHECK(sl_app_render_frame(app));
    CHECK(sl_app_read_color(app, out));
}
static double max_diff(const float *a, const float *b) {
    double m = 0;
    for (int i = 0; i < W * H * 4; i++) m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

static const char *tint_broken =
    "void example_tint(inout SlSurface s) {\n"
    "    s.base_color = s.base_color * ;\n"       /* line 2: syntax error */
    "}\n";
static const char *tint_green =
    "void example_tint(inout SlSurface s) {\n"
    "    s.base_color = s.base_color * vec3(0.0, 1.0, 0.0);\n"
    "}\n";

int main(void) {
    snprintf(tmp, sizeof tmp, "%s/shadelab-reload-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmp)) return 2;
    char plugdir[512], shaderdir[512];
    snprintf(plugdir, sizeof plugdir, "%s/example", tmp);
    snprintf(shaderdir, sizeof shaderdir, "%s/shaders", tmp);
    /* quoted: a checkout's path may hold spaces */
    sh("mkdir -p '%s' && cp -L '" SL_EXAMPLE_DIR "/example.so' '" SL_EXAMPLE_DIR "/tint.glsl' '" SL_EXAMPLE_DIR
       "/vignette.frag' '%s'", plugdir, plugdir);
    sh("cp -r '" SL_SOURCE_SHADER_DIR "' '%s'%s", shaderdir, "");
    setenv("SHADELAB_SHADER_DIR", shaderdir, 1);

    char so[600];
    snprintf(so, sizeof so, "%s/example.so", plugdir);
    sl_app app;
    sl_app_options opt = {.scene_text = sl_basic_scene_json, .backend = SL_BACKEND_OSMESA, .width = W, .height = H, .plugins = {so}, .plugin_count = 1,
                          .settings = {"example.vignette=false"}, .setting_count = 1, .strict = true};
    CHECK_MSG(sl_app_init(&app, &opt, err, sizeof err) && sl_app_start_gl(&app, err, sizeof err), "%s", err);
    static float good[W * H * 4], green[W * H * 4];
    render(&app, good);

    /* 1. a broken SURFACE chunk: error with file:line, last good program kept */
    write_file(plugdir, "tint.glsl", tint_broken);
    sl_log_capture(logbuf, sizeof logbuf);
    bool polled = sl_renderer_poll_reload(&app);
    sl_log_capture(NULL, 0);
    CHECK(polled);
    char where[600];
    snprintf(where, sizeof where, "%s/tint.glsl:2", plugdir);
    CHECK_CONTAINS(logbuf, where);
    CHECK_CONTAINS(logbuf, "error");
    render(&app, img);
    CHECK_MSG(max_diff(img, good) == 0, "the image changed after a failed reload (max diff %g)", max_diff(img, good));
    /* nothing changed since: no reload storm while the file stays broken */
    sl_log_capture(logbuf, sizeof logbuf);
    bool again = sl_renderer_poll_reload(&app);
    sl_log_capture(NULL, 0);
    CHECK_MSG(!again, "a second poll reloaded again without any file change:\n%s", logbuf);

    /* 2. fixed (differently): picked up by mtime, the image turns green-only */
    write_file(plugdir, "tint.glsl", tint_green);
    sl_log_capture(logbuf, sizeof logbuf);
    CHECK(sl_renderer_poll_reload(&app));
    sl_log_capture(NULL, 0);
    CHECK_MSG(!strstr(logbuf, "error"), "%s", logbuf);
    render(&app, green);
    double red = 0, grn = 0;
    for (int i = 0; i < W * H; i++) { red += green[i * 4]; grn += green[i * 4 + 1]; }
    CHECK_MSG(max_diff(green, good) > 0.05, "the fixed shader did not take effect");
    CHECK_MSG(red < 0.2 * grn, "tint to green: red %g, green %g", red, grn); /* background keeps some red */
    sl_log_capture(logbuf, sizeof logbuf);
    again = sl_renderer_poll_reload(&app);
    sl_log_capture(NULL, 0);
    CHECK_MSG(!again, "poll reloaded again without a file change:\n%s", logbuf);

    /* 3. a core shader (F5 path: sl_renderer_reload_shaders) */
    char lambert[600];
    snprintf(lambert, sizeof lambert, "%s/lambert.glsl", shaderdir);
    char *orig = sl_read_file(lambert, NULL, NULL, 0);
    CHECK(orig != NULL);
    int lines = 0;
    for (const char *c = orig; c && *c; c++) lines += *c == '\n';
    char *broken = malloc(strlen(orig) + 64);
    sprintf(broken, "%snot glsl at all\n", orig);
    write_file(shaderdir, "lambert.glsl", broken);
    sl_log_capture(logbuf, sizeof logbuf);
    int failed = sl_renderer_reload_shaders(&app);
    sl_log_capture(NULL, 0);
    CHECK(failed > 0);
    snprintf(where, sizeof where, "lambert.glsl:%d", lines + 1);
    CHECK_CONTAINS(logbuf, where);
    render(&app, img);
    CHECK_MSG(max_diff(img, green) == 0, "image changed after a failed core-shader reload");
    write_file(shaderdir, "lambert.glsl", orig);
    sl_log_capture(logbuf, sizeof logbuf);
    failed = sl_renderer_reload_shaders(&app);
    sl_log_capture(NULL, 0);
    CHECK_MSG(failed == 0, "%s", logbuf);
    render(&app, img);
    CHECK(max_diff(img, green) == 0);

    /* 4. a plugin's stand-alone pass program (vignette.frag) */
    CHECK(sl_app_set(&app, "example.vignette=true", SL_SRC_GUI, err, sizeof err));
    static float vig[W * H * 4];
    render(&app, vig);
    CHECK(max_diff(vig, green) > 0.01);
    char path[600];
    snprintf(path, sizeof path, "%s/vignette.frag", plugdir);
    char *vorig = sl_read_file(path, NULL, NULL, 0);
    write_file(plugdir, "vignette.frag", "void main() { this is broken }\n");
    sl_log_capture(logbuf, sizeof logbuf);
    failed = sl_renderer_reload_shaders(&app);
    sl_log_capture(NULL, 0);
    CHECK(failed > 0);
    snprintf(where, sizeof where, "%s/vignette.frag:1", plugdir);
    CHECK_CONTAINS(logbuf, where);
    render(&app, img);
    CHECK_MSG(max_diff(img, vig) == 0, "pass output changed after a failed reload");
    write_file(plugdir, "vignette.frag", vorig);
    sl_log_capture(logbuf, sizeof logbuf);
    CHECK(sl_renderer_poll_reload(&app));
    sl_log_capture(NULL, 0);
    CHECK_MSG(!strstr(logbuf, "error"), "%s", logbuf);
    render(&app, img);
    CHECK(max_diff(img, vig) == 0);

    /* 5. a chunk broken outside a reload (a recomposition after an edit): the plugin is switched
     * off with one message; the next hot reload switches it on again with the fixed file */
    write_file(plugdir, "tint.glsl", tint_broken);
    sl_renderer_poll_reload(&app); /* the reload itself keeps the last good program */
    app.params.recompile_version++; /* an edit that recomposes every material */
    int errors = sl_log_count(SL_LOG_ERROR);
    sl_log_capture(logbuf, sizeof logbuf);
    render(&app, img);
    sl_log_capture(NULL, 0);
    CHECK_MSG(sl_log_count(SL_LOG_ERROR) - errors == 1, "%s", logbuf);
    CHECK_CONTAINS(logbuf, "plugin example disabled");
    CHECK(!app.plugins.items[1]->ok);
    write_file(plugdir, "tint.glsl", tint_green);
    sl_log_capture(logbuf, sizeof logbuf);
    CHECK(sl_renderer_poll_reload(&app));
    render(&app, img);
    sl_log_capture(NULL, 0);
    CHECK_MSG(!strstr(logbuf, "error"), "%s", logbuf);
    CHECK(app.plugins.items[1]->ok);
    CHECK_MSG(max_diff(img, vig) == 0, "after the fix the plugin's image is back (max diff %g)", max_diff(img, vig));

    sl_app_shutdown(&app);
    free(orig); free(broken); free(vorig);
    sh("rm -rf '%s'%s", tmp, "");
    return check_result();
}
