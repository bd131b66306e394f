/* sl_program_uniform (render/composer.h): the location of a uniform from the program's cache of
 * names, each asked of GL once per link. Against glGetUniformLocation itself on a program with
 * scalars, an array, an array of structs and more names than the cache's first table holds:
 * every name, asked twice (the second from the cache); inactive and unknown names -1; an array's
 * bare name is its element 0; after the program is built again from changed files, the names of
 * the new program, not the cached ones. */
#include "render/composer.h"
#include "test_tmp.h"
#include <shadelab/gl.h>
#include <shadelab/harness.h>

#define LIGHTS 40

static void write_file(const char *name, const char *text) {
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", sl_test_dir(), name);
    FILE *f = fopen(path, "w");
    CHECK_MSG(f != NULL, "cannot write %s", path);
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

static const char *VS = "void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n";

/* a fragment shader reading `used` (a float), `unused` declared and not read */
static void write_fs(const char *used) {
    char text[2048];
    snprintf(text, sizeof text,
             "struct Light { vec3 color; float range; };\n"
             "uniform Light lights[%d];\n"
             "uniform float weights[4];\n"
             "uniform float %s;\n"
             "uniform float unused;\n"
             "out vec4 o;\n"
             "void main() {\n"
             "  vec3 c = vec3(0.0);\n"
             "  for (int i = 0; i < %d; i++) c += lights[i].color * lights[i].range;\n"
             "  o = vec4(c, weights[0] + weights[3] + %s);\n"
             "}\n",
             LIGHTS, used, LIGHTS, used);
    write_file("u.frag", text);
}

/* sl_program_uniform against GL for `name`, asked twice */
static void same(sl_program *p, const char *name) {
    int gl = glGetUniformLocation(p->id, name);
    int first = sl_program_uniform(p, name), cached = sl_program_uniform(p, name);
    CHECK_MSG(first == gl && cached == gl, "%s: sl_program_uniform %d then %d, GL %d", name, first, cached, gl);
}

int main(void) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();
    write_file("u.vert", VS);
    write_fs("gain");
    sl_program *p = sl_program_from_files(sl_test_dir(), "u.vert", "u.frag", NULL, err, sizeof err);
    CHECK_MSG(p && p->id, "build: %s", err);
    if (!p || !p->id) return check_result();

    same(p, "gain");
    CHECK(sl_program_uniform(p, "gain") >= 0);
    CHECK_MSG(sl_program_uniform(p, "unused") == -1, "a declared, unread uniform has no location");
    CHECK_MSG(sl_program_uniform(p, "no_such") == -1 && sl_program_uniform(p, "no_such") == -1, "an unknown name: -1");
    same(p, "weights");
    same(p, "weights[3]");
    CHECK_MSG(sl_program_uniform(p, "weights") == glGetUniformLocation(p->id, "weights[0]"),
              "an array's bare name is its element 0");
    /* 2 × 40 struct members, cached as any name: the cache grows past its first 64 slots */
    int distinct = 0;
    for (int i = 0; i < LIGHTS; i++) {
        char name[64];
        snprintf(name, sizeof name, "lights[%d].color", i);
        same(p, name);
        snprintf(name, sizeof name, "lights[%d].range", i);
        same(p, name);
        distinct += glGetUniformLocation(p->id, name) >= 0;
    }
    CHECK_MSG(distinct == LIGHTS, "%d of %d lights' ranges active", distinct, LIGHTS);
    for (int i = 0; i < 100; i++) { /* and unknown names, many of them */
        char name[64];
        snprintf(name, sizeof name, "missing_%d", i);
        same(p, name);
    }
    same(p, "gain"); /* still found after the table grew */

    /* built again from changed files: the new program's names */
    unsigned before = p->id;
    write_fs("level");
    CHECK_MSG(sl_program_rebuild_files(p, sl_test_dir(), err, sizeof err), "rebuild: %s", err);
    unsigned after = sl_program_id(p);
    CHECK_MSG(after && after != before, "the rebuilt program has a new GL id (%u, was %u)", after, before);
    same(p, "level");
    CHECK_MSG(sl_program_uniform(p, "gain") == -1, "the old program's uniform is gone after the rebuild");
    CHECK(sl_program_uniform(p, "level") >= 0);
    sl_program_free(p);
    sl_harness_destroy(h);
    return check_result();
}
