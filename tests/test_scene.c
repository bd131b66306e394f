/* The JSON scene loader: the shipped scenes load with the expected contents, and bad input of
 * every kind is refused with a message naming the file, line and cause, without crashing
 * (the fuzz and truncation loops at the end are meant to run under SL_SANITIZE too). */
#include "check.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define FIXTURE(name) SL_TEST_DATA_DIR "/scenes/" name

static char err[4096];
static char logbuf[65536];

/* Loads a fixture; returns the result, the message in err and the warnings in logbuf. */
static bool load_fixture(sl_scene *s, const char *path) {
    memset(s, 0, sizeof *s);
    err[0] = 0;
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_scene_load_file(s, path, NULL, err, sizeof err);
    sl_log_capture(NULL, 0);
    return ok;
}

static bool load_text(sl_scene *s, const char *text) {
    memset(s, 0, sizeof *s);
    err[0] = 0;
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_scene_load_text(s, text, "inline.json", NULL, NULL, err, sizeof err);
    sl_log_capture(NULL, 0);
    return ok;
}

/* A failed load must leave the scene zeroed (nothing to free, nothing leaked). */
static bool scene_is_zero(const sl_scene *s) {
    static const sl_scene zero;
    return memcmp(s, &zero, sizeof zero) == 0;
}

static const float *node_world(const sl_scene *s, const char *name) {
    int i = sl_scene_find_node(s, name);
    return i >= 0 ? s->nodes[i].world : NULL;
}

/* scenes/basic.json: the bare scene (the built-in default before issue 19, still compiled in as
 * the harness's default scene). */
static void check_basic_scene(sl_scene *s) {
    CHECK(s->camera_count == 1 && s->material_count == 4 && s->node_count == 4);
    CHECK(s->mesh_count == 4 && s->light_count == 2 && s->plugin_count == 0);
    CHECK_NEAR(s->cameras[0].fov_y_deg, 40, 0);
    CHECK_NEAR(s->cameras[0].znear, 0.05, 1e-7);
    CHECK_NEAR(s->cameras[0].up[1], 1, 0);
    int red = sl_scene_find_material(s, "red");
    CHECK(red >= 0);
    if (red >= 0) {
        const sl_prop *map = sl_prop_find(&s->materials[red].props, "base_color_map");
        CHECK(map && map->kind == SL_PROP_STRING && strncmp(map->str, "checker:8:", 10) == 0);
        CHECK(map && map->line == 8);
        CHECK(strcmp(s->materials[red].model, "lambert") == 0 && s->materials[red].cast_shadows);
    }
    int white = sl_scene_find_material(s, "white");
    const sl_prop *bc = white >= 0 ? sl_prop_find(&s->materials[white].props, "base_color") : NULL;
    CHECK(bc && bc->kind == SL_PROP_VEC && bc->count == 3 && bc->v[0] == 0.8f);
    int sun = sl_scene_find_light(s, "sun");
    CHECK(sun >= 0);
    if (sun >= 0) {
        const sl_light *l = &s->lights[sun];
        double len = sqrt(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                          l->direction[2] * l->direction[2]);
        CHECK_NEAR(len, 1, 1e-6);
        CHECK_NEAR(l->direction[1] / l->direction[0], -1.0 / -0.4, 1e-5); /* normalised, same direction */
        CHECK(strcmp(l->type, "directional") == 0 && l->intensity == 2.5f && l->enabled && !l->cast_shadows);
    }
    const float *w = node_world(s, "sphere_left");
    CHECK(w && w[12] == -1.6f && w[13] == 0.8f && w[14] == 0.0f);
    /* plane 12 × 12 at y = 0, spheres of radius 0.8 centred at y = 0.8 */
    CHECK_NEAR(s->bounds_min[0], -6, 1e-5);
    CHECK_NEAR(s->bounds_max[0], 6, 1e-5);
    CHECK_NEAR(s->bounds_min[1], 0, 1e-5);
    CHECK_NEAR(s->bounds_max[1], 1.6, 1e-5);
}

static bool has_plugin(const sl_scene *s, const char *name) {
    for (int i = 0; i < s->plugin_count; i++)
        if (!strcmp(s->plugins[i], name)) return true;
    return false;
}

static void test_default_scene(void) {
    sl_scene s = {0};
    bool ok = sl_scene_load_default(&s, NULL, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    CHECK(strcmp(s.path, "<default>") == 0);
    /* issue 19: the default shows the bundled plugins together, needing no files */
    CHECK(has_plugin(&s, "ggx") && has_plugin(&s, "envmap") && has_plugin(&s, "spotlight-shadow") &&
          has_plugin(&s, "normal-map") && has_plugin(&s, "tonemap"));
    CHECK(s.environment.map == NULL); /* no environment given: envmap's procedural sky */
    int sun = sl_scene_find_light(&s, "sun"), spot = sl_scene_find_light(&s, "spot");
    CHECK(sun >= 0 && spot >= 0);
    if (sun >= 0) CHECK(!strcmp(s.lights[sun].type, "directional") && s.lights[sun].cast_shadows);
    if (spot >= 0) CHECK(!strcmp(s.lights[spot].type, "spot"));
    int floor = sl_scene_find_material(&s, "floor"), gold = sl_scene_find_material(&s, "gold");
    CHECK(floor >= 0 && gold >= 0);
    if (floor >= 0) {
        const sl_prop *nm = sl_prop_find(&s.materials[floor].props, "normal_map");
        CHECK(nm && nm->kind == SL_PROP_STRING && !strncmp(nm->str, "waves:", 6)); /* procedural, no file */
    }
    if (gold >= 0) {
        const sl_prop *m = sl_prop_find(&s.materials[gold].props, "metallic");
        CHECK(m && m->v[0] == 1.0f && !strcmp(s.materials[gold].model, "ggx"));
    }
    int ggx_spheres = 0;
    for (int i = 0; i < s.material_count; i++)
        if (!strcmp(s.materials[i].model, "ggx") && sl_prop_find(&s.materials[i].props, "roughness")) ggx_spheres++;
    CHECK(ggx_spheres >= 5); /* several roughnesses, a metal, the floor, the teapot */
    CHECK(sl_scene_find_node(&s, "teapot") >= 0);
    sl_scene_free(&s);
    CHECK(scene_is_zero(&s));
    sl_scene_free(&s); /* twice is harmless */

    /* the files on disk are the same scenes: default.json, and basic.json (the bare scene, also
     * compiled in as the harness's default) */
    CHECK(load_fixture(&s, SL_SOURCE_DIR "/scenes/default.json"));
    CHECK(s.plugin_count == 5 && s.dir && s.dir[0] == '/');
    sl_scene_free(&s);
    CHECK(load_fixture(&s, SL_SOURCE_DIR "/scenes/basic.json"));
    check_basic_scene(&s);
    sl_scene_free(&s);
    extern const char sl_basic_scene_json[];
    CHECK(load_text(&s, sl_basic_scene_json));
    check_basic_scene(&s);
    sl_scene_free(&s);
}

static void test_shipped_scenes(void) {
    const char *files[] = {"spheres.json", "teapot.json", "furnace.json"};
    for (int i = 0; i < 3; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/scenes/%s", SL_SOURCE_DIR, files[i]);
        sl_scene s;
        int warnings = sl_log_count(SL_LOG_WARN);
        bool ok = load_fixture(&s, path);
        CHECK_MSG(ok, "%s", err);
        CHECK_MSG(sl_log_count(SL_LOG_WARN) == warnings, "%s: unexpected warnings:\n%s", files[i], logbuf);
        CHECK(s.camera_count >= 1 && s.mesh_count >= 1);
        sl_scene_free(&s);
    }
    sl_scene s;
    if (load_fixture(&s, SL_SOURCE_DIR "/scenes/spheres.json")) {
        CHECK(s.mesh_count == 6 && s.light_count == 2 && s.material_count == 6);
        int grid = sl_scene_find_node(&s, "grid"), parent = sl_scene_find_node(&s, "spheres");
        CHECK(grid >= 0 && parent >= 0 && s.nodes[grid].parent == parent);
        sl_scene_free(&s);
    }
    if (load_fixture(&s, SL_SOURCE_DIR "/scenes/furnace.json")) {
        CHECK(s.light_count == 0 && s.environment.map == NULL);
        CHECK(s.environment.color[0] == 1 && s.environment.color[1] == 1 && s.environment.color[2] == 1);
        CHECK(s.environment.intensity == 1);
        for (int i = 0; i < s.mesh_count; i++) {
            const sl_prop *bc = sl_prop_find(&s.materials[s.meshes[i].material].props, "base_color");
            CHECK(bc && bc->count == 3 && bc->v[0] == 1 && bc->v[1] == 1 && bc->v[2] == 1);
        }
        sl_scene_free(&s);
    }
    if (load_fixture(&s, SL_SOURCE_DIR "/scenes/teapot.json")) {
        int t = sl_scene_find_node(&s, "teapot");
        CHECK(t >= 0 && s.nodes[t].mesh_count == 1);
        if (t >= 0) CHECK_NEAR(s.meshes[s.nodes[t].meshes[0]].data.bounds_max[1], 1.0, 1e-5);
        sl_scene_free(&s);
    }
}

/* Each bad fixture: load fails, the scene stays zeroed, and the message has every fragment. */
static void expect_error(const char *file, const char *const *fragments) {
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/%s", SL_TEST_DATA_DIR, file);
    sl_scene s;
    bool ok = load_fixture(&s, path);
    CHECK_MSG(!ok, "%s loaded but should not have", file);
    CHECK(scene_is_zero(&s));
    for (int i = 0; fragments[i]; i++) CHECK_CONTAINS(err, fragments[i]);
    if (ok) sl_scene_free(&s);
}

static void test_bad_fixtures(void) {
    expect_error("bad_syntax.json", (const char *[]){"bad_syntax.json:4:", "malformed JSON",
                                                    "trailing comma before '}'", "^", NULL});
    expect_error("bad_type.json", (const char *[]){"bad_type.json:4:7:", "camera 'main'",
                                                  "\"position\" must be an array of 3 numbers",
                                                  "found the string \"abc\"", NULL});
    expect_error("plugin_path.json", (const char *[]){"plugin_path.json:2:", "../../tmp/evil.so",
                                                     "never paths", NULL});
    expect_error("duplicate_material.json", (const char *[]){"duplicate_material.json:5:",
                                                             "duplicate material name 'red'",
                                                             "first defined at line 4", NULL});
    expect_error("unknown_material.json", (const char *[]){"unknown_material.json:5:",
                                                          "unknown material 'gren'",
                                                          "did you mean 'green'?", NULL});
    expect_error("unknown_parent.json", (const char *[]){"unknown_parent.json:4:", "unknown parent 'tabel'",
                                                        "did you mean 'table'?", NULL});
    expect_error("missing_mesh.json", (const char *[]){"missing_mesh.json:4:", "no_such_dir/no_such_mesh.glb",
                                                      "looked in", "scene directory",
                                                      "tests/data/scenes/no_such_dir/no_such_mesh.glb",
                                                      "No such file or directory", NULL});
    expect_error("bad_primitive.json", (const char *[]){"bad_primitive.json:4:", "unknown primitive 'sphree'",
                                                       "did you mean 'sphere'?", NULL});
    expect_error("negative_radius.json", (const char *[]){"negative_radius.json:5:", "node 'ball'",
                                                         "\"radius\" must be a number > 0, found -1", NULL});
    expect_error("empty.json", (const char *[]){"empty.json:1:1:", "empty", NULL});
    expect_error("array.json", (const char *[]){"array.json:1:1:", "top level must be a JSON object",
                                               "found an empty array", NULL});
    expect_error("nan.json", (const char *[]){"nan.json:3:", "NaN and Infinity", NULL});
    expect_error("huge.json", (const char *[]){"huge.json:4:", "light 'sun'", "\"intensity\" must be a finite number", NULL});

    sl_scene s;
    CHECK(!load_fixture(&s, FIXTURE("does_not_exist.json")));
    CHECK_CONTAINS(err, "does_not_exist.json: No such file or directory");
    CHECK(!load_fixture(&s, FIXTURE("")));
    CHECK_CONTAINS(err, "is a directory");
}

static void test_unknown_keys_warn(void) {
    sl_scene s;
    int before = sl_log_count(SL_LOG_WARN);
    bool ok = load_fixture(&s, FIXTURE("unknown_keys.json"));
    CHECK_MSG(ok, "%s", err);
    /* 4: the material key typo (line 5, "base_colour") is not the loader's to judge: only the loaded
     * plugins' schema knows material keys, so the application reports it (test_core_bad_input) */
    CHECK(sl_log_count(SL_LOG_WARN) - before == 4);
    CHECK_CONTAINS(logbuf, "unknown_keys.json:3:3: top level: unknown key \"camera\" ignored (did you mean 'cameras'?)");
    CHECK_CONTAINS(logbuf, "unknown_keys.json:4:");
    CHECK_CONTAINS(logbuf, "unknown key \"postion\" ignored (did you mean 'position'?)");
    CHECK_MSG(!strstr(logbuf, "base_colour"), "the scene loader judged a material key: %s", logbuf);
    CHECK_CONTAINS(logbuf, "unknown_keys.json:7:");
    CHECK_CONTAINS(logbuf, "did you mean 'translate'?");
    CHECK_CONTAINS(logbuf, "unknown_keys.json:8:");
    CHECK_CONTAINS(logbuf, "\"radus\" ignored (did you mean 'radius'?)");
    if (ok) {
        /* loading went on: defaults where the typos were */
        CHECK(s.camera_count == 1 && s.cameras[0].position[2] == 5.0f && s.cameras[0].fov_y_deg == 40);
        CHECK(s.mesh_count == 1 && s.meshes[0].data.bounds_max[1] == 1.0f); /* radius 1, not 2 */
        int grey = sl_scene_find_material(&s, "grey");
        CHECK(grey >= 0 && sl_prop_find(&s.materials[grey].props, "base_colour"));
        sl_scene_free(&s);
    }
}

static void test_inline_errors(void) {
    sl_scene s;
    struct { const char *text, *fragment; } cases[] = {
        {"{ \"nodes\": [ { \"name\": \"a\" } ] // comment\n}", "comments are not allowed"},
        {"{ 'nodes': [] }", "double quotes"},
        {"{ \"nodes\": [] \"lights\": [] }", "missing ','"},
        {"{ \"nodes\": [ { \"name\": \"a }", "unterminated string"},
        {"{ \"nodes\": [", "unexpected end of file"},
        {"{ \"a\": }", "missing value after ':'"},
        {"{ } { }", "after the end of the top-level object"},
        {"{ \"nodes\": [ { \"name\": tru } ] }", "inline.json:1:24:"},
        {"\x01\x02\x03", "unexpected byte 0x01"},
        {"{ \"a\": \x80 }", "unexpected byte 0x80"},
        {"{x: 1}", "unexpected 'x' (keys and strings must be quoted"},
        {"[1,x]", "inline.json:1:4:"},
        {"", "empty"},
        {"   \n\t  ", "empty"},
        {"null", "top level must be a JSON object"},
        {"\"text\"", "found the string \"text\""},
        {"{ \"plugins\": [\"a.so\"] }", "never paths"},
        {"{ \"plugins\": [\"/usr/lib/x\"] }", "never paths"},
        {"{ \"plugins\": [\"C:evil\"] }", "never paths"},
        {"{ \"plugins\": [\"good name\"] }", "not a plugin name"},
        {"{ \"plugins\": \"ggx\" }", "\"plugins\" must be an array"},
        {"{ \"params\": { \"nodot\": 1 } }", "must be a parameter id"},
        {"{ \"params\": { \"a.b\": {} } }", "array of 2 to 4 finite numbers, found an object"},
        {"{ \"params\": { \"a.b\": [1, 2, 3, 4, 5] } }", "found an array of 5 numbers"},
        {"{ \"materials\": [ { \"model\": \"ggx\" } ] }", "material #0 has no \"name\""},
        {"{ \"materials\": [ { \"name\": \"\" } ] }", "\"name\" must be a non-empty string"},
        {"{ \"materials\": [ { \"name\": 7 } ] }", "found the number 7"},
        {"{ \"materials\": [ { \"name\": \"m\", \"cast_shadows\": \"yes\" } ] }", "must be true or false"},
        {"{ \"materials\": [ 3 ] }", "material #0 must be an object"},
        {"{ \"cameras\": [ { \"far\": 0.01 } ] }", "\"far\" (0.01) must be greater than \"near\" (0.05)"},
        {"{ \"cameras\": [ { \"fov_y\": 180 } ] }", "\"fov_y\" must be a number in (0, 179]"},
        {"{ \"cameras\": [ { \"position\": [0, 5, 0], \"target\": [0, 0, 0] } ] }", "parallel"},
        {"{ \"cameras\": [ { \"position\": [1, 1, 1], \"target\": [1, 1, 1] } ] }", "same point"},
        {"{ \"cameras\": [ { \"up\": [0, 0, 0] } ] }", "non-zero vector"},
        {"{ \"cameras\": [ { \"name\": \"a\" }, { \"name\": \"a\" } ] }", "duplicate camera name 'a' (first defined at line 1)"},
        {"{ \"lights\": [ { \"name\": \"l\" } ] }", "has no \"type\""},
        {"{ \"lights\": [ { \"type\": \"point\", \"color\": [1, -1, 1] } ] }", "must not be negative"},
        {"{ \"lights\": [ { \"type\": \"point\", \"intensity\": -2 } ] }", "\"intensity\" must be a number ≥ 0"},
        {"{ \"lights\": [ { \"type\": \"spot\", \"direction\": [0, 0, 0] } ] }", "non-zero vector"},
        {"{ \"lights\": [ { \"name\": \"x\", \"type\": \"point\" }, { \"name\": \"x\", \"type\": \"point\" } ] }", "duplicate light name 'x'"},
        {"{ \"lights\": [ { \"type\": \"spot\", \"cone_angle\": null } ] }", "\"cone_angle\" must be a number, true/false"},
        {"{ \"nodes\": [ { \"name\": \"a\" }, { \"name\": \"a\" } ] }", "duplicate node name 'a' (first defined at line 1)"},
        {"{ \"nodes\": [ { \"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], \"translate\": [1,2,3] } ] }", "either \"matrix\" or"},
        {"{ \"nodes\": [ { \"matrix\": [1, 0, 0] } ] }", "\"matrix\" must be an array of 16 numbers"},
        {"{ \"nodes\": [ { \"scale\": 0 } ] }", "\"scale\" must not be zero in more than one axis"},
        {"{ \"nodes\": [ { \"scale\": [1, 0, 0] } ] }", "collapse to a line or a point"},
        {"{ \"nodes\": [ { \"matrix\": [0,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,0,1] } ] }", "collapses the node to a line or a point"},
        {"{ \"nodes\": [ { \"matrix\": [1,0,0,0, 2,0,0,0, 0,0,0,0, 0,0,0,1] } ] }", "rank < 2"},
        {"{ \"nodes\": [ { \"translate\": [1e38, 0, 0] } ] }", "beyond 1e+07"},
        {"{ \"nodes\": [ { \"scale\": [1, 1e30, 1] } ] }", "beyond 1e+07"},
        {"{ \"nodes\": [ { \"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, -3e38,0,0,1] } ] }", "element 12"},
        {"{ \"nodes\": [ { \"translate\": [9e6, 0, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 5e6} } ] }", "reaches 1.4e+07 from the origin"},
        {"{ \"nodes\": [ { \"scale\": \"big\" } ] }", "\"scale\" must be a number or an array of 3 numbers"},
        {"{ \"nodes\": [ { \"rotate\": [0, 0, 0, 0] } ] }", "quaternion [x, y, z, w] must not be zero"},
        {"{ \"nodes\": [ { \"rotate\": [90, 0] } ] }", "Euler angles in degrees"},
        {"{ \"nodes\": [ { \"translate\": [1, 2, \"3\"] } ] }", "an array of 3 values, not all numbers"},
        {"{ \"nodes\": [ { \"mesh\": {} } ] }", "needs \"primitive\""},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"cube\", \"file\": \"x.glb\" } } ] }", "not both"},
        {"{ \"nodes\": [ { \"mesh\": \"sphere\" } ] }", "\"mesh\" must be an object"},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": 3 } } ] }", "\"primitive\" must be a non-empty string"},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"sphere\", \"segments\": 2.5 } } ] }", "\"segments\" must be an integer in [3, 2048]"},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"sphere\", \"segments\": 1e9 } } ] }", "found 1e+09"},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"sphere\", \"radius\": \"NaN\" } } ] }", "found the string \"NaN\""},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"sphere\", \"radius\": 1e300 } } ] }", "must be a finite number"},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"torus\", \"major_radius\": 1, \"minor_radius\": 2 } } ] }", "must be smaller than"},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"plane\", \"size\": [1, -1] } } ] }", "two numbers > 0"},
        {"{ \"nodes\": [ { \"mesh\": { \"primitive\": \"teapot\", \"tessellation\": 0 } } ] }", "\"tessellation\" must be an integer in [1, 128]"},
        {"{ \"nodes\": [ { \"name\": \"a\", \"children\": [ { \"name\": \"b\", \"parent\": \"a\" } ] } ] }", "use one of the two"},
        {"{ \"nodes\": [ { \"children\": {} } ] }", "\"children\" must be an array"},
        {"{ \"nodes\": [ { \"name\": \"bad\\u0001name\" } ] }", "control characters"},
        {"{ \"environment\": { \"map\": \"no/such/sky.exr\" } }", "environment map: 'no/such/sky.exr' not found"},
        {"{ \"environment\": { \"intensity\": -1 } }", "\"intensity\" must be a number ≥ 0"},
        {"{ \"environment\": [] }", "\"environment\" must be an object"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        bool ok = load_text(&s, cases[i].text);
        CHECK_MSG(!ok, "case %zu loaded: %s", i, cases[i].text);
        CHECK_MSG(strstr(err, cases[i].fragment) && strncmp(err, "inline.json:", 12) == 0,
                  "case %zu (%s): expected \"%s\" in: %s", i, cases[i].text, cases[i].fragment, err);
        CHECK(scene_is_zero(&s));
        if (ok) sl_scene_free(&s);
    }
    /* an error message always fits the buffer and is NUL-terminated */
    char tiny[16];
    memset(tiny, 'x', sizeof tiny);
    CHECK(!sl_scene_load_text(&s, "{ \"nodes\": 3 }", "a-long-file-name.json", NULL, NULL, tiny, sizeof tiny));
    CHECK(memchr(tiny, 0, sizeof tiny) != NULL);
    CHECK(!sl_scene_load_text(&s, "{", "x", NULL, NULL, NULL, 0)); /* no buffer at all */
    CHECK(!sl_scene_load_text(&s, NULL, "x", NULL, NULL, err, sizeof err));
    /* a NUL byte inside a file */
    char path[1024];
    snprintf(path, sizeof path, "%s/scene_test_nul.json", sl_test_dir());
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (f) {
        fwrite("{\n  \"nodes\": [] \0 }", 1, 20, f);
        fclose(f);
        CHECK(!load_fixture(&s, path));
        CHECK_CONTAINS(err, "scene_test_nul.json:2:15: malformed JSON: unexpected byte 0x00");
        remove(path);
    }
}

static void test_nesting_limits(void) {
    sl_scene s;
    /* "children" nested 100 levels: refused with a clear message, no stack overflow */
    size_t cap = 100 * 64 + 64;
    char *text = malloc(cap);
    strcpy(text, "{ \"nodes\": [");
    for (int i = 0; i < 100; i++) {
        char part[64];
        snprintf(part, sizeof part, "{ \"name\": \"n%d\", \"children\": [", i);
        strcat(text, part);
    }
    for (int i = 0; i < 100; i++) strcat(text, "] }");
    strcat(text, "] }");
    CHECK(!load_text(&s, text));
    CHECK_CONTAINS(err, "nested deeper than 64 levels");
    free(text);

    /* exactly at the limit loads */
    text = malloc(cap);
    strcpy(text, "{ \"nodes\": [");
    for (int i = 0; i <= SL_SCENE_MAX_DEPTH; i++) {
        char part[64];
        snprintf(part, sizeof part, "{ \"name\": \"n%d\", \"children\": [", i);
        strcat(text, part);
    }
    for (int i = 0; i <= SL_SCENE_MAX_DEPTH; i++) strcat(text, "] }");
    strcat(text, "] }");
    CHECK_MSG(load_text(&s, text), "%s", err);
    CHECK(s.node_count == SL_SCENE_MAX_DEPTH + 1 && s.nodes[s.node_count - 1].parent == s.node_count - 2);
    sl_scene_free(&s);
    free(text);

    /* "parent" chains are limited the same way */
    size_t cap2 = 80 * 80 + 64;
    text = malloc(cap2);
    strcpy(text, "{ \"nodes\": [ { \"name\": \"p0\" }");
    for (int i = 1; i < 80; i++) {
        char part[80];
        snprintf(part, sizeof part, ", { \"name\": \"p%d\", \"parent\": \"p%d\" }", i, i - 1);
        strcat(text, part);
    }
    strcat(text, "] }");
    CHECK(!load_text(&s, text));
    CHECK_CONTAINS(err, "nested deeper than 64 levels");
    free(text);

    /* counts: too many entries or keys is refused before any quadratic work */
    text = malloc(20001 * 3 + 64);
    strcpy(text, "{ \"lights\": [");
    char *w = text + strlen(text);
    for (int i = 0; i < 20001; i++) w += sprintf(w, "%s{}", i ? "," : "");
    strcpy(w, "] }");
    CHECK(!load_text(&s, text));
    CHECK_CONTAINS(err, "\"lights\" has 20001 entries; at most 20000 are allowed");
    free(text);
    text = malloc(1100 * 16 + 64);
    strcpy(text, "{ \"materials\": [ { \"name\": \"m\"");
    w = text + strlen(text);
    for (int i = 0; i < 1100; i++) w += sprintf(w, ", \"k%d\": 1", i);
    strcpy(w, " } ] }");
    CHECK(!load_text(&s, text));
    CHECK_CONTAINS(err, "material 'm' has 1101 keys; at most 1024 are allowed");
    free(text);

    /* JSON nesting beyond cJSON's limit */
    text = malloc(5000);
    strcpy(text, "{ \"x\": ");
    for (int i = 0; i < 2000; i++) strcat(text, "[");
    CHECK(!load_text(&s, text));
    CHECK_CONTAINS(err, "nested deeper than");
    free(text);
}

static void test_transforms(void) {
    sl_scene s;
    const char *text =
        "{ \"nodes\": [\n"
        "  { \"name\": \"root\", \"translate\": [1, 2, 3], \"rotate\": [0, 90, 0], \"scale\": 2,\n"
        "    \"children\": [ { \"name\": \"kid\", \"translate\": [1, 0, 0],\n"
        "                    \"mesh\": { \"primitive\": \"cube\", \"size\": 1 } } ] },\n"
        "  { \"name\": \"adopted\", \"parent\": \"kid\", \"rotate\": [0, 0, 0.70710678, 0.70710678] },\n"
        "  { \"name\": \"m\", \"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,6,7,1] },\n"
        "  { \"name\": \"zyx\", \"rotate\": [90, 90, 0] }\n"
        "] }";
    bool ok = load_text(&s, text);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    /* kid at local (1,0,0): scaled ×2, rotated 90° about Y (+X → −Z), moved by (1,2,3) */
    const float *kid = node_world(&s, "kid");
    CHECK_NEAR(kid[12], 1, 1e-5);
    CHECK_NEAR(kid[13], 2, 1e-5);
    CHECK_NEAR(kid[14], 3 - 2, 1e-5);
    /* the cube (size 1) ends up 2 wide around (1, 2, 1) */
    CHECK_NEAR(s.bounds_min[0], 0, 1e-5);
    CHECK_NEAR(s.bounds_max[1], 3, 1e-5);
    CHECK_NEAR(s.bounds_max[2], 2, 1e-5);
    int adopted = sl_scene_find_node(&s, "adopted");
    CHECK(adopted >= 0 && s.nodes[adopted].parent == sl_scene_find_node(&s, "kid"));
    /* quaternion 90° about Z: local +X → +Y */
    const float *a = s.nodes[adopted].local;
    CHECK_NEAR(a[0], 0, 1e-6);
    CHECK_NEAR(a[1], 1, 1e-6);
    const float *m = node_world(&s, "m");
    CHECK(m[12] == 5 && m[13] == 6 && m[14] == 7);
    /* Euler [90, 90, 0]: X first (+Y → +Z), then Y (+Z → +X): R·(0,1,0) = (1,0,0) */
    const float *z = s.nodes[sl_scene_find_node(&s, "zyx")].local;
    CHECK_NEAR(z[4], 1, 1e-6);
    CHECK_NEAR(z[5], 0, 1e-6);
    CHECK_NEAR(z[6], 0, 1e-6);
    sl_scene_free(&s);
}

static void test_defaults_and_props(void) {
    sl_scene s;
    const char *text =
        "{ \"comment\": \"x\", \"plugins\": [\"ggx\", \"normal-map\", \"ggx\"],\n"
        "  \"params\": { \"ggx.samples\": 64, \"tonemap.enabled\": false, \"material.skin.tint\": [1, 0.5, 0.25] },\n"
        "  \"materials\": [ { \"name\": \"skin\", \"model\": \"ggx\", \"cast_shadows\": false, \"roughness\": 0.4,\n"
        "                   \"base_color_map\": \"textures/skin.png\", \"uv_scale\": [2, 2], \"two_sided\": true } ],\n"
        "  \"lights\": [ { \"type\": \"spot\", \"position\": [0, 3, 0], \"direction\": [0, -2, 0], \"cone_angle\": 30,\n"
        "                \"falloff\": \"smooth\", \"enabled\": false, \"cast_shadows\": true } ],\n"
        "  \"environment\": { \"map\": \"constant:0.5,0.5,0.5\", \"yaw\": 90, \"mip_bias\": 1 },\n"
        "  \"nodes\": [ { \"mesh\": { \"primitive\": \"teapot\", \"tessellation\": 2 } } ]\n"
        "}";
    bool ok = load_text(&s, text);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    CHECK(s.plugin_count == 2 && strcmp(s.plugins[1], "normal-map") == 0);
    CHECK_CONTAINS(logbuf, "'ggx' is listed twice");
    const sl_prop *p = sl_prop_find(&s.params, "ggx.samples");
    CHECK(p && p->kind == SL_PROP_NUMBER && p->v[0] == 64 && p->line == 2);
    p = sl_prop_find(&s.params, "tonemap.enabled");
    CHECK(p && p->kind == SL_PROP_BOOL && p->v[0] == 0);
    p = sl_prop_find(&s.params, "material.skin.tint");
    CHECK(p && p->kind == SL_PROP_VEC && p->count == 3 && p->v[2] == 0.25f);
    const sl_material *m = &s.materials[sl_scene_find_material(&s, "skin")];
    CHECK(strcmp(m->model, "ggx") == 0 && !m->cast_shadows && m->props.count == 4 && m->line == 3);
    p = sl_prop_find(&m->props, "base_color_map");
    CHECK(p && strcmp(p->str, "textures/skin.png") == 0 && p->line == 4); /* kept as written */
    p = sl_prop_find(&m->props, "uv_scale");
    CHECK(p && p->kind == SL_PROP_VEC && p->count == 2);
    CHECK(s.light_count == 1 && strcmp(s.lights[0].name, "light0") == 0 && strcmp(s.lights[0].type, "spot") == 0);
    CHECK(!s.lights[0].enabled && s.lights[0].cast_shadows && s.lights[0].direction[1] == -1.0f);
    CHECK(s.lights[0].color[0] == 1 && s.lights[0].intensity == 1);
    p = sl_prop_find(&s.lights[0].props, "falloff");
    CHECK(p && p->kind == SL_PROP_STRING && strcmp(p->str, "smooth") == 0 && p->line == 6);
    CHECK(sl_prop_find(&s.lights[0].props, "cone_angle") && !sl_prop_find(&s.lights[0].props, "enabled"));
    CHECK(s.environment.map && strcmp(s.environment.map, "constant:0.5,0.5,0.5") == 0);
    CHECK(s.environment.yaw_deg == 90 && s.environment.intensity == 1 && sl_prop_find(&s.environment.props, "mip_bias"));
    /* a node without a material gets the built-in "default" one */
    CHECK(s.mesh_count == 1 && strcmp(s.materials[s.meshes[0].material].name, "default") == 0);
    CHECK(strcmp(s.nodes[0].name, "node0") == 0);
    sl_scene_free(&s);

    /* a UTF-8 byte order mark is fine; the environment defaults to black, intensity 1 */
    CHECK(load_text(&s, "\xEF\xBB\xBF{ }"));
    CHECK(s.environment.color[0] == 0 && s.environment.intensity == 1 && s.environment.map == NULL);
    sl_scene_free(&s);
}

static void test_failure_keeps_scene(void) {
    sl_scene s = {0};
    CHECK(sl_scene_load_default(&s, NULL, err, sizeof err));
    int nodes = s.node_count;
    CHECK(!sl_scene_load_text(&s, "{ \"nodes\": [ { \"mesh\": 1 } ] }", "bad.json", NULL, NULL, err, sizeof err));
    CHECK(s.node_count == nodes && s.nodes != NULL && strcmp(s.path, "<default>") == 0);
    sl_scene_free(&s);
}

/* Deterministic mutation fuzzing and every truncation of the default scene: no crash, no leak
 * (under ASan), and a failed load always explains itself. */
static uint32_t rng_state = 12345;
static uint32_t rng(void) {
    rng_state = rng_state * 1664525u + 1013904223u;
    return rng_state >> 8;
}

static void test_fuzz(void) {
    extern const char sl_default_scene_json[];
    size_t len = strlen(sl_default_scene_json);
    char *buf = malloc(len + 64);
    sl_scene s;
    int failures_without_message = 0, loaded = 0, wrong = 0;
    size_t last_brace = strrchr(sl_default_scene_json, '}') - sl_default_scene_json;
    for (size_t cut = 0; cut < len; cut++) {
        memcpy(buf, sl_default_scene_json, cut);
        buf[cut] = 0;
        bool ok = load_text(&s, buf);
        if (ok) sl_scene_free(&s), loaded++;
        else failures_without_message += err[0] == 0;
        wrong += ok != (cut > last_brace); /* only the trailing whitespace may go */
    }
    CHECK(wrong == 0);
    static const char tokens[] = "{}[],:\"0123456789-+.eE \n\\tfnu/'";
    for (int iter = 0; iter < 3000; iter++) {
        memcpy(buf, sl_default_scene_json, len + 1);
        size_t n = len;
        int edits = 1 + (int)(rng() % 4);
        for (int e = 0; e < edits; e++) {
            size_t at = rng() % n;
            switch (rng() % 3) {
            case 0: buf[at] = tokens[rng() % (sizeof tokens - 1)]; break;
            case 1: memmove(buf + at, buf + at + 1, n - at); n--; break; /* delete */
            default:
                if (n + 1 < len + 63) {
                    memmove(buf + at + 1, buf + at, n - at + 1);
                    buf[at] = tokens[rng() % (sizeof tokens - 1)];
                    n++;
                }
            }
        }
        bool ok = load_text(&s, buf);
        if (ok) {
            for (int i = 0; i < s.mesh_count; i++) CHECK(s.meshes[i].material >= 0 && s.meshes[i].material < s.material_count);
            sl_scene_free(&s);
            loaded++;
        } else {
            failures_without_message += err[0] == 0;
        }
    }
    CHECK(failures_without_message == 0);
    printf("fuzz: %d of %zu mutated/truncated scenes loaded, the rest were refused with a message\n",
           loaded, len + 3000);
    free(buf);
}

int main(void) {
    sl_log_threshold = SL_LOG_ERROR + 1; /* the tests read the captured log instead */
    test_default_scene();
    test_shipped_scenes();
    test_bad_fixtures();
    test_unknown_keys_warn();
    test_inline_errors();
    test_nesting_limits();
    test_transforms();
    test_defaults_and_props();
    test_failure_keeps_scene();
    test_fuzz();
    return check_result();
}
