/* Mesh files through assimp (core/scene/scene_assimp.c), with the small self-made fixtures in
 * tests/data/scenes/: an OBJ quad with an MTL material, and a glTF with two quads (one with
 * mirrored UVs), KHR_lights_punctual lights (directional, spot, point) and a camera. The
 * Lee Perry-Smith head from ../shared/assets is used when present, else that part is skipped. */
#include "check.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FIXTURE(name) SL_TEST_DATA_DIR "/scenes/" name

static char err[4096];
static char logbuf[65536];

static bool ends_with(const char *s, const char *tail) {
    size_t a = strlen(s), b = strlen(tail);
    return a >= b && strcmp(s + a - b, tail) == 0;
}

static const sl_mesh *mesh_named(const sl_scene *s, const char *name) {
    for (int i = 0; i < s->mesh_count; i++)
        if (strcmp(s->meshes[i].name, name) == 0) return &s->meshes[i];
    return NULL;
}

static int frames_bad(const sl_mesh_data *m) {
    int bad = 0;
    for (int i = 0; i < m->vertex_count; i++) {
        const float *n = m->normals + 3 * i, *t = m->tangents + 4 * i;
        double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), lt = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        double d = n[0] * t[0] + n[1] * t[1] + n[2] * t[2];
        bad += !(fabs(ln - 1) < 1e-4 && fabs(lt - 1) < 1e-4 && fabs(d) < 1e-3 && (t[3] == 1 || t[3] == -1));
    }
    return bad;
}

static void test_obj(void) {
    sl_scene s = {0};
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_scene_import_file(&s, FIXTURE("quad.obj"), -1, err, sizeof err);
    sl_log_capture(NULL, 0);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    CHECK(s.mesh_count == 1);
    const sl_mesh_data *d = &s.meshes[0].data;
    CHECK(d->vertex_count == 4 && d->index_count == 6);
    CHECK(frames_bad(d) == 0);
    /* OBJ's v = 0 is the bottom: the top-left corner (−1, 1) must get uv (0, 0) here */
    for (int i = 0; i < d->vertex_count; i++) {
        const float *p = d->positions + 3 * i, *uv = d->uvs + 2 * i;
        CHECK_NEAR(uv[0], (p[0] + 1) / 2, 1e-6);
        CHECK_NEAR(uv[1], (1 - p[1]) / 2, 1e-6);
        CHECK_NEAR(d->tangents[4 * i], 1, 1e-5);
        CHECK(d->tangents[4 * i + 3] == 1);
    }
    const sl_material *m = &s.materials[s.meshes[0].material];
    CHECK(strcmp(m->name, "quad/tile") == 0 && strcmp(m->model, "lambert") == 0);
    CHECK(s.material_count == 1); /* unused assimp defaults are not imported */
    /* imported materials publish standard inputs (glTF names), never a plugin's keys */
    CHECK(m->props.count == 0 && m->source && ends_with(m->source, "quad.obj"));
    CHECK(!sl_prop_find(&m->inputs, "brdf")); /* plain diffuse OBJ: no metallic-roughness, no ggx */
    const sl_prop *bc = sl_prop_find(&m->inputs, "base_color");
    CHECK(bc && bc->count == 3 && fabsf(bc->v[0] - 0.2f) < 1e-6f && fabsf(bc->v[2] - 0.6f) < 1e-6f);
    const sl_prop *map = sl_prop_find(&m->inputs, "base_color_texture");
    CHECK(map && map->str[0] == '/' && ends_with(map->str, "/tests/data/scenes/tile.png"));
    CHECK_CONTAINS(logbuf, "tile.png' not found"); /* referenced but absent: said so */
    sl_scene_free(&s);
}

static void test_gltf(void) {
    sl_scene s = {0};
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_scene_import_file(&s, FIXTURE("quads.gltf"), -1, err, sizeof err);
    sl_log_capture(NULL, 0);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    CHECK(s.mesh_count == 2 && s.light_count == 3 && s.camera_count == 1 && s.material_count == 1);
    const sl_mesh *up = mesh_named(&s, "quads/upright"), *mirror = mesh_named(&s, "quads/mirror");
    CHECK(up && mirror);
    if (up && mirror) {
        CHECK(frames_bad(&up->data) == 0 && frames_bad(&mirror->data) == 0);
        for (int i = 0; i < 4; i++) {
            const float *p = up->data.positions + 3 * i, *uv = up->data.uvs + 2 * i;
            /* glTF UVs arrive as written in the file (origin top left) */
            CHECK_NEAR(uv[0], (p[0] + 1) / 2, 1e-6);
            CHECK_NEAR(uv[1], (1 - p[1]) / 2, 1e-6);
            CHECK_NEAR(up->data.tangents[4 * i], 1, 1e-5);
            CHECK(up->data.tangents[4 * i + 3] == 1);
            CHECK_NEAR(mirror->data.tangents[4 * i], -1, 1e-5);
            CHECK(mirror->data.tangents[4 * i + 3] == -1);
        }
        /* assimp's tangents agree with ours on the same data */
        sl_mesh_data copy = up->data;
        float saved[16];
        memcpy(saved, copy.tangents, sizeof saved);
        sl_mesh_generate_tangents(&copy);
        for (int i = 0; i < 16; i++) CHECK_NEAR(copy.tangents[i], saved[i], 1e-5);
    }
    const sl_material *m = &s.materials[0];
    CHECK(strcmp(m->name, "quads/paint") == 0);
    CHECK(m->props.count == 0);
    const sl_prop *p = sl_prop_find(&m->inputs, "base_color");
    CHECK(p && p->count == 3 && p->v[0] == 0.5f && p->v[1] == 0.25f && p->v[2] == 1.0f);
    p = sl_prop_find(&m->inputs, "brdf");
    CHECK(p && p->kind == SL_PROP_STRING && strcmp(p->str, "metallic-roughness") == 0);
    p = sl_prop_find(&m->inputs, "metallic");
    CHECK(p && fabsf(p->v[0] - 0.2f) < 1e-6f);
    p = sl_prop_find(&m->inputs, "roughness");
    CHECK(p && fabsf(p->v[0] - 0.7f) < 1e-6f);
    p = sl_prop_find(&m->inputs, "base_color_texture");
    CHECK(p && ends_with(p->str, "/tests/data/scenes/albedo.png") && p->str[0] == '/');
    p = sl_prop_find(&m->inputs, "normal_texture");
    CHECK(p && ends_with(p->str, "/tests/data/scenes/normal.png"));

    int sun = sl_scene_find_light(&s, "quads/sun"), spot = sl_scene_find_light(&s, "quads/spot"),
        bulb = sl_scene_find_light(&s, "quads/bulb");
    CHECK(sun >= 0 && spot >= 0 && bulb >= 0);
    if (sun >= 0 && spot >= 0 && bulb >= 0) {
        const sl_light *l = &s.lights[sun];
        CHECK(strcmp(l->type, "directional") == 0 && l->intensity == 3 && l->direction[2] == -1);
        l = &s.lights[spot];
        CHECK(strcmp(l->type, "spot") == 0);
        CHECK_NEAR(l->intensity, 20, 1e-5);
        CHECK_NEAR(l->color[1], 0.5, 1e-6);
        CHECK_NEAR(l->position[1], 2, 1e-6);
        CHECK_NEAR(l->direction[1], -1, 1e-6); /* the node turns −Z to −Y */
        const sl_prop *cone = sl_prop_find(&l->props, "cone_angle"), *inner = sl_prop_find(&l->props, "inner_cone_angle");
        CHECK(cone && inner);
        if (cone && inner) {
            CHECK_NEAR(cone->v[0], 0.5 * 180 / M_PI, 1e-4); /* half-angles, in degrees */
            CHECK_NEAR(inner->v[0], 0.25 * 180 / M_PI, 1e-4);
        }
        const sl_prop *falloff = sl_prop_find(&l->props, "falloff");
        CHECK(falloff && strcmp(falloff->str, "gltf") == 0);
        l = &s.lights[bulb];
        CHECK(strcmp(l->type, "point") == 0 && l->intensity == 5);
        CHECK(l->position[0] == 1 && l->position[1] == 1 && l->position[2] == 1);
    }
    const sl_camera *c = &s.cameras[0];
    CHECK(strcmp(c->name, "quads/cam") == 0);
    CHECK_NEAR(c->position[2], 5, 1e-6);
    CHECK_NEAR(c->target[2] - c->position[2], -1, 1e-6);
    CHECK_NEAR(c->fov_y_deg, 0.8 * 180 / M_PI, 1e-3);
    CHECK_NEAR(c->znear, 0.1, 1e-7);
    CHECK_NEAR(c->zfar, 50, 1e-5);
    /* hierarchy: ROOT with six children; "mirrored" is moved by +3 in x */
    int mirrored = sl_scene_find_node(&s, "quads/mirrored");
    CHECK(mirrored >= 0 && s.nodes[mirrored].parent == 0 && s.nodes[mirrored].world[12] == 3);
    sl_scene_free(&s);
}

static void test_through_json(void) {
    sl_scene s = {0};
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_scene_load_file(&s, FIXTURE("import_quads.json"), NULL, err, sizeof err);
    sl_log_capture(NULL, 0);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    CHECK(s.mesh_count == 4 && s.light_count == 6 && s.camera_count == 2);
    /* the imported hierarchy hangs under the JSON node, named after it */
    int quads = sl_scene_find_node(&s, "quads"), root = sl_scene_find_node(&s, "quads/ROOT");
    CHECK(quads >= 0 && root >= 0 && s.nodes[root].parent == quads);
    int m2 = sl_scene_find_node(&s, "red_quads/mirrored");
    CHECK(m2 >= 0);
    if (m2 >= 0) { /* holder (0,0,−2) · red_quads (0,10,0) · mirrored (3,0,0) */
        CHECK(s.nodes[m2].world[12] == 3 && s.nodes[m2].world[13] == 10 && s.nodes[m2].world[14] == -2);
    }
    /* lights and cameras follow their node */
    int spot = sl_scene_find_light(&s, "red_quads/spot"), cam = sl_scene_find_camera(&s, "quads/cam");
    CHECK(spot >= 0 && cam >= 0);
    if (spot >= 0) CHECK_NEAR(s.lights[spot].position[1], 12, 1e-5);
    if (cam >= 0) CHECK_NEAR(s.cameras[cam].position[2], 3, 1e-5);
    /* materials: one shared "quads/paint" with the mesh key's model; the override on red_quads */
    int paint = sl_scene_find_material(&s, "quads/paint"), over = sl_scene_find_material(&s, "override");
    CHECK(paint >= 0 && over >= 0 && s.material_count == 2);
    if (paint >= 0) CHECK(strcmp(s.materials[paint].model, "ggx") == 0);
    int overridden = 0, painted = 0;
    for (int i = 0; i < s.mesh_count; i++) {
        overridden += s.meshes[i].material == over;
        painted += s.meshes[i].material == paint;
    }
    CHECK(overridden == 2 && painted == 2);
    sl_scene_free(&s);

    ok = sl_scene_load_file(&s, FIXTURE("import_obj.json"), NULL, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    if (ok) {
        CHECK(s.mesh_count == 1 && s.meshes[0].data.vertex_count == 4);
        sl_scene_free(&s);
    }
}

static void test_bad_files(void) {
    /* a corrupt glTF gets the glTF reader's reason, a corrupt file of another format assimp's;
     * both named with the path */
    char path[1024], ply[1024];
    snprintf(path, sizeof path, "%s/scene_test_corrupt.glb", sl_test_dir());
    snprintf(ply, sizeof ply, "%s/scene_test_corrupt.ply", sl_test_dir());
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (f) {
        fputs("glTF this is not a binary glTF file at all", f);
        fclose(f);
    }
    f = fopen(ply, "wb");
    CHECK(f != NULL);
    if (f) {
        fputs("ply\nformat nonsense 9.9\nend_header\n", f);
        fclose(f);
    }
    sl_scene s = {0};
    CHECK(!sl_scene_import_file(&s, path, -1, err, sizeof err));
    CHECK_CONTAINS(err, "scene_test_corrupt.glb: GLB container version ");
    CHECK(s.mesh_count == 0);
    sl_scene_free(&s);
    CHECK(!sl_scene_import_file(&s, ply, -1, err, sizeof err));
    CHECK_CONTAINS(err, "scene_test_corrupt.ply: assimp could not import it: ");
    sl_scene_free(&s);

    /* the same through a scene file: error names the scene file, line and node */
    char scene_text[2048];
    snprintf(scene_text, sizeof scene_text,
             "{ \"nodes\": [\n  { \"name\": \"broken\", \"mesh\": { \"file\": \"%s\" } } ] }", ply);
    CHECK(!sl_scene_load_text(&s, scene_text, "corrupt.json", NULL, NULL, err, sizeof err));
    CHECK_CONTAINS(err, "corrupt.json:2:");
    CHECK_CONTAINS(err, "mesh of node 'broken'");
    CHECK_CONTAINS(err, "assimp could not import it");
    unlink(path);
    unlink(ply);

    /* a missing file: every place looked in, with the reason */
    CHECK(!sl_scene_load_text(&s, "{ \"nodes\": [ { \"mesh\": { \"file\": \"nowhere/x.glb\" } } ] }",
                              "missing.json", SL_TEST_DATA_DIR, &(sl_scene_load_opts){.data_dir = sl_test_dir()},
                              err, sizeof err));
    CHECK_CONTAINS(err, "'nowhere/x.glb' not found; looked in: scene directory " SL_TEST_DATA_DIR "/nowhere/x.glb (No such file or directory)");
    char expect[1200];
    snprintf(expect, sizeof expect, "data directory %s/nowhere/x.glb (No such file or directory)", sl_test_dir());
    CHECK_CONTAINS(err, expect);

    /* a scene whose files are generated names the command that writes them */
    CHECK(!sl_scene_load_text(&s, "{ \"nodes\": [ { \"mesh\": { \"file\": \"gen/x.obj\" } } ],\n"
                                  "  \"generated_by\": \"make-x gen\" }",
                              "generated.json", SL_TEST_DATA_DIR, NULL, err, sizeof err));
    CHECK_CONTAINS(err, "'gen/x.obj' not found; looked in: scene directory ");
    CHECK_CONTAINS(err, "This scene's files are generated: run make-x gen");
    CHECK(!strstr(err, "--data"));
    CHECK(!sl_scene_load_text(&s, "{ \"generated_by\": 3 }", "generated.json", SL_TEST_DATA_DIR, NULL, err, sizeof err));
    CHECK_CONTAINS(err, "generated.json:1:");
    CHECK_CONTAINS(err, "\"generated_by\" must be the command");
    sl_scene_free(&s);

    /* a directory is not a mesh */
    CHECK(!sl_scene_load_text(&s, "{ \"nodes\": [ { \"mesh\": { \"file\": \"scenes\" } } ] }",
                              "dir.json", SL_TEST_DATA_DIR, NULL, err, sizeof err));
    CHECK_CONTAINS(err, "is a directory");
}

/* The head scan from the shared assets, when this machine has it (not on CI). */
static void test_head(void) {
    const char *data = getenv("SHADELAB_DATA");
    char probe[1024];
    snprintf(probe, sizeof probe, "%s/head/LeePerrySmith.glb", data ? data : "");
    if (!data || access(probe, R_OK) != 0) {
        printf("head: SKIPPED (no head/LeePerrySmith.glb under SHADELAB_DATA=%s)\n", data ? data : "(unset)");
        return;
    }
    sl_scene s = {0};
    bool ok = sl_scene_load_text(&s, "{ \"nodes\": [ { \"name\": \"head\", \"mesh\": { \"file\": \"head/LeePerrySmith.glb\" } } ] }",
                                 "head.json", NULL, NULL, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    int verts = 0, tris = 0;
    for (int i = 0; i < s.mesh_count; i++) {
        verts += s.meshes[i].data.vertex_count;
        tris += s.meshes[i].data.index_count / 3;
        CHECK(frames_bad(&s.meshes[i].data) == 0);
    }
    CHECK(verts == 9279 && tris == 17684); /* as the asset's README says */
    printf("head: %d vertices, %d triangles, bounds (%g %g %g)..(%g %g %g)\n", verts, tris, s.bounds_min[0],
           s.bounds_min[1], s.bounds_min[2], s.bounds_max[0], s.bounds_max[1], s.bounds_max[2]);
    sl_scene_free(&s);
}

int main(void) {
    sl_log_threshold = SL_LOG_ERROR + 1;
    test_obj();
    test_gltf();
    test_through_json();
    test_bad_files();
    test_head();
    return check_result();
}
