/* The Draco decoder behind a C table (core/scene/gltf_draco.cpp, built as the module
 * shadelab-draco.so and opened on first use: module.h). Used by the glTF reader for
 * KHR_draco_mesh_compression (gltf_draco.c). */
#ifndef SL_GLTF_DRACO_H
#define SL_GLTF_DRACO_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct sl_draco_api {
    unsigned struct_size;
    /* Decodes a Draco triangle mesh: its point and face counts, or NULL with Draco's words in err. */
    void *(*decode)(const unsigned char *data, size_t size, int *points, int *faces, char *err, size_t err_size);
    /* 3 × faces point indices. */
    void (*indices)(const void *mesh, uint32_t *out);
    /* The attribute of that unique id as points × comps floats (normalized integers as Draco
     * normalizes them); false when there is none or it has fewer components. */
    bool (*attribute)(const void *mesh, int unique_id, int comps, float *out);
    void (*free)(void *mesh);
} sl_draco_api;

/* The module's table (opened once), or NULL with why in err. */
const sl_draco_api *sl_draco(char *err, size_t err_size);
#endif
