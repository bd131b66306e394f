/* shadelab-bake-normals: tangent-space → object-space normal maps for a mesh, procedural maps,
 * and a green-convention check. --help (or -h) prints the usage. */
#include "nm_tools.h"
#include <shadelab/input.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage[] =
    "usage:\n"
    "  shadelab-bake-normals --help | -h\n"
    "      This text.\n"
    "  shadelab-bake-normals --scene S.json --material NAME --out OUT.(png|exr)\n"
    "        [--map TANGENT_MAP] [--data DIR] [--size WxH] [--green opengl|directx] [--strength K] [--dilate PX]\n"
    "      Bakes the material's tangent-space normal_map (or --map) into an object-space map for every mesh\n"
    "      that uses the material, with the same tangent frames the renderer interpolates. Use the result\n"
    "      with \"normal_space\": \"object\". Size defaults to the tangent map's.\n"
    "  shadelab-bake-normals --generate SPEC --size N --out OUT.(png|exr)\n"
    "      Procedural +Y tangent-space map: flat, tilt:X,Y, bumps:N:A, waves:N:A:SEED.\n"
    "  shadelab-bake-normals --generate-property SPEC --size N --out OUT.png\n"
    "      Procedural property map for phong (R gloss, B AO): property:N:A, constant:GLOSS,AO.\n"
    "  shadelab-bake-normals --detect-green MAP\n"
    "      Says whether a tangent-space map is +Y (OpenGL) or -Y (DirectX), from the curl of its slopes.\n";

static bool write_image(const char *path, const sl_image *img) {
    char err[1024];
    /* display_encoded = true: the values are written as they are (data, not colour) */
    if (!sl_image_write(path, img->pixels, img->width, img->height, true, err, sizeof err)) {
        fprintf(stderr, "shadelab-bake-normals: %s\n", err);
        return false;
    }
    printf("wrote %s (%dx%d)\n", path, img->width, img->height);
    return true;
}

int main(int argc, char **argv) {
    const char *scene_path = NULL, *material = NULL, *out = NULL, *map = NULL, *data = NULL, *gen = NULL,
               *gen_prop = NULL, *detect = NULL;
    int W = 0, H = 0;
    nm_bake_opts o = {.green_sign = 1, .strength = 1, .dilate = 8};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { fputs(usage, stdout); return 0; }
#define ARG(name, dst) if (!strcmp(a, name)) { if (!v) { fprintf(stderr, "%s needs a value\n", name); return 2; } dst = v; i++; continue; }
        ARG("--scene", scene_path) ARG("--material", material) ARG("--out", out) ARG("--map", map)
        ARG("--data", data) ARG("--generate", gen) ARG("--generate-property", gen_prop) ARG("--detect-green", detect)
#undef ARG
        if (!strcmp(a, "--size") && v) { /* WxH, or N for NxN: whole numbers 1..16384 (<shadelab/input.h>) */
            long k;
            if (sl_parse_long(v, 1, 16384, &k)) W = H = (int)k;
            else if (!sl_parse_size(v, 16384, &W, &H)) { fprintf(stderr, "--size %s: expected N or WxH, 1..16384 each\n", v); return 2; }
            i++;
        } else if (!strcmp(a, "--green") && v) {
            if (!strcmp(v, "opengl")) o.green_sign = 1;
            else if (!strcmp(v, "directx")) o.green_sign = -1;
            else { fprintf(stderr, "--green %s: expected opengl or directx\n", v); return 2; }
            i++;
        } else if (!strcmp(a, "--strength") && v) {
            double k;
            if (!sl_parse_double(v, 0, 100, &k)) { fprintf(stderr, "--strength %s: expected a finite number 0..100\n", v); return 2; }
            o.strength = (float)k, i++;
        } else if (!strcmp(a, "--dilate") && v) {
            long k;
            if (!sl_parse_long(v, 0, 4096, &k)) { fprintf(stderr, "--dilate %s: expected a whole number 0..4096\n", v); return 2; }
            o.dilate = (int)k, i++;
        }
        else { fprintf(stderr, "unknown argument %s\n\n%s", a, usage); return 2; }
    }
    char err[4096];
    if (detect) {
        sl_image img;
        if (!sl_image_load(&img, detect, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        double cp, cm;
        int s = nm_detect_green(&img, &cp, &cm);
        printf("%s: mean |curl| of the slope field: +Y %.5f, -Y %.5f -> %s (ratio %.2f)\n", detect, cp, cm,
               s > 0 ? "+Y (opengl)" : "-Y (directx)", s > 0 ? cm / cp : cp / cm);
        sl_image_free(&img);
        return 0;
    }
    if (gen || gen_prop) {
        if (!out || W < 1) { fprintf(stderr, "--generate needs --size N and --out FILE\n"); return 2; }
        sl_image img;
        bool ok = gen ? nm_generate_tangent_map(&img, gen, W, err, sizeof err)
                      : nm_generate_property_map(&img, gen_prop, W, err, sizeof err);
        if (!ok) { fprintf(stderr, "%s\n", err); return 1; }
        ok = write_image(out, &img);
        sl_image_free(&img);
        return ok ? 0 : 1;
    }
    if (!scene_path || !material || !out) { fputs(usage, stderr); return 2; }

    sl_scene scene = {0};
    sl_scene_load_opts lo = {.data_dir = data};
    if (!sl_scene_load_file(&scene, scene_path, &lo, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
    int mat = sl_scene_find_material(&scene, material);
    if (mat < 0) { fprintf(stderr, "%s: no material named '%s'\n", scene_path, material); return 1; }
    char *map_path = NULL;
    if (map) map_path = strdup(map);
    else {
        const sl_prop *p = sl_prop_find(&scene.materials[mat].props, "normal_map");
        if (!p || p->kind != SL_PROP_STRING) {
            fprintf(stderr, "material '%s' has no normal_map (give --map)\n", material);
            return 1;
        }
        const sl_prop *space = sl_prop_find(&scene.materials[mat].props, "normal_space");
        if (space && space->str && !strcmp(space->str, "object")) {
            fprintf(stderr, "material '%s': its normal_map is already object-space\n", material);
            return 1;
        }
        map_path = sl_scene_resolve_path(&scene, data, p->str, err, sizeof err);
        if (!map_path) { fprintf(stderr, "normal_map %s\n", err); return 1; }
    }
    sl_image tmap;
    if (!sl_image_load(&tmap, map_path, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
    const sl_mesh_data *meshes[1024];
    int count = 0;
    for (int i = 0; i < scene.mesh_count && count < 1024; i++)
        if (scene.meshes[i].material == mat) meshes[count++] = &scene.meshes[i].data;
    if (!count) { fprintf(stderr, "no mesh uses material '%s'\n", material); return 1; }
    if (W < 1) W = tmap.width, H = tmap.height;
    sl_image obj;
    long covered = nm_bake_object_space(meshes, count, &tmap, &o, W, H, &obj, err, sizeof err);
    if (covered < 0) { fprintf(stderr, "%s\n", err); return 1; }
    printf("%s: %d mesh(es), %ld of %d texels covered (%.1f%%), map %s\n", material, count, covered, W * H,
           100.0 * covered / ((double)W * H), map_path);
    bool ok = write_image(out, &obj);
    sl_image_free(&obj);
    sl_image_free(&tmap);
    free(map_path);
    sl_scene_free(&scene);
    return ok ? 0 : 1;
}
