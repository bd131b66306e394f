/* libFuzzer target for the project's OBJ reader (core/scene/obj_reader.c, sl_scene_import_obj),
 * not assimp's. The reader takes a path, so each input is written to a file in a private
 * temporary directory: the text before a line "#MTL" becomes fuzz.obj, the text after it fuzz.mtl
 * (read when the OBJ says "mtllib fuzz.mtl"). Build and run: see fuzz/README.md. */
#include "log.h"
#include "scene/scene.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[4096], obj_path[4200], mtl_path[4200];

static void write_file(const char *path, const uint8_t *data, size_t size) {
    FILE *f = fopen(path, "wb");
    if (!f) abort();
    if (size && fwrite(data, 1, size, f) != size) abort();
    fclose(f);
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc, (void)argv;
    sl_log_threshold = SL_LOG_ERROR + 1; /* quiet: warnings for odd input are expected */
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/shadelab-obj-fuzz.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) abort();
    snprintf(obj_path, sizeof obj_path, "%s/fuzz.obj", dir);
    snprintf(mtl_path, sizeof mtl_path, "%s/fuzz.mtl", dir);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    size_t split = size;
    for (size_t i = 0; i + 5 <= size; i++)
        if (!memcmp(data + i, "#MTL\n", 5) && (i == 0 || data[i - 1] == '\n')) {
            split = i;
            break;
        }
    write_file(obj_path, data, split);
    if (split < size) write_file(mtl_path, data + split + 5, size - split - 5);
    else unlink(mtl_path);
    sl_scene scene;
    memset(&scene, 0, sizeof scene);
    char err[2048] = "";
    bool ok = sl_scene_import_obj(&scene, obj_path, -1, err, sizeof err);
    if (ok) {
        sl_scene_update_transforms(&scene);
        for (int i = 0; i < scene.mesh_count; i++) { /* every index names a vertex of its mesh */
            const sl_mesh_data *d = &scene.meshes[i].data;
            if (d->index_count % 3 || d->vertex_count <= 0) abort();
            for (int k = 0; k < d->index_count; k++)
                if (d->indices[k] >= (uint32_t)d->vertex_count) abort();
        }
    } else if (!err[0] || !strstr(err, "fuzz.obj")) {
        abort(); /* a refusal names the file */
    }
    sl_scene_free(&scene);
    return 0;
}
