/* Bad input end to end through the application: every case gives a clear message naming the
 * file/line or id and the cause, and nothing crashes. */
#include "check.h"
#include "app.h"
#include "log.h"
#include <stdlib.h>
#include <unistd.h>

static char err[8192];
static char logbuf[65536];

static bool init_text(sl_app *app, const char *json, const char *const *settings) {
    sl_app_options opt = {.scene_text = json, .backend = SL_BACKEND_OSMESA, .width = 32, .height = 32};
    for (const char *const *s = settings; s && *s; s++) opt.settings[opt.setting_count++] = *s;
    err[0] = 0;
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_app_init(app, &opt, err, sizeof err);
    sl_log_capture(NULL, 0);
    return ok;
}

static const char *good =
    "{\n"
    "  \"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
    "  \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}],\n"
    "  \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, 0]}]\n"
    "}\n";

int main(void) {
    sl_app app;
    /* malformed JSON: file:line:column */
    CHECK(!init_text(&app, "{\n  \"materials\": [\n    {\"name\": \"m\",, }\n  ]\n}\n", NULL));
    CHECK_CONTAINS(err, ":3:");
    sl_app_shutdown(&app);

    /* a missing scene file is named with the reason */
    {
        sl_app_options opt = {.scene_path = "/nonexistent/dir/scene.json", .backend = SL_BACKEND_OSMESA};
        CHECK(!sl_app_init(&app, &opt, err, sizeof err));
        CHECK_CONTAINS(err, "/nonexistent/dir/scene.json");
        sl_app_shutdown(&app);
    }

    /* unknown material key: a warning with the nearest valid key, loading goes on */
    const char *typo =
        "{\n  \"materials\": [{\"name\": \"m\",\n     \"base_colour\": [0.5, 0.5, 0.5]}],\n"
        "  \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}]\n}\n";
    CHECK(init_text(&app, typo, NULL));
    CHECK_CONTAINS(logbuf, "base_colour");
    CHECK_CONTAINS(logbuf, "did you mean \"base_color\"");
    CHECK_CONTAINS(logbuf, "no loaded plugin declares key \"base_colour\"");
    CHECK_CONTAINS(logbuf, ":3");
    sl_app_shutdown(&app);

    /* a material value of the wrong type is an error naming file, line, material and key */
    const char *badval =
        "{\n  \"materials\": [{\"name\": \"m\",\n     \"base_color\": \"blue\"}],\n"
        "  \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}]\n}\n";
    CHECK(!init_text(&app, badval, NULL));
    CHECK_CONTAINS(err, ":3");
    CHECK_CONTAINS(err, "base_color");
    sl_app_shutdown(&app);

    /* --set: unknown id, out of range, malformed, unknown material / key / light */
    CHECK(!init_text(&app, good, (const char *[]){"core.ssa=2", NULL}));
    CHECK_CONTAINS(err, "did you mean \"core.ssaa\"");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"core.ssaa=100", NULL}));
    CHECK_CONTAINS(err, "[1, 8]");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"core.ssaa=two", NULL}));
    CHECK_CONTAINS(err, "not an integer");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"core.ssaa", NULL}));
    CHECK_CONTAINS(err, "ID=VALUE");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"material.nope.base_color=1,1,1", NULL}));
    CHECK_CONTAINS(err, "materials: m");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"material.m.base_colr=1,1,1", NULL}));
    CHECK_CONTAINS(err, "did you mean \"base_color\"");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"material.m.base_color=1,1", NULL}));
    CHECK_CONTAINS(err, "three comma-separated numbers");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"light.moon.enabled=false", NULL}));
    CHECK_CONTAINS(err, "lights: sun");
    sl_app_shutdown(&app);
    CHECK(!init_text(&app, good, (const char *[]){"light.sun.intensity=-1", NULL}));
    CHECK_CONTAINS(err, "outside the valid range");
    sl_app_shutdown(&app);
    CHECK(init_text(&app, good, (const char *[]){"light.sun.enabled=off", "material.m.base_color=0.1,0.2,0.3", NULL}));
    CHECK(!app.scene.lights[0].enabled);
    sl_app_shutdown(&app);

    /* a scene naming a model nobody provides, and a light type nobody provides: warned */
    const char *unknown_model =
        "{\"materials\": [{\"name\": \"m\", \"model\": \"ggx\"}],\n"
        " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"cube\"}, \"material\": \"m\"}],\n"
        " \"lights\": [{\"name\": \"s\", \"type\": \"spot\", \"position\": [0, 2, 0]}]}\n";
    CHECK(init_text(&app, unknown_model, NULL));
    CHECK_CONTAINS(logbuf, "shading model \"ggx\" is not provided");
    CHECK_CONTAINS(logbuf, "type \"spot\" is not provided");
    sl_app_shutdown(&app);

    /* a missing texture is named with where it was looked for, rendering goes on (placeholder) */
    const char *missing_tex =
        "{\"materials\": [{\"name\": \"m\", \"base_color_map\": \"no_such_texture.png\"}],\n"
        " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"plane\"}, \"material\": \"m\"}]}\n";
    CHECK(init_text(&app, missing_tex, NULL));
    sl_log_capture(logbuf, sizeof logbuf);
    CHECK(sl_app_start_gl(&app, err, sizeof err));
    CHECK(sl_app_render_frame(&app));
    sl_log_capture(NULL, 0);
    CHECK_CONTAINS(logbuf, "no_such_texture.png");
    sl_app_shutdown(&app);

    /* a malformed procedural texture spec */
    const char *bad_proc =
        "{\"materials\": [{\"name\": \"m\", \"base_color_map\": \"checker:x:1,1,1\"}],\n"
        " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"plane\"}, \"material\": \"m\"}]}\n";
    CHECK(init_text(&app, bad_proc, NULL));
    sl_log_capture(logbuf, sizeof logbuf);
    CHECK(sl_app_start_gl(&app, err, sizeof err));
    sl_log_capture(NULL, 0);
    CHECK_CONTAINS(logbuf, "checker");
    sl_app_shutdown(&app);

    /* unknown debug view */
    {
        sl_app_options opt = {.scene_text = good, .backend = SL_BACKEND_OSMESA, .debug_view = "uvs"};
        CHECK(!sl_app_init(&app, &opt, err, sizeof err));
        CHECK_CONTAINS(err, "did you mean \"uv\"");
        sl_app_shutdown(&app);
    }
    return check_result();
}
