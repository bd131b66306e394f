/* Imports one model file with one reader and prints what came out and how long it took: the OBJ
 * comparison of issue 14 (tools/import/bench_import.sh runs it under /usr/bin/time -v). In
 * tests/ because it calls the core's scene API, which a tool may not (tests/module_rule.sh).
 *   usage: import_file obj|assimp|auto FILE */
#include "scene/scene.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

int main(int argc, char **argv) {
    if (argc != 3 || (strcmp(argv[1], "obj") && strcmp(argv[1], "assimp") && strcmp(argv[1], "auto"))) {
        fprintf(stderr, "usage: %s obj|assimp|auto FILE\n", argv[0]);
        return 2;
    }
    sl_scene s = {0};
    char err[2048] = "";
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    bool ok = !strcmp(argv[1], "obj")      ? sl_scene_import_obj(&s, argv[2], -1, err, sizeof err)
              : !strcmp(argv[1], "assimp") ? sl_scene_import_assimp(&s, argv[2], -1, err, sizeof err)
                                           : sl_scene_import_file(&s, argv[2], -1, err, sizeof err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (!ok) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    long long verts = 0, tris = 0;
    for (int i = 0; i < s.mesh_count; i++) verts += s.meshes[i].data.vertex_count, tris += s.meshes[i].data.index_count / 3;
    printf("%s reader: %d meshes, %lld vertices, %lld triangles, %d materials in %.2f s\n", argv[1], s.mesh_count, verts,
           tris, s.material_count, (t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) * 1e-9);
    sl_scene_free(&s);
    return 0;
}
