/* libFuzzer target for shadelab's own scene parser: sl_scene_load_text (core/scene/scene_json.c
 * and the primitive generators it calls), not assimp's. Mesh files named by a scene are not
 * imported here (sl_scene_import_model and sl_scene_load_model are stubbed below), so the fuzzer never reads files and
 * only our code is exercised. Build and run: see fuzz/README.md. */
#include "scene/scene.h"
#include "log.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char sl_default_scene_json[] = "{}";

bool sl_scene_import_model(sl_scene *scene, const char *path, int parent_node, const sl_scene_load_opts *opts,
                           char *err, size_t n) {
    snprintf(err, n, "%s: mesh import is disabled in the fuzzer", path);
    return false;
}

bool sl_scene_load_model(sl_scene *scene, const char *path, const sl_scene_load_opts *opts, char *err, size_t n) {
    (void)scene;
    snprintf(err, n, "%s: model import is disabled in the fuzzer", path);
    return false;
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    sl_log_threshold = SL_LOG_ERROR + 1; /* quiet: warnings for odd input are expected */
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = 0;
    sl_scene scene;
    memset(&scene, 0, sizeof scene); /* as sl_app does: the loader fills a zeroed scene */
    char err[2048];
    sl_scene_load_opts opts = {0};
    if (sl_scene_load_text(&scene, text, "<fuzz>", NULL, &opts, err, sizeof err)) {
        sl_scene_update_transforms(&scene);
        sl_scene_free(&scene);
    } else {
        /* a failure must leave a safely freeable scene and a message */
        if (!err[0]) abort();
        sl_scene_free(&scene);
    }
    free(text);
    return 0;
}
