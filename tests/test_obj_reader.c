/* The project's OBJ reader (core/scene/obj_reader.c) against the assimp import it replaces, and
 * on hostile files.
 *
 * Comparison: every OBJ among the test data (tests/data, recursively) and assimp's own test models
 * (/usr/share/assimp/models{,-nonbsd}/OBJ and invalid/, Debian's assimp-testmodels, when
 * installed) is loaded with both readers (sl_scene_import_obj, sl_scene_import_assimp). Both
 * must refuse it, or both load it with the same nodes, meshes (names, materials, vertex and
 * index counts, positions, normals and UVs vertex by vertex within 1e-6 relative, total triangle
 * area) and material inputs (base colour, opacity, textures). Differences that are by design are
 * listed in `expected` with the reason; any other fails the test.
 *
 * Hostile files, generated here: each refused with "file:line: cause", or loaded as documented
 * (relative indices, fan triangulation of a 1000-gon, continuations, UTF-8 BOM). */
#include "check.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char logbuf[1 << 16];

/* Files whose two imports differ by design: the name's end, and why. */
static const struct { const char *file, *why; } expected[] = {
    {"concave_polygon.obj", "a concave polygon: fan vs assimp's ear clipping, same vertices, other triangles"},
    {"box_longline.obj", "a face repeating its 4 corners 236 times: other triangles, so other generated normals"},
    {"regr01.obj", "UVs 1 and 0.99999994 at one position: assimp joins values within 1e-5, the reader equal ones"},
    {"space_in_material_name.obj", "a concave 66-gon: fan vs ear clipping, as above"},
};

static const char *expected_difference(const char *path) {
    size_t n = strlen(path);
    for (size_t i = 0; i < sizeof expected / sizeof *expected; i++) {
        size_t m = strlen(expected[i].file);
        if (n >= m && !strcmp(path + n - m, expected[i].file)) return expected[i].why;
    }
    return NULL;
}

static double area(const sl_mesh_data *d) {
    double a = 0;
    for (int t = 0; t + 2 < d->index_count; t += 3) {
        const float *p = d->positions + 3 * d->indices[t], *q = d->positions + 3 * d->indices[t + 1],
                    *r = d->positions + 3 * d->indices[t + 2];
        double e1[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, e2[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
        double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        a += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return a;
}

static bool close_arrays(const float *a, const float *b, int n) {
    for (int i = 0; i < n; i++)
        if (!(fabsf(a[i] - b[i]) <= 1e-6f * (1.0f + fabsf(a[i])))) return false;
    return true;
}

static bool same_prop(const sl_prop_list *a, const sl_prop_list *b, const char *key) {
    const sl_prop *p = sl_prop_find(a, key), *q = sl_prop_find(b, key);
    if (!p || !q) return !p && !q;
    if (p->kind != q->kind || p->count != q->count) return false;
    if (p->kind == SL_PROP_STRING) return !strcmp(p->str, q->str);
    for (int k = 0; k < (p->kind == SL_PROP_VEC ? p->count : 1); k++)
        if (fabsf(p->v[k] - q->v[k]) > 1e-6f) return false;
    return true;
}

/* 0: same; else the number of differences (each printed). */
static int compare_scenes(const char *path, const sl_scene *a, const sl_scene *b) {
    int diff = 0;
#define DIFF(...) (diff++, printf("    differs: " __VA_ARGS__), putchar('\n'))
    if (a->node_count != b->node_count) DIFF("%d nodes vs %d", a->node_count, b->node_count);
    for (int i = 0; i < a->node_count && i < b->node_count; i++) {
        if (strcmp(a->nodes[i].name, b->nodes[i].name) || a->nodes[i].parent != b->nodes[i].parent ||
            a->nodes[i].mesh_count != b->nodes[i].mesh_count)
            DIFF("node %d: '%s' (parent %d, %d meshes) vs '%s' (parent %d, %d meshes)", i, a->nodes[i].name,
                 a->nodes[i].parent, a->nodes[i].mesh_count, b->nodes[i].name, b->nodes[i].parent, b->nodes[i].mesh_count);
    }
    if (a->mesh_count != b->mesh_count) DIFF("%d meshes vs %d", a->mesh_count, b->mesh_count);
    for (int i = 0; i < a->mesh_count && i < b->mesh_count; i++) {
        const sl_mesh *x = &a->meshes[i], *y = &b->meshes[i];
        const sl_mesh_data *d = &x->data, *e = &y->data;
        if (strcmp(x->name, y->name)) DIFF("mesh %d named '%s' vs '%s'", i, x->name, y->name);
        const sl_material *mx = &a->materials[x->material], *my = &b->materials[y->material];
        if (strcmp(mx->name, my->name)) DIFF("mesh %d material '%s' vs '%s'", i, mx->name, my->name);
        static const char *const keys[] = {"base_color", "opacity", "base_color_texture", "normal_texture", "brdf",
                                           "metallic", "roughness", "emissive", "emissive_texture"};
        for (size_t k = 0; k < sizeof keys / sizeof *keys; k++)
            if (!same_prop(&mx->inputs, &my->inputs, keys[k])) DIFF("material '%s' input %s", mx->name, keys[k]);
        if (d->vertex_count != e->vertex_count || d->index_count != e->index_count) {
            DIFF("mesh '%s': %d vertices, %d triangles vs %d, %d", x->name, d->vertex_count, d->index_count / 3,
                 e->vertex_count, e->index_count / 3);
            continue;
        }
        if (!close_arrays(d->positions, e->positions, 3 * d->vertex_count)) DIFF("mesh '%s': positions", x->name);
        if (!close_arrays(d->normals, e->normals, 3 * d->vertex_count)) DIFF("mesh '%s': normals", x->name);
        if (!close_arrays(d->uvs, e->uvs, 2 * d->vertex_count)) DIFF("mesh '%s': uvs", x->name);
        double aa = area(d), ab = area(e);
        if (!(fabs(aa - ab) <= 1e-5 * (aa + ab) + 1e-9)) DIFF("mesh '%s': triangle area %.9g vs %.9g", x->name, aa, ab);
    }
    if (diff) printf("    (%s)\n", path);
#undef DIFF
    return diff;
}

static int files_compared, files_same, files_refused;

static void compare_file(const char *path) {
    sl_scene a = {0}, b = {0};
    char ea[1024] = "", eb[1024] = "";
    sl_log_capture(logbuf, sizeof logbuf);
    bool oa = sl_scene_import_obj(&a, path, -1, ea, sizeof ea);
    bool ob = sl_scene_import_assimp(&b, path, -1, eb, sizeof eb);
    sl_log_capture(NULL, 0);
    files_compared++;
    const char *why = expected_difference(path);
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    int diff = 0;
    if (!oa || !ob) {
        if (!oa) CHECK_MSG(ea[0] && strstr(ea, name), "%s: refused without a message naming it: '%s'", path, ea);
        if (!oa && !ob) files_refused++;
        diff = oa != ob;
        printf("%-34s %s\n    obj reader: %s\n    assimp:     %s\n", name, oa == ob ? "both refuse" : "ONE REFUSES",
               oa ? "loaded" : ea, ob ? "loaded" : eb);
    } else {
        diff = compare_scenes(path, &a, &b);
        int tris = 0, verts = 0;
        for (int i = 0; i < a.mesh_count; i++) tris += a.meshes[i].data.index_count / 3, verts += a.meshes[i].data.vertex_count;
        printf("%-34s %s (%d meshes, %d vertices, %d triangles)\n", name, diff ? "DIFFERENT" : "same", a.mesh_count, verts,
               tris);
    }
    if (diff && why) printf("    expected: %s\n", why);
    else CHECK_MSG(!diff, "%s: the OBJ reader and assimp disagree", path);
    files_same += !diff;
    sl_scene_free(&a);
    sl_scene_free(&b);
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Every *.obj under dir (recursively), in name order. */
static void compare_dir(const char *dir, int depth) {
    DIR *d = opendir(dir);
    if (!d) return;
    char *names[512];
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) && n < 512;)
        if (e->d_name[0] != '.') names[n++] = strdup(e->d_name);
    closedir(d);
    qsort(names, (size_t)n, sizeof *names, cmp_str);
    for (int i = 0; i < n; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        struct stat st;
        size_t len = strlen(names[i]);
        if (!strcmp(names[i], "fuzz_obj")) { /* fuzzer inputs, not models: test_fuzz_inputs */
        } else if (stat(path, &st) == 0 && S_ISDIR(st.st_mode) && depth < 4) compare_dir(path, depth + 1);
        else if (S_ISREG(st.st_mode) && len > 4 && !strcasecmp(names[i] + len - 4, ".obj")) compare_file(path);
        free(names[i]);
    }
}

/* ---- hostile and edge cases ---------------------------------------------------------------- */

static char file_path[4096];

static const char *write_file(const char *name, const char *text, size_t len) {
    snprintf(file_path, sizeof file_path, "%s/%s", sl_test_dir(), name);
    FILE *f = fopen(file_path, "wb");
    if (f) fwrite(text, 1, len, f), fclose(f);
    return file_path;
}

/* Loads text as NAME; expects a refusal whose message holds `needle` (NULL: expects a load). */
static bool load(const char *name, const char *text, size_t len, const char *needle, sl_scene *out) {
    const char *path = write_file(name, text, len);
    sl_scene s = {0};
    char err[1024] = "";
    sl_log_capture(logbuf, sizeof logbuf);
    bool ok = sl_scene_import_obj(&s, path, -1, err, sizeof err);
    sl_log_capture(NULL, 0);
    printf("%-22s %s\n", name, ok ? "loaded" : err);
    if (needle) {
        CHECK_MSG(!ok, "%s: loaded, expected a refusal with '%s'", name, needle);
        CHECK_CONTAINS(err, needle);
    } else {
        CHECK_MSG(ok, "%s: %s", name, err);
    }
    if (out && ok) *out = s;
    else sl_scene_free(&s);
    return ok;
}
#define LOAD(name, text, needle, out) load(name, text, sizeof text - 1, needle, out)

static void test_hostile(void) {
    LOAD("huge_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "huge_index.obj:4: face: vertex index beyond 2^31", NULL);
    LOAD("past_end.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "past_end.obj:4: face: vertex index 4, but only 3 defined", NULL);
    LOAD("forward.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "forward.obj:3: face: vertex index 3, but only 2 defined", NULL);
    LOAD("zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "zero_index.obj:4: face: vertex index 0", NULL);
    LOAD("neg_past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "neg_past.obj:4: face: vertex index -4 reaches before", NULL);
    LOAD("bad_vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "bad_vt.obj:5: face: texture coordinate index 2", NULL);
    LOAD("bad_vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "bad_vn.obj:4: face: normal index 1, but only 0 defined", NULL);
    LOAD("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "nan.obj:2: 'v': nan is not a finite float", NULL);
    LOAD("inf.obj", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n", "inf.obj:2: 'v': -inf is not a finite float", NULL);
    LOAD("overflow.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", "overflow.obj:2: 'v': 1e39 is not a finite float", NULL);
    LOAD("missing.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "missing.obj:2: 'v' has 2 of its 3 coordinates", NULL);
    LOAD("not_number.obj", "v 0 0 0\nv 1 0 0\nvn 0 x 1\n", "not_number.obj:3: 'vn': 'x' is not a number", NULL);
    LOAD("no_digits.obj", "v 0 0 0\nv 1 0 0\nv - 1 0\n", "no_digits.obj:3: 'v': '-' is not a number", NULL);
    LOAD("bad_corner.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n", "bad_corner.obj:4: face: unexpected 'x'", NULL);
    LOAD("binary.obj", "v 0 0 0\n\x7f" "ELF\x02\x01\x01\x00\x00\x00\n", "binary.obj:2: binary data (a NUL byte)", NULL);
    LOAD("empty.obj", "# nothing\n", "empty.obj: no mesh left to draw", NULL);
    LOAD("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\nf 1 2\n", "lines.obj: no mesh left to draw", NULL);
    /* an overlong line: SL_OBJ_MAX_LINE + 10 bytes of a comment, then a triangle */
    size_t big = SL_OBJ_MAX_LINE + 10;
    char *longline = malloc(big + 64);
    if (longline) {
        memset(longline, 'x', big);
        longline[0] = '#';
        size_t n = big + (size_t)snprintf(longline + big, 64, "\n%s", "v 0 0 0\n");
        load("long_line.obj", longline, n, "long_line.obj:1: line longer than 1048576 bytes", NULL);
        free(longline);
    }
    /* relative (negative) indices, quads and a 1000-gon fan-triangulated, continuations, a BOM */
    sl_scene s = {0};
    if (LOAD("relative.obj", "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\nf 1 2 \\\n 3\n", NULL, &s)) {
        CHECK(s.mesh_count == 1 && s.meshes[0].data.vertex_count == 4 && s.meshes[0].data.index_count == 9);
        sl_scene_free(&s);
    }
    /* a regular 1000-gon: 998 triangles sharing vertex 1, area within 1e-5 of the polygon's */
    FILE *f = fopen(write_file("polygon.obj", "", 0), "w");
    if (f) {
        const int N = 1000;
        for (int i = 0; i < N; i++) fprintf(f, "v %.9f %.9f 0\n", cos(2 * M_PI * i / N), sin(2 * M_PI * i / N));
        fprintf(f, "f");
        for (int i = 1; i <= N; i++) fprintf(f, " %d", i);
        fprintf(f, "\n");
        fclose(f);
        char err[512] = "";
        bool ok = sl_scene_import_obj(&s, file_path, -1, err, sizeof err);
        CHECK_MSG(ok, "%s", err);
        if (ok) {
            const sl_mesh_data *d = &s.meshes[0].data;
            CHECK(d->vertex_count == N && d->index_count == 3 * (N - 2));
            bool fan = true;
            for (int t = 0; t < N - 2; t++) fan = fan && d->indices[3 * t] == 0;
            CHECK(fan);
            CHECK_NEAR(area(d), 0.5 * N * sin(2 * M_PI / N), 1e-5);
        }
        sl_scene_free(&s);
    }
}

/* tests/data/fuzz_obj/: inputs for fuzz/obj_fuzzer (hand-made edge cases, and what it finds),
 * split as the fuzzer does (the text after a line "#MTL" is fuzz.mtl): each loads or is refused
 * with a message naming it, and a loaded mesh's indices all name its vertices. */
static void test_fuzz_inputs(void) {
    const char *dir = SL_TEST_DATA_DIR "/fuzz_obj";
    DIR *d = opendir(dir);
    CHECK_MSG(d != NULL, "cannot open %s", dir);
    int files = 0;
    for (struct dirent *e; d && (e = readdir(d));) {
        if (e->d_name[0] == '.' || strstr(e->d_name, "README")) continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        if (!f) continue;
        static char data[1 << 20];
        size_t n = fread(data, 1, sizeof data, f);
        fclose(f);
        size_t split = n;
        for (size_t i = 0; i + 5 <= n && split == n; i++)
            if (!memcmp(data + i, "#MTL\n", 5) && (i == 0 || data[i - 1] == '\n')) split = i;
        if (split < n) write_file("fuzz.mtl", data + split + 5, n - split - 5);
        const char *obj = write_file("fuzz.obj", data, split);
        sl_scene s = {0};
        char err[1024] = "";
        sl_log_capture(logbuf, sizeof logbuf);
        bool ok = sl_scene_import_obj(&s, obj, -1, err, sizeof err);
        sl_log_capture(NULL, 0);
        printf("fuzz_obj/%-24s %s\n", e->d_name, ok ? "loaded" : err);
        if (!ok) CHECK_CONTAINS(err, "fuzz.obj");
        if (ok && !strcmp(e->d_name, "groups_materials.obj")) {
            /* g/usemtl runs as assimp splits them; MTL values, options before a name with a space */
            CHECK(s.mesh_count == 3 && s.node_count == 4); /* "usemtl" alone is ignored (assimp) */
            if (s.mesh_count == 3) {
                CHECK(!strcmp(s.meshes[0].name, "fuzz/one") && s.meshes[0].data.index_count == 6);
                CHECK(!strcmp(s.meshes[1].name, "fuzz/two") && s.meshes[1].data.vertex_count == 3);
                CHECK(!strcmp(s.meshes[2].name, "fuzz/blue"));
                const sl_material *red = &s.materials[s.meshes[0].material], *def = &s.materials[s.meshes[1].material],
                                  *blue = &s.materials[s.meshes[2].material];
                CHECK(!strcmp(red->name, "fuzz/red") && !strcmp(def->name, "fuzz/red"));
                const sl_prop *p = sl_prop_find(&red->inputs, "opacity");
                CHECK(p && p->v[0] == 0.5f);
                p = sl_prop_find(&red->inputs, "base_color_texture");
                CHECK(p && strlen(p->str) > 13 && !strcmp(p->str + strlen(p->str) - 13, "/tex ture.png"));
                p = sl_prop_find(&blue->inputs, "roughness");
                CHECK(p && p->v[0] == 0.5f && sl_prop_find(&blue->inputs, "brdf"));
                p = sl_prop_find(&blue->inputs, "emissive");
                CHECK(p && p->v[2] == 3.0f && sl_prop_find(&blue->inputs, "normal_texture"));
            }
        }
        for (int m = 0; ok && m < s.mesh_count; m++)
            for (int k = 0; k < s.meshes[m].data.index_count; k++)
                CHECK(s.meshes[m].data.indices[k] < (uint32_t)s.meshes[m].data.vertex_count);
        sl_scene_free(&s);
        files++;
    }
    if (d) closedir(d);
    CHECK(files > 0);
}

int main(void) {
    test_hostile();
    test_fuzz_inputs();
    compare_dir(SL_TEST_DATA_DIR, 0);
    compare_dir("/usr/share/assimp/models/OBJ", 0);
    compare_dir("/usr/share/assimp/models-nonbsd/OBJ", 0);
    compare_dir("/usr/share/assimp/models/invalid", 0);
    printf("%d OBJ files compared: %d the same with both readers (%d refused by both)\n", files_compared, files_same,
           files_refused);
    CHECK(files_compared > 0);
    return check_result();
}
