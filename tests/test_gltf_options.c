/* A model needs no JSON scene: the options that change what a model file shows, on files this test
 * writes (tests/gltf_writer.h).
 *  - variants: --variant NAME (or index) puts KHR_materials_variants' mapped material on the
 *    primitive; the default keeps the primitive's own; a name the file lacks is an error listing
 *    the file's variants; a non-glTF file refuses the option.
 *  - animation: --animation NAME or N plays that animation; an unknown one lists the file's.
 *  - ground, shadows, env (through sl_app_init, as the command line does): the floor sits at the
 *    bottom of the bounds and leaves the default camera's framing alone; every light casts
 *    shadows and a shadow provider is loaded; --env replaces the environment map, and a missing
 *    file is an error naming it.
 *  - shadow_render: with --ground --shadows the floor behind the quad, where the key light's ray
 *    meets the quad (computed here), is darker than a lit floor point by more than the shadow's
 *    share of the light; without --shadows the two agree. With the sky's sun a light of its own
 *    (envmap.sun_light, the default) the key light stands down: --shadows adds no light. */
#include "app.h"
#include "camera.h"
#include "check.h"
#include "gltf_writer.h"
#include "image/image.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"

#include <math.h>

static char err[8192], logbuf[1 << 16];

/* The quad with three materials and two variants mapping it to materials 1 and 2, and a second
 * animation "grow" (a scale channel). */
static void variant_file(const char *path) {
    gw_doc g;
    CHECK(gw_quad(&g));
    gw_set(&g, "/materials/1", "{\"name\": \"gold\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [1, 0.8, 0.3, 1]}}");
    gw_set(&g, "/materials/2", "{\"name\": \"blue\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [0.1, 0.2, 1, 1]}}");
    gw_set(&g, "/extensionsUsed", "[\"KHR_materials_variants\"]");
    gw_set(&g, "/extensions", "{\"KHR_materials_variants\": {\"variants\": [{\"name\": \"golden\"}, {\"name\": \"navy\"}]}}");
    gw_set(&g, "/meshes/0/primitives/0/extensions", "{\"KHR_materials_variants\": {\"mappings\": [{\"material\": 1, "
           "\"variants\": [0]}, {\"material\": 2, \"variants\": [1]}]}}");
    gw_set(&g, "/animations/0/name", "\"slide\"");
    gw_set(&g, "/animations/1", "{\"name\": \"grow\", \"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": "
           "\"scale\"}}], \"samplers\": [{\"input\": 4, \"output\": 5}]}");
    CHECK(gw_write(&g, path, GW_GLB));
    gw_free(&g);
}

static bool load(sl_scene *s, const char *path, const char *variant, const char *animation) {
    sl_scene_load_opts o = {.gltf_variant = variant, .gltf_animation = animation};
    memset(s, 0, sizeof *s);
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_scene_load_file(s, path, &o, err, sizeof err);
    sl_log_capture(NULL, 0);
    return ok;
}

static void test_variants(const char *path) {
    const char *choice[] = {NULL, "golden", "navy", "1"};
    const char *material[] = {"variants/paint", "variants/gold", "variants/blue", "variants/blue"};
    for (int k = 0; k < 4; k++) {
        sl_scene s;
        bool ok = load(&s, path, choice[k], NULL);
        CHECK_MSG(ok, "variant %s: %s", choice[k] ? choice[k] : "(default)", err);
        if (ok && s.mesh_count == 1)
            CHECK_MSG(!strcmp(s.materials[s.meshes[0].material].name, material[k]), "variant %s: material %s, expected %s",
                      choice[k] ? choice[k] : "(default)", s.materials[s.meshes[0].material].name, material[k]);
        sl_scene_free(&s);
    }
    sl_scene s;
    CHECK(!load(&s, path, "green", NULL));
    CHECK_CONTAINS(err, "/extensions/KHR_materials_variants/variants: no variant \"green\" (the file has: 0 \"golden\", 1 \"navy\")");
    sl_scene_free(&s);
    CHECK(!load(&s, SL_TEST_DATA_DIR "/scenes/quad.obj", "golden", NULL));
    CHECK_CONTAINS(err, "quad.obj: --variant applies to glTF files only");
    sl_scene_free(&s);
}

static void test_animation(const char *path) {
    sl_scene s;
    CHECK(load(&s, path, NULL, NULL)); /* the first, named in the warning */
    CHECK(s.anim_channel_count == 1 && s.anim_channels[0].path == SL_ANIM_TRANSLATION);
    CHECK_CONTAINS(logbuf, "/animations: 2 animations: the first is played (--animation picks another)");
    sl_scene_free(&s);
    const char *grow[] = {"grow", "1"};
    for (int k = 0; k < 2; k++) {
        CHECK_MSG(load(&s, path, NULL, grow[k]), "--animation %s: %s", grow[k], err);
        CHECK(s.anim_channel_count == 1 && s.anim_channels[0].path == SL_ANIM_SCALE);
        CHECK(!strstr(logbuf, "2 animations"));
        sl_scene_free(&s);
    }
    CHECK(!load(&s, path, NULL, "jump"));
    CHECK_CONTAINS(err, "/animations: no animation \"jump\" (the file has: 0 \"slide\", 1 \"grow\")");
    sl_scene_free(&s);
}

/* `setting`: one more --set (NULL: none) */
static bool init_with(sl_app *app, const char *path, const char *env, bool ground, bool shadows, const char *setting) {
    sl_app_options opt = {.scene_path = path, .backend = SL_BACKEND_OSMESA, .width = 96, .height = 96, .keep_color = true,
                          .env_map = env, .ground = ground, .shadows = shadows};
    opt.settings[opt.setting_count++] = "tonemap.enabled=false";
    opt.settings[opt.setting_count++] = "aa.enabled=false";
    if (setting) opt.settings[opt.setting_count++] = setting;
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_app_init(app, &opt, err, sizeof err);
    sl_log_capture(NULL, 0);
    return ok;
}
static bool init(sl_app *app, const char *path, const char *env, bool ground, bool shadows) {
    return init_with(app, path, env, ground, shadows, NULL);
}

static bool has_plugin(const sl_app *app, const char *id) {
    for (int i = 0; i < app->plugins.count; i++)
        if (!strcmp(app->plugins.items[i]->id, id) && app->plugins.items[i]->ok) return true;
    return false;
}

static void test_scene_options(const char *dir) {
    char path[4200], env[4200];
    gw_doc g;
    CHECK(gw_quad(&g));
    gw_set(&g, "/nodes/1/camera", NULL); /* framed by the default camera */
    snprintf(path, sizeof path, "%s/nocamera.glb", dir);
    CHECK(gw_write(&g, path, GW_GLB));
    gw_free(&g);
    sl_app plain, app;
    CHECK_MSG(init(&plain, path, NULL, false, false), "%s", err);
    CHECK_MSG(init(&app, path, NULL, true, true), "%s", err);
    int ground = -1;
    for (int i = 0; i < app.scene.mesh_count; i++)
        if (!strcmp(app.scene.meshes[i].name, "ground")) ground = i;
    CHECK(ground >= 0 && app.scene.bounds_min[1] == -1 && plain.scene.bounds_min[1] == -1);
    CHECK(app.scene.bounds_max[0] > plain.scene.bounds_max[0] * 2); /* the floor reaches beyond the quad */
    CHECK(app.camera.distance == plain.camera.distance && app.camera.target[1] == plain.camera.target[1]);
    bool all = app.scene.light_count > 0;
    for (int i = 0; i < app.scene.light_count; i++) all = all && app.scene.lights[i].cast_shadows;
    CHECK(all && sl_scene_find_light(&app.scene, "key") >= 0);
    CHECK(has_plugin(&app, "spotlight-shadow") && !has_plugin(&plain, "spotlight-shadow"));
    sl_app_shutdown(&plain);
    sl_app_shutdown(&app);
    /* --env: an EXR replaces the environment; a missing one is refused naming it */
    const float sky[4 * 8 * 4] = {0};
    snprintf(env, sizeof env, "%s/sky.exr", dir);
    CHECK_MSG(sl_image_write(env, sky, 8, 4, false, err, sizeof err), "%s", err);
    CHECK_MSG(init(&app, path, env, false, false), "%s", err);
    CHECK(app.scene.environment.map && strstr(app.scene.environment.map, "/sky.exr"));
    sl_app_shutdown(&app);
    snprintf(env, sizeof env, "%s/no-such-sky.hdr", dir);
    CHECK(!init(&app, path, env, false, false));
    CHECK_CONTAINS(err, "--env ");
    CHECK_CONTAINS(err, "no-such-sky.hdr: No such file or directory");
    sl_app_shutdown(&app);
}

/* The linear radiance at world point p (the floor) in the last frame. */
static float radiance_at(sl_app *app, const float *img, const float p[3]) {
    float view[16], proj[16], v[4] = {0}, c[4] = {0};
    sl_camera_matrices(&app->camera, view, proj);
    for (int r = 0; r < 4; r++) v[r] = view[r] * p[0] + view[4 + r] * p[1] + view[8 + r] * p[2] + view[12 + r];
    for (int r = 0; r < 4; r++) c[r] = proj[r] * v[0] + proj[4 + r] * v[1] + proj[8 + r] * v[2] + proj[12 + r] * v[3];
    int x = (int)((c[0] / c[3] * 0.5f + 0.5f) * 96), y = (int)((0.5f - c[1] / c[3] * 0.5f) * 96);
    if (x < 0 || x >= 96 || y < 0 || y >= 96) return NAN;
    const float *px = img + 4 * (y * 96 + x);
    return (px[0] + px[1] + px[2]) / 3;
}

/* The floor's radiance at `shadowed` and `lit` (below), with and without --shadows ([k][point]),
 * the sky's sun a light of its own or not (setting). */
static bool floor_points(const char *dir, const char *path, const char *setting, const float shadowed[3],
                         const float lit[3], float at[2][2]) {
    bool all = true;
    for (int k = 0; k < 2; k++) {
        sl_app app;
        bool ok = init_with(&app, path, NULL, true, k == 0, setting);
        CHECK_MSG(ok, "%s", err);
        float *img = malloc(sizeof(float) * 4 * 96 * 96);
        ok = ok && sl_app_start_gl(&app, err, sizeof err) && sl_app_render_frame(&app) && sl_app_read_color(&app, img);
        CHECK_MSG(ok, "render: %s", err);
        if (ok) at[k][0] = radiance_at(&app, img, shadowed), at[k][1] = radiance_at(&app, img, lit);
        char out[4300];
        snprintf(out, sizeof out, "%s/shadow_%s_%s.exr", dir, k ? "off" : "on", setting ? "sky_sun_off" : "sky_sun");
        if (ok) sl_app_save(&app, out, err, sizeof err);
        free(img);
        sl_app_shutdown(&app);
        all = all && ok;
    }
    return all;
}

static void test_shadow_render(const char *dir) {
    char path[4200];
    gw_doc g;
    CHECK(gw_quad(&g));
    gw_set(&g, "/nodes/1/camera", NULL); /* the default camera: the floor points below are in view */
    snprintf(path, sizeof path, "%s/shadow.glb", dir);
    CHECK(gw_write(&g, path, GW_GLB));
    gw_free(&g);
    /* the key light travels along d = (0.45, −0.7, −0.55): from the floor point (1.4, −1, −0.55)
     * towards the light the ray meets the quad (z = 0) at (0.95, −0.3); (1.4, −1, 0.55) sees the
     * light past it */
    const float shadowed[3] = {1.4f, -1, -0.55f}, lit[3] = {1.4f, -1, 0.55f};
    float at[2][2] = {{0}}; /* [--shadows on/off][shadowed, lit] */
    /* the sky's sun in the sky's image (envmap.sun_light=false): the key light stands */
    floor_points(dir, path, "envmap.sun_light=false", shadowed, lit, at);
    /* the key light adds E cos θ · albedo / π to the lit floor (Lambert, albedo 0.5, E = 3,
     * cos θ = 0.7 / |d|) and nothing to the shadowed one, where only the sky remains */
    double cos_t = 0.7 / sqrt(0.45 * 0.45 + 0.7 * 0.7 + 0.55 * 0.55), key = 3 * cos_t * 0.5 / M_PI;
    printf("shadow_render: shadowed floor %.4f (without --shadows %.4f), lit floor %.4f (without %.4f, the key "
           "light's closed form adds %.4f)\n", at[0][0], at[1][0], at[0][1], at[1][1], key);
    CHECK_MSG(fabs(at[0][0] - at[1][0]) < 0.03 * at[1][0], "the floor behind the quad is not in the key light's shadow");
    CHECK_MSG(fabs(at[0][1] - at[1][1] - key) < 0.03 * key, "the lit floor gains %.4f, not the key light's %.4f",
              at[0][1] - at[1][1], key);
    CHECK_MSG(fabs(at[1][0] - at[1][1]) < 0.05 * at[1][1], "without --shadows the two floor points differ");
    /* the sky's sun a light of its own (the default): it casts the shadows and the key light
     * stands down, so --shadows adds no light where the sun's shadow does not fall: both floor
     * points (in the key light's would-be shadow and beside it) are as without --shadows */
    float sun[2][2] = {{0}};
    floor_points(dir, path, NULL, shadowed, lit, sun);
    printf("shadow_render, the sky's sun a light: with --shadows %.4f / %.4f, without %.4f / %.4f\n", sun[0][0],
           sun[0][1], sun[1][0], sun[1][1]);
    for (int p = 0; p < 2; p++)
        CHECK_MSG(fabs(sun[0][p] - sun[1][p]) < 0.02 * sun[1][p], "--shadows added light (%.4f against %.4f) where the "
                  "sky's sun stands for the key light", sun[0][p], sun[1][p]);
}

int main(void) {
    char path[4200];
    snprintf(path, sizeof path, "%s/variants.glb", sl_test_dir());
    variant_file(path);
    test_variants(path);
    test_animation(path);
    test_scene_options(sl_test_dir());
    test_shadow_render(sl_test_dir());
    return check_result();
}
