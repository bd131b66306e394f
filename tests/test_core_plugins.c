/* The plugin loader's paths: success, every failure reported with its real cause and the
 * viewer going on without the plugin, requires/conflicts, duplicate shading models, scene
 * plugin names, shader compile errors naming the plugin file and line. */
#include "check.h"
#include "app.h"
#include "core_plugin.h"
#include "log.h"
#include "render/renderer.h"
#include "test_tmp.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdlib.h>
#include <unistd.h>

static char err[16384];
static char logbuf[65536];
static const char *scene =
    "{\"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
    " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}],\n"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -1]}]}\n";

#define TP(name) SL_TEST_PLUGIN_DIR "/" name "/" name ".so"

/* Loads the given plugins; returns the record of the last one. */
static sl_plugin_rec *load(sl_app *app, const char *const *plugins, const char *json, bool strict, bool *ok) {
    sl_app_options opt = {.scene_text = json ? json : scene, .backend = SL_BACKEND_OSMESA, .width = 32, .height = 32,
                          .strict = strict, .no_default_plugins = true}; /* the loader's own records only */
    for (const char *const *p = plugins; *p; p++) opt.plugins[opt.plugin_count++] = *p;
    sl_log_capture(logbuf, sizeof logbuf);
    err[0] = 0;
    *ok = sl_app_init(app, &opt, err, sizeof err);
    sl_log_capture(NULL, 0);
    return app->plugins.count ? app->plugins.items[app->plugins.count - 1] : NULL;
}

static void expect_disabled(const char *path, const char *fragment1, const char *fragment2) {
    sl_app app;
    bool ok;
    load(&app, (const char *[]){path, NULL}, NULL, false, &ok);
    sl_plugin_rec *r = app.plugins.count > 1 ? app.plugins.items[1] : NULL; /* [0] is the core */
    CHECK_MSG(ok, "viewer should go on without %s: %s", path, err);
    CHECK(r && !r->ok);
    if (r && r->disabled_reason) {
        CHECK_CONTAINS(r->disabled_reason, fragment1);
        if (fragment2) CHECK_CONTAINS(r->disabled_reason, fragment2);
    }
    /* and it still renders */
    if (ok) {
        CHECK(sl_app_start_gl(&app, err, sizeof err));
        CHECK(sl_app_render_frame(&app));
    }
    sl_app_shutdown(&app);
    /* --strict makes it fatal */
    load(&app, (const char *[]){path, NULL}, NULL, true, &ok);
    CHECK(!ok);
    CHECK_CONTAINS(err, fragment1);
    sl_app_shutdown(&app);
}

/* Text and JSON of a value in range for light key q, unlike its default. */
static void light_test_value(const sl_param *q, char *text, char *json, size_t n) {
    switch (q->desc.type) {
    case SL_PARAM_BOOL:
        snprintf(text, n, "%s", q->desc.default_value.b ? "false" : "true");
        snprintf(json, n, "%s", text);
        break;
    case SL_PARAM_FLOAT:
        snprintf(text, n, "%.9g", q->desc.min + 0.375 * (q->desc.max - q->desc.min));
        snprintf(json, n, "%s", text);
        break;
    case SL_PARAM_ENUM: {
        int last = 0;
        while (q->desc.enum_values[last + 1]) last++;
        snprintf(text, n, "%s", q->desc.enum_values[last]);
        snprintf(json, n, "\"%s\"", text);
        break;
    }
    case SL_PARAM_COLOR:
        snprintf(text, n, "0.25,0.5,0.75");
        snprintf(json, n, "[0.25, 0.5, 0.75]");
        break;
    default: /* VEC3: a unit vector, so that a normalised key keeps it */
        snprintf(text, n, "0,0.6,-0.8");
        snprintf(json, n, "[0, 0.6, -0.8]");
    }
}

static bool same_value(const sl_param *q, const sl_value *a, const sl_value *b) {
    switch (q->desc.type) {
    case SL_PARAM_BOOL: return a->b == b->b;
    case SL_PARAM_ENUM: case SL_PARAM_INT: return a->i == b->i;
    case SL_PARAM_FLOAT: return fabsf(a->f[0] - b->f[0]) <= 1e-6f * fabsf(b->f[0]);
    default: return fabsf(a->f[0] - b->f[0]) + fabsf(a->f[1] - b->f[1]) + fabsf(a->f[2] - b->f[2]) <= 1e-6f;
    }
}

/* The light keys every light has are one table (core_plugin.c): each key the core declares is
 * a field of the light record, written by --set and by the scene file alike, read back by the
 * panel's getter, and never stored in the plugin slots. */
static void core_light_keys(void) {
    sl_app app;
    bool ok;
    load(&app, (const char *[]){NULL}, NULL, true, &ok);
    CHECK_MSG(ok, "%s", err);
    int keys = 0;
    for (int i = 0; ok && i < app.params.count; i++) {
        const sl_param *q = &app.params.items[i];
        if (q->desc.scope != SL_SCOPE_LIGHT || strcmp(q->owner, "core")) continue;
        keys++;
        const char *key = q->full_id;
        CHECK_MSG(sl_core_light_key(key), "core light key %s is not a field of the light record", key);
        char text[64], json[64], set[128], why[512];
        light_test_value(q, text, json, sizeof text);
        sl_value want, got = {0};
        CHECK(sl_param_parse(q, text, &want, why, sizeof why));
        /* --set light.sun.KEY=VALUE */
        snprintf(set, sizeof set, "light.sun.%s=%s", key, text);
        CHECK_MSG(sl_app_set(&app, set, SL_SRC_CLI, why, sizeof why), "%s: %s", set, why);
        CHECK(sl_core_light_get(&app.scene.lights[0], key, &got));
        CHECK_MSG(same_value(q, &got, &want), "--set %s did not reach the light record", set);
        for (int s = 0; s < 8; s++) CHECK_MSG(app.light_params[0][s] == 0, "%s wrote plugin slot %d", key, s);
        /* the same key in the scene file */
        char scene_json[1024];
        snprintf(scene_json, sizeof scene_json,
                 "{\"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"cube\"}}],\n"
                 " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"%s\": %s}]}\n", key, json);
        sl_app from_file;
        bool loaded;
        load(&from_file, (const char *[]){NULL}, scene_json, true, &loaded);
        CHECK_MSG(loaded, "light key %s in a scene file: %s", key, err);
        if (loaded) {
            memset(&got, 0, sizeof got);
            CHECK(sl_core_light_get(&from_file.scene.lights[0], key, &got));
            CHECK_MSG(same_value(q, &got, &want), "scene key %s: %s differs from --set's value", key, json);
        }
        sl_app_shutdown(&from_file);
    }
    CHECK(keys >= 9); /* enabled … animate_amount */
    char why[512];
    CHECK(!sl_app_set(&app, "light.sun.direction=0,0,0", SL_SRC_CLI, why, sizeof why));
    CHECK_CONTAINS(why, "light.sun.direction: a direction must not be zero");
    sl_app_shutdown(&app);
}

int main(void) {
    setenv("SHADELAB_PLUGIN_PATH", SL_TEST_PLUGIN_DIR, 1);
    sl_app app;
    bool ok;

    /* a good plugin by path and by name */
    sl_plugin_rec *r = load(&app, (const char *[]){TP("tp-good"), NULL}, NULL, false, &ok);
    CHECK(ok && r && r->ok);
    CHECK(sl_params_find(&app.params, "tp-good.gain") != NULL);
    CHECK(sl_params_find(&app.params, "tp-good.enabled") != NULL);
    sl_app_shutdown(&app);
    r = load(&app, (const char *[]){"tp-good", NULL}, NULL, false, &ok);
    CHECK(ok && r && r->ok && !strcmp(r->id, "tp-good"));
    sl_app_shutdown(&app);

    /* every failure names its cause */
    char host_abi[64], major_plus[64];
    snprintf(host_abi, sizeof host_abi, "host provides ABI %d.%d", SL_ABI_MAJOR, SL_ABI_MINOR);
    snprintf(major_plus, sizeof major_plus, "plugin built for ABI %d.%d", SL_ABI_MAJOR + 1, SL_ABI_MINOR);
    expect_disabled(TP("tp-abi-major"), major_plus, host_abi); /* built with SL_ABI_MAJOR=2 */
    expect_disabled(TP("tp-abi-minor"), "plugin built for ABI 1.99", host_abi);
    expect_disabled(TP("tp-no-entry"), "no shadelab_plugin_entry", NULL);
    expect_disabled(TP("tp-undefined"), "missing symbol", "tp_function_that_does_not_exist");
    expect_disabled(TP("tp-missing-dep"), "missing dependency library", "libtp_dep.so");
    expect_disabled(TP("tp-fail-create"), "create() failed", NULL);
    expect_disabled("no-such-plugin", "not found", SL_TEST_PLUGIN_DIR "/no-such-plugin/no-such-plugin.so");
    expect_disabled("/tmp/definitely/not/here.so", "does not exist", NULL);
    expect_disabled(TP("tp-requires"), "requires plugin tp-nonexistent", "not found");
    {
        char path[1100];
        snprintf(path, sizeof path, "%s/not_a_library.so", sl_test_dir());
        FILE *f = fopen(path, "w");
        CHECK(f != NULL);
        if (f) {
            fputs("this is text", f);
            fclose(f);
        }
        expect_disabled(path, "not a shared library", NULL);
    }

    /* a plugin is found for an imported material by its descriptor's material_inputs, so that
     * list and its keys' material_input must agree: either one alone is refused, naming it */
    expect_disabled(TP("tp-input-unlisted"), "create() failed", NULL); /* its add_param was refused */
    CHECK_CONTAINS(logbuf, "material key tp_scale takes the material input \"tp_input\", which its descriptor's "
                           "material_inputs does not list");
    expect_disabled(TP("tp-input-unclaimed"), "material_inputs lists \"tp_input\", which none of its material keys "
                                              "takes", NULL);
    r = load(&app, (const char *[]){"tp-input-agreed", NULL}, NULL, true, &ok);
    CHECK_MSG(ok && r && r->ok, "%s", err);
    sl_app_shutdown(&app);

    /* likewise the shading models (ABI 1.15): the host names the plugin that provides a model by
     * its descriptor's shading_models, read without create() */
    expect_disabled(TP("tp-model-unlisted"), "create() failed", NULL);
    CHECK_CONTAINS(logbuf, "shading model \"tp-model-unlisted-model\" is not in its descriptor's shading_models");
    expect_disabled(TP("tp-model-unprovided"), "shading_models lists \"tp-phantom-model\", which none of its "
                                               "shading-model chunks provides", NULL);
    /* a chunk gated on a parameter that cannot switch programs (ABI 1.17 when_param) */
    expect_disabled(TP("tp-bad-gate"), "when_param \"gain\" is not one of its bool global parameters", NULL);
    char provider[64] = "";
    CHECK(sl_plugin_for_model("tp-other-model", provider, sizeof provider) && !strcmp(provider, "tp-other"));
    CHECK(!sl_plugin_for_model("no-such-model", provider, sizeof provider));

    core_light_keys();

    /* requires pulls in the dependency by name, in order */
    r = load(&app, (const char *[]){"tp-requires-good", NULL}, NULL, false, &ok);
    CHECK(ok);
    CHECK(sl_plugins_find(&app.plugins, "tp-good") >= 0);
    CHECK(app.plugins.items[sl_plugins_find(&app.plugins, "tp-requires-good")]->ok);
    sl_app_shutdown(&app);

    /* conflicts: both named */
    r = load(&app, (const char *[]){"tp-good", "tp-conflicts", NULL}, NULL, false, &ok);
    CHECK(ok && r && !r->ok);
    if (r && r->disabled_reason) CHECK_CONTAINS(r->disabled_reason, "conflicts with plugin tp-good");
    sl_app_shutdown(&app);

    /* two providers of one shading model: a load error naming both */
    r = load(&app, (const char *[]){"tp-dup-model", NULL}, NULL, false, &ok);
    CHECK(ok && r && !r->ok);
    CHECK_CONTAINS(logbuf, "shading model \"lambert\" is already provided by plugin core");
    CHECK(sl_params_find(&app.params, "tp-dup-model.gain") == NULL); /* registrations rolled back */
    sl_app_shutdown(&app);

    /* a scene may only name plugins */
    const char *scene_path =
        "{\"plugins\": [\"" SL_TEST_PLUGIN_DIR "/tp-good/tp-good.so\"],\n"
        " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"cube\"}}]}\n";
    sl_app_options opt = {.scene_text = scene_path, .backend = SL_BACKEND_OSMESA};
    sl_log_capture(logbuf, sizeof logbuf);
    bool loaded = sl_app_init(&app, &opt, err, sizeof err);
    sl_log_capture(NULL, 0);
    bool refused = !loaded || sl_plugins_find(&app.plugins, "tp-good") < 0 ||
                   !app.plugins.items[sl_plugins_find(&app.plugins, "tp-good")]->ok;
    CHECK(refused);
    CHECK(strstr(err, "path") || strstr(logbuf, "path"));
    sl_app_shutdown(&app);
    const char *scene_name =
        "{\"plugins\": [\"tp-good\"],\n \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"cube\"}}]}\n";
    opt.scene_text = scene_name;
    CHECK(sl_app_init(&app, &opt, err, sizeof err));
    CHECK(sl_plugins_find(&app.plugins, "tp-good") >= 0 && app.plugins.items[sl_plugins_find(&app.plugins, "tp-good")]->ok);
    sl_app_shutdown(&app);

    /* A shader compile error in a plugin's chunk (issue 41, one failure policy): the plugin is
     * switched off with ONE message naming it and its file and line (not one per material), the
     * viewer goes on, the materials fall back to the core's model; --strict makes it fatal. */
    const char *bad_scene =
        "{\"materials\": [{\"name\": \"m\", \"model\": \"tp-bad-glsl-model\", \"base_color\": [0.5, 0.5, 0.5]},\n"
        "               {\"name\": \"m2\", \"model\": \"tp-bad-glsl-model\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
        " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3], \"target\": [0, 0, 0]}],\n"
        " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"plane\", \"size\": 10}, \"rotate\": [90, 0, 0], \"material\": \"m\"},\n"
        "           {\"name\": \"n2\", \"mesh\": {\"primitive\": \"cube\"}, \"translate\": [0, 0, -5], \"material\": \"m2\"}],\n"
        " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 1}]}\n";
    for (int strict = 0; strict < 2; strict++) {
        r = load(&app, (const char *[]){"tp-bad-glsl", NULL}, bad_scene, strict, &ok);
        CHECK(ok);
        int errors_before = sl_log_count(SL_LOG_ERROR);
        sl_log_capture(logbuf, sizeof logbuf);
        bool started = sl_app_start_gl(&app, err, sizeof err);
        CHECK_MSG(started, "%s", err);
        app.opt.keep_color = true;
        bool rendered = started && sl_app_render_frame(&app);
        sl_log_capture(NULL, 0);
        CHECK(rendered);
        CHECK_MSG(sl_log_count(SL_LOG_ERROR) - errors_before == 1, "%d errors:\n%s", sl_log_count(SL_LOG_ERROR) - errors_before,
                  logbuf);
        CHECK_CONTAINS(logbuf, "plugin tp-bad-glsl disabled");
        CHECK_CONTAINS(logbuf, "tests/plugins/test_plugin_bad.glsl:4");
        CHECK_CONTAINS(logbuf, "undefined_identifier");
        int k = sl_plugins_find(&app.plugins, "tp-bad-glsl");
        CHECK(k >= 1 && !app.plugins.items[k]->ok);
        if (k >= 1 && app.plugins.items[k]->disabled_reason)
            CHECK_CONTAINS(app.plugins.items[k]->disabled_reason, "test_plugin_bad.glsl:4");
        if (rendered) { /* the plane in Lambert: 0.5/π × E, E = 1 at normal incidence */
            static float px[32 * 32 * 4];
            CHECK(sl_app_read_color(&app, px));
            CHECK_NEAR(px[(16 * 32 + 16) * 4], 0.5 / M_PI, 2e-3);
        }
        if (strict) CHECK(app.strict_failure && strstr(app.strict_failure, "tp-bad-glsl"));
        else CHECK(!app.strict_failure);
        sl_app_shutdown(&app);
    }

    /* the plugin's model, hook and pass work when used */
    const char *mark_scene =
        "{\"materials\": [{\"name\": \"m\", \"model\": \"tp-good-model\", \"base_color\": [0.5, 0.5, 0.5], \"tp_mark\": true}],\n"
        " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3], \"target\": [0, 0, 0]}],\n"
        " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"plane\", \"size\": 10}, \"rotate\": [90, 0, 0], \"material\": \"m\"}],\n"
        " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 1}]}\n";
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 16, .height = 16,
                                                          .scene_json = mark_scene, .float32 = true,
                                                          .plugins = (const char *[]){"tp-good", NULL},
                                                          .settings = (const char *[]){"tp-good.tint=1,0.5,0.25", NULL}},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (h) {
        static float px[16 * 16 * 4];
        CHECK(sl_harness_render(h, px));
        int c = (8 * 16 + 8) * 4;
        /* tp_model: base_color·E·cos (no 1/π), base_color tinted by the surface hook */
        CHECK_NEAR(px[c + 0], 0.5, 2e-3);
        CHECK_NEAR(px[c + 1], 0.25, 2e-3);
        CHECK_NEAR(px[c + 2], 0.125, 2e-3);
        CHECK(sl_harness_set(h, "tp-good.gain=2", err, sizeof err));
        CHECK(sl_harness_render(h, px));
        CHECK_NEAR(px[c + 0], 1.0, 4e-3);
        /* a second harness in the same process is refused with a message, the first one unharmed */
        char err2[512] = "";
        sl_harness *second = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc)}, err2, sizeof err2);
        CHECK(second == NULL);
        CHECK_CONTAINS(err2, "a harness already exists");
        CHECK(sl_harness_render(h, px));
        CHECK_NEAR(px[c + 0], 1.0, 4e-3);
        sl_harness_destroy(h);
        h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc)}, err2, sizeof err2);
        CHECK_MSG(h != NULL, "after destroying the first: %s", err2);
        sl_harness_destroy(h);
    }
    /* SL_DRAW_MATERIALS: the marked material drawn with the plugin's model (no 1/π) in a prepass,
     * the unmarked one skipped; the forward pass still uses the material's own model (Lambert) */
    {
        const char *two =
            "{\"materials\": [{\"name\": \"marked\", \"base_color\": [0.5, 0.5, 0.5], \"tp_mark\": true},\n"
            "                 {\"name\": \"plain\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
            " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3], \"target\": [0, 0, 0]}],\n"
            " \"nodes\": [{\"name\": \"l\", \"translate\": [-1, 0, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 2}, \"rotate\": [90, 0, 0], \"material\": \"marked\"},\n"
            "           {\"name\": \"r\", \"translate\": [1, 0, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 2}, \"rotate\": [90, 0, 0], \"material\": \"plain\"}],\n"
            " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 1}]}\n";
        sl_app_options o = {.scene_text = two, .backend = SL_BACKEND_OSMESA, .width = 32, .height = 16, .keep_color = true};
        o.plugins[o.plugin_count++] = "tp-good";
        o.settings[o.setting_count++] = "tp-good.override_pass=true";
        o.settings[o.setting_count++] = "tp-good.tint=1,1,1";
        sl_app a;
        CHECK(sl_app_init(&a, &o, err, sizeof err) && sl_app_start_gl(&a, err, sizeof err) && sl_app_render_frame(&a));
        static float ov[32 * 16 * 4], col[32 * 16 * 4];
        CHECK(sl_renderer_read(&a, "tp.override", ov));
        CHECK(sl_app_read_color(&a, col));
        int left = (8 * 32 + 8) * 4, right = (8 * 32 + 24) * 4;
        CHECK_NEAR(ov[left], 0.5, 2e-3);               /* tp_model: base·E·cos */
        CHECK_NEAR(col[left], 0.5 / M_PI, 2e-3);       /* forward: Lambert */
        CHECK_NEAR(ov[right], 0.0, 1e-6);              /* unmarked: not drawn */
        CHECK_NEAR(col[right], 0.5 / M_PI, 2e-3);
        sl_app_shutdown(&a);
    }
    /* a material key declared by two plugins is one key, declared in any program either is in:
     * tp-other's model reads tp_scale, first declared by tp-good */
    {
        const char *shared =
            "{\"materials\": [{\"name\": \"m\", \"model\": \"tp-other-model\", \"base_color\": [0.5, 0.5, 0.5], \"tp_scale\": 2},\n"
            "                 {\"name\": \"t\", \"base_color_map\": \"checker:2:1,1,1:0,0,0\"}],\n"
            " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3], \"target\": [0, 0, 0]}],\n"
            " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"plane\", \"size\": 10}, \"rotate\": [90, 0, 0], \"material\": \"m\"},\n"
            "           {\"name\": \"u\", \"translate\": [0, 0, -20], \"mesh\": {\"primitive\": \"cube\"}, \"material\": \"t\"}],\n"
            " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 1}]}\n";
        sl_app_options o = {.scene_text = shared, .backend = SL_BACKEND_OSMESA, .width = 16, .height = 16, .keep_color = true};
        o.plugins[o.plugin_count++] = "tp-good";
        o.plugins[o.plugin_count++] = "tp-other";
        sl_app a;
        bool ok = sl_app_init(&a, &o, err, sizeof err) && sl_app_start_gl(&a, err, sizeof err) && sl_app_render_frame(&a);
        CHECK_MSG(ok, "%s", err);
        static float col[16 * 16 * 4];
        if (ok) {
            CHECK(sl_app_read_color(&a, col));
            CHECK_NEAR(col[(8 * 16 + 8) * 4], 1.0, 4e-3); /* 0.5 · E · cos · tp_scale 2 */
            /* the core's texture for a material key, through the host call plugins use */
            CHECK(sl_renderer_material_texture(&a, 1, "base_color_map") != 0);
            CHECK(sl_renderer_material_texture(&a, 0, "base_color_map") == 0);
        }
        sl_app_shutdown(&a);
    }
    return check_result();
}
