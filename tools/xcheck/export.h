/* shadelab-xcheck's exporter: a loaded scene (an sl_app after sl_app_init, with every scene and
 * --set value applied) written as a Blender scene: DIR/scene.json (what to build), DIR/assets/
 * (meshes, textures, the environment as a lat-long EXR), DIR/xcheck_blender.py (the builder) and
 * DIR/scene.py (runs the builder on the files beside it):
 *
 *   blender -b --factory-startup --python DIR/scene.py -- OUTDIR
 *
 * renders OUTDIR/combined_0000.exr (linear radiance) and OUTDIR/index_0000.exr (object index,
 * 0 = background). The unit conversions and what is not cross-checked are in docs/xcheck.md. */
#ifndef XCHECK_EXPORT_H
#define XCHECK_EXPORT_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "toolkit.h"

typedef struct xc_export_options {
    int width, height;  /* image size */
    int samples;        /* Cycles samples per pixel */
    int bounces;        /* Cycles' max bounces (0: direct light only) */
    /* Objects visible to camera rays only: no object occludes, shadows or reflects any object
     * (itself included), the quantity an environment lighting without visibility computes.
     * scene.json's render.object_rays is "camera"; absent, every ray sees every object. */
    bool unoccluded;
    const char *builder; /* path of xcheck_blender.py */
} xc_export_options;

/* One object of the reference: a mesh of a scene node (or, for a glTF file, a mesh object of
 * Blender's import). Its Cycles pass index is its position + 1. */
typedef struct xc_object {
    char name[160];
    char material[160]; /* its material's name ("a, b" when several) */
    bool checked;       /* false: its material is not cross-checked (see notes) */
} xc_object;

typedef struct xc_export {
    xc_object *objects; int object_count;
    /* What the reference does not show as shadelab does: "not cross-checked: …" and
     * "approximated: …" lines, one per feature and material or light. */
    char **notes; int note_count;
    uint64_t hash;      /* of every file written (what was exported) */
    /* The scene is a .gltf/.glb opened directly: Blender's own importer reads it (geometry and
     * materials), the objects are known after the render (xc_export_read_objects). */
    bool gltf;
} xc_export;

bool xc_export_scene(sl_app *app, const xc_export_options *o, const char *dir, xc_export *out, char *err, size_t n);
void xc_export_free(xc_export *e);

/* Reads the objects Blender's glTF import made (objects.json written beside the render). */
bool xc_export_read_objects(xc_export *e, const char *objects_json, char *err, size_t n);

/* mkdir -p; false with err set when a component cannot be made. */
bool xc_mkdirs(const char *path, char *err, size_t n);
#endif
