/* libFuzzer target for the project's glTF reader (core/scene/gltf_*.c, sl_scene_import_gltf).
 * The reader takes a path, so each input is written to a private temporary directory as fuzz.glb
 * (input starting with the GLB magic) or fuzz.gltf; a buffer or image URI resolves beside it.
 * Aborts when a refusal does not name the file, or a loaded mesh has an index past its vertices
 * or a non-finite position. Build and run: see fuzz/README.md. */
#include "log.h"
#include "module.h"
#include "scene/scene.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[4096], glb_path[4200], gltf_path[4200];

/* The Draco module (a C++ adapter over Debian's libdraco) is not part of this target: a Draco
 * primitive gets the reader's "module missing" error, which names the file like any other. */
const void *sl_module_open(const char *name, const char *env_var, const char *build_copy, const char *symbol,
                           unsigned min_size, char *why, size_t why_size) {
    (void)env_var, (void)build_copy, (void)symbol, (void)min_size;
    snprintf(why, why_size, "%s is not loaded in the fuzzer", name);
    return NULL;
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc, (void)argv;
    sl_log_threshold = SL_LOG_ERROR + 1; /* quiet: warnings for odd input are expected */
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/shadelab-gltf-fuzz.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) abort();
    snprintf(glb_path, sizeof glb_path, "%s/fuzz.glb", dir);
    snprintf(gltf_path, sizeof gltf_path, "%s/fuzz.gltf", dir);
    return 0;
}

static void check_meshes(const sl_scene *scene) {
    for (int i = 0; i < scene->mesh_count; i++) {
        const sl_mesh_data *d = &scene->meshes[i].data;
        if (d->index_count % 3 || d->vertex_count <= 0) abort();
        for (int k = 0; k < d->index_count; k++)
            if (d->indices[k] >= (uint32_t)d->vertex_count) abort();
        for (int k = 0; k < 3 * d->vertex_count; k++)
            if (!isfinite(d->positions[k])) abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *path = size >= 4 && !memcmp(data, "glTF", 4) ? glb_path : gltf_path;
    FILE *f = fopen(path, "wb");
    if (!f) abort();
    if (size && fwrite(data, 1, size, f) != size) abort();
    fclose(f);
    sl_scene scene;
    memset(&scene, 0, sizeof scene);
    char err[4096] = "";
    if (sl_scene_import_gltf(&scene, path, -1, NULL, err, sizeof err)) {
        sl_scene_update_transforms(&scene);
        check_meshes(&scene);
        for (int c = 0; c < scene.anim_channel_count; c++) sl_scene_animate(&scene, 0.37 * c);
    } else if (strstr(err, path) != err) {
        abort(); /* a refusal names the file */
    }
    sl_scene_free(&scene);
    unlink(path);
    return 0;
}
