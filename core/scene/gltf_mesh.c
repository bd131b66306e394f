/* glTF meshes (glTF 2.0 §3.7.2): each primitive one scene mesh, triangles only. Strips and fans
 * become triangle lists; points and lines are dropped (named); an index past the vertices drops
 * its triangle (named, with the count); a primitive without normals gets flat normals, as §3.7.2.1
 * asks; tangents are the file's, or the project's (core/scene/tangents.c) when it has none; the
 * mesh's default morph weights are applied to the base shape. UVs arrive as written (v = 0 at
 * the image top, the scene convention). Attribute formats follow §3.7.2.1's table, widened by
 * KHR_mesh_quantization when the file uses it. */
#include "scene/gltf.h"
#include "scene/gltf_draco.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct primitive {
    char at[96];             /* "/meshes/2/primitives/0" */
    int vertex_count;
    float *pos, *nrm, *tan, *uv0, *uv1;
    uint32_t *tris;          /* 3 per triangle */
    int tri_count;
    /* KHR_draco_mesh_compression: the decoded mesh, its points and the attributes it holds */
    const sl_draco_api *draco;
    void *draco_mesh;
    const cJSON *draco_attrs;
    int draco_points, draco_faces;
} primitive;

static void primitive_free(primitive *p) {
    free(p->pos), free(p->nrm), free(p->tan), free(p->uv0), free(p->uv1), free(p->tris);
    if (p->draco_mesh) p->draco->free(p->draco_mesh);
}

/* Attribute `name` from the Draco mesh (its accessor gives the count, which must be the points'). */
static bool draco_attribute(gltf_import *im, primitive *p, int index, const char *name, const char *type, const char *at,
                            float **out) {
    gltf_doc *d = &im->doc;
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(p->draco_attrs, name);
    int comps = type[3] - '0', count = gltf_accessor_count(d, index);
    if (count < 0) return false;
    if (!cJSON_IsNumber(id) || id->valuedouble < 0 || id->valuedouble > 1e9)
        return gltf_fail(d, at, "its KHR_draco_mesh_compression id is not a non-negative integer");
    if (count != p->draco_points)
        return gltf_fail(d, at, "its accessor says %d elements, the Draco mesh has %d points", count, p->draco_points);
    if (!(*out = malloc(sizeof(float) * (size_t)comps * (size_t)count))) return gltf_fail(d, at, "out of memory");
    if (!p->draco->attribute(p->draco_mesh, id->valueint, comps, *out))
        return gltf_fail(d, at, "the Draco mesh has no attribute %d of %d components", id->valueint, comps);
    return true;
}

/* KHR_draco_mesh_compression (on the primitive at p->at): its bufferView decoded by the Draco
 * module; attributes and indices then come from it. */
static bool open_draco(gltf_import *im, primitive *p, const cJSON *ext) {
    gltf_doc *d = &im->doc;
    char at[160], why[600];
    snprintf(at, sizeof at, "%s/extensions/KHR_draco_mesh_compression", p->at);
    int view = -1;
    const unsigned char *bytes;
    size_t len, stride;
    if (!cJSON_IsObject(ext)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_index(d, ext, at, "bufferView", "bufferViews", true, &view) ||
        !gltf_get_object(d, ext, at, "attributes", &p->draco_attrs) || !gltf_buffer_view(d, view, &bytes, &len, &stride))
        return false;
    if (!p->draco_attrs) return gltf_fail(d, at, "attributes is missing (required)");
    if (!(p->draco = sl_draco(why, sizeof why))) return gltf_fail(d, at, "%s", why);
    if (!(p->draco_mesh = p->draco->decode(bytes, len, &p->draco_points, &p->draco_faces, why, sizeof why)))
        return gltf_fail(d, at, "%s", why);
    return true;
}

/* Attribute `name` of the primitive (absent: *out NULL); its count must be the vertex count. */
static bool attribute(gltf_import *im, primitive *p, const cJSON *attrs, const char *name, const char *type,
                      unsigned allowed, float **out) {
    char at[128];
    snprintf(at, sizeof at, "%s/attributes", p->at);
    int index = -1, count = 0;
    *out = NULL;
    if (!gltf_get_index(&im->doc, attrs, at, name, "accessors", false, &index)) return false;
    if (index < 0) return true;
    snprintf(at, sizeof at, "%s/attributes/%s", p->at, name);
    if (p->draco_mesh && cJSON_GetObjectItemCaseSensitive(p->draco_attrs, name)) {
        if (!draco_attribute(im, p, index, name, type, at, out)) return false;
        count = p->draco_points;
    } else if (!(*out = gltf_read_floats(&im->doc, index, type, allowed, at, &count))) {
        return false;
    }
    if (p->vertex_count && count != p->vertex_count)
        return gltf_fail(&im->doc, at, "%d elements, but POSITION has %d (all attributes of a primitive have one count)",
                         count, p->vertex_count);
    p->vertex_count = count;
    return true;
}

/* The triangles of the primitive's index list (or 0..n−1) in `mode` (4 list, 5 strip, 6 fan). */
static bool triangles(gltf_import *im, primitive *p, int mode, const uint32_t *idx, int n) {
    int tris = mode == 4 ? n / 3 : n >= 3 ? n - 2 : 0;
    if (mode == 4 && n % 3) gltf_note(&im->doc, p->at, "%d indices are not a whole number of triangles: the last %d ignored", n, n % 3);
    if (!(p->tris = malloc(sizeof(uint32_t) * 3 * (size_t)(tris ? tris : 1)))) return gltf_fail(&im->doc, p->at, "out of memory");
    int dropped = 0;
    for (int t = 0; t < tris; t++) {
        uint32_t a, b, c;
        if (mode == 4) a = idx ? idx[3 * t] : 3u * t, b = idx ? idx[3 * t + 1] : 3u * t + 1, c = idx ? idx[3 * t + 2] : 3u * t + 2;
        else if (mode == 5) { /* strip: every other triangle turned back to counter-clockwise */
            uint32_t v0 = idx ? idx[t] : (uint32_t)t, v1 = idx ? idx[t + 1] : (uint32_t)t + 1, v2 = idx ? idx[t + 2] : (uint32_t)t + 2;
            a = v0, b = t % 2 ? v2 : v1, c = t % 2 ? v1 : v2;
        } else
            a = idx ? idx[0] : 0, b = idx ? idx[t + 1] : (uint32_t)t + 1, c = idx ? idx[t + 2] : (uint32_t)t + 2;
        if (a >= (uint32_t)p->vertex_count || b >= (uint32_t)p->vertex_count || c >= (uint32_t)p->vertex_count) {
            dropped++;
            continue;
        }
        p->tris[3 * p->tri_count] = a, p->tris[3 * p->tri_count + 1] = b, p->tris[3 * p->tri_count + 2] = c;
        p->tri_count++;
    }
    if (dropped)
        gltf_note(&im->doc, p->at, "%d triangle%s with an index past the %d vertices dropped", dropped, dropped > 1 ? "s" : "",
                  p->vertex_count);
    return true;
}

/* Adds the mesh's default morph weights (§3.7.2.2) times each target's displacements. */
static bool morph(gltf_import *im, primitive *p, const cJSON *prim, const cJSON *weights, unsigned q) {
    const cJSON *targets, *t;
    if (!gltf_get_array(&im->doc, prim, p->at, "targets", &targets)) return false;
    int k = 0;
    cJSON_ArrayForEach(t, targets) {
        const cJSON *w = cJSON_GetArrayItem(weights, k);
        double wk = cJSON_IsNumber(w) && isfinite(w->valuedouble) ? w->valuedouble : 0;
        char at[128];
        snprintf(at, sizeof at, "%s/targets/%d", p->at, k++);
        if (wk == 0) continue;
        if (!cJSON_IsObject(t)) return gltf_fail(&im->doc, at, "must be an object");
        primitive tp = {.vertex_count = p->vertex_count};
        snprintf(tp.at, sizeof tp.at, "%s", at);
        const unsigned deltas = GLTF_F32 | (q ? GLTF_I8N | GLTF_I16N | GLTF_I8 | GLTF_I16 : 0);
        bool ok = attribute(im, &tp, t, "POSITION", "VEC3", deltas, &tp.pos) && attribute(im, &tp, t, "NORMAL", "VEC3", deltas, &tp.nrm);
        for (int i = 0; ok && i < 3 * p->vertex_count; i++) {
            if (tp.pos) p->pos[i] += (float)wk * tp.pos[i];
            if (tp.nrm && p->nrm) p->nrm[i] += (float)wk * tp.nrm[i];
        }
        free(tp.pos), free(tp.nrm);
        if (!ok) return false;
    }
    return true;
}

/* The primitive's material: the default one, or the variant's (KHR_materials_variants). */
static bool primitive_material(gltf_import *im, const cJSON *prim, const char *at, int *material) {
    gltf_doc *d = &im->doc;
    if (!gltf_get_index(d, prim, at, "material", "materials", false, material)) return false;
    const cJSON *ext, *kv = NULL, *mappings = NULL, *m;
    char ep[160], kp[200];
    snprintf(ep, sizeof ep, "%s/extensions", at);
    snprintf(kp, sizeof kp, "%s/KHR_materials_variants", ep);
    if (im->variant < 0 || !gltf_get_object(d, prim, at, "extensions", &ext) ||
        (ext && !gltf_get_object(d, ext, ep, "KHR_materials_variants", &kv)) ||
        (kv && !gltf_get_array(d, kv, kp, "mappings", &mappings)))
        return !d->failed;
    int k = 0;
    cJSON_ArrayForEach(m, mappings) {
        char mp[240];
        snprintf(mp, sizeof mp, "%s/mappings/%d", kp, k++);
        const cJSON *variants, *v;
        int mat = -1;
        if (!gltf_get_index(d, m, mp, "material", "materials", true, &mat) || !gltf_get_array(d, m, mp, "variants", &variants))
            return false;
        cJSON_ArrayForEach(v, variants) if (cJSON_IsNumber(v) && v->valuedouble == im->variant) *material = mat;
    }
    return true;
}

/* Reads the primitive at p->at; false after gltf_fail, true with tri_count 0 when it is dropped. */
static bool read_primitive(gltf_import *im, const cJSON *prim, const cJSON *weights, primitive *p) {
    gltf_doc *d = &im->doc;
    long long mode = 4;
    int indices = -1;
    const cJSON *attrs;
    if (!cJSON_IsObject(prim)) return gltf_fail(d, p->at, "must be an object");
    if (!gltf_get_int(d, prim, p->at, "mode", 0, 6, &mode) || !gltf_get_object(d, prim, p->at, "attributes", &attrs) ||
        !gltf_get_index(d, prim, p->at, "indices", "accessors", false, &indices))
        return false;
    if (mode < 4) {
        static const char *const names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
        gltf_note(d, p->at, "mode %lld (%s) not drawn: shadelab draws triangles", mode, names[mode]);
        return true;
    }
    if (!attrs) return gltf_fail(d, p->at, "attributes is missing (required)");
    bool q = gltf_uses_extension(d, "KHR_mesh_quantization");
    const unsigned quantized = GLTF_I8 | GLTF_I8N | GLTF_U8 | GLTF_U8N | GLTF_I16 | GLTF_I16N | GLTF_U16 | GLTF_U16N;
    if (!cJSON_GetObjectItemCaseSensitive(attrs, "POSITION")) {
        gltf_note(d, p->at, "no POSITION: not drawn");
        return true;
    }
    const cJSON *ext, *draco = NULL;
    char ep[140];
    snprintf(ep, sizeof ep, "%s/extensions", p->at);
    if (!gltf_get_object(d, prim, p->at, "extensions", &ext) ||
        (ext && !gltf_get_object(d, ext, ep, "KHR_draco_mesh_compression", &draco)) || (draco && !open_draco(im, p, draco)))
        return false;
    if (!attribute(im, p, attrs, "POSITION", "VEC3", GLTF_F32 | (q ? quantized : 0), &p->pos) ||
        !attribute(im, p, attrs, "NORMAL", "VEC3", GLTF_F32 | (q ? GLTF_I8N | GLTF_I16N : 0), &p->nrm) ||
        !attribute(im, p, attrs, "TANGENT", "VEC4", GLTF_F32 | (q ? GLTF_I8N | GLTF_I16N : 0), &p->tan) ||
        !attribute(im, p, attrs, "TEXCOORD_0", "VEC2", GLTF_F32 | GLTF_U8N | GLTF_U16N | (q ? quantized : 0), &p->uv0) ||
        !attribute(im, p, attrs, "TEXCOORD_1", "VEC2", GLTF_F32 | GLTF_U8N | GLTF_U16N | (q ? quantized : 0), &p->uv1))
        return false;
    if (cJSON_GetObjectItemCaseSensitive(attrs, "COLOR_0")) im->unrendered |= GLTF_UNRENDERED_COLOR;
    if (cJSON_GetObjectItemCaseSensitive(attrs, "JOINTS_0")) im->unrendered |= GLTF_UNRENDERED_SKIN;
    if (p->vertex_count > (1 << 26) || im->vertices + p->vertex_count > SL_IMPORT_MAX_TRIANGLES)
        return gltf_fail(d, p->at, "%d vertices: over the import budget (SL_IMPORT_MAX_TRIANGLES vertices and triangles)",
                         p->vertex_count);
    uint32_t *idx = NULL;
    int n = p->vertex_count;
    char ip[128];
    snprintf(ip, sizeof ip, "%s/indices", p->at);
    if (p->draco_mesh) { /* the Draco mesh's faces: a triangle list whatever the mode says */
        if (!(idx = malloc(sizeof(uint32_t) * 3 * (size_t)(p->draco_faces + 1)))) return gltf_fail(d, ip, "out of memory");
        p->draco->indices(p->draco_mesh, idx);
        n = 3 * p->draco_faces, mode = 4;
    } else if (indices >= 0 && !(idx = gltf_read_indices(d, indices, ip, &n))) {
        return false;
    }
    bool ok = triangles(im, p, (int)mode, idx, n) && morph(im, p, prim, weights, q);
    free(idx);
    if (ok && im->triangles + p->tri_count > SL_IMPORT_MAX_TRIANGLES)
        return gltf_fail(d, p->at, "%lld triangles in all: over the import budget of %d (SL_IMPORT_MAX_TRIANGLES)",
                         im->triangles + p->tri_count, SL_IMPORT_MAX_TRIANGLES);
    return ok;
}

/* Non-finite positions: their triangles dropped (named), the positions zeroed. */
static void drop_nonfinite(gltf_import *im, primitive *p) {
    int bad = 0, kept = 0;
    for (int t = 0; t < p->tri_count; t++) {
        bool ok = true;
        for (int k = 0; k < 3; k++) {
            const float *v = p->pos + 3 * p->tris[3 * t + k];
            ok = ok && isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
        }
        if (!ok) {
            bad++;
            continue;
        }
        memmove(p->tris + 3 * kept++, p->tris + 3 * t, 3 * sizeof(uint32_t));
    }
    for (int i = 0; i < 3 * p->vertex_count; i++)
        if (!isfinite(p->pos[i])) p->pos[i] = 0;
    if (bad) gltf_note(&im->doc, p->at, "%d triangle%s with a non-finite position dropped", bad, bad > 1 ? "s" : "");
    p->tri_count = kept;
}

/* The vertices the triangles use, in the file's order: source[new] = old, map[old] = new. Two
 * primitives sharing one vertex accessor (one per material, say) each keep only their own. */
static int compact(const primitive *p, int *source, uint32_t *map) {
    memset(map, 0xFF, sizeof(uint32_t) * (size_t)p->vertex_count);
    for (int i = 0; i < 3 * p->tri_count; i++) map[p->tris[i]] = 0;
    int n = 0;
    for (int v = 0; v < p->vertex_count; v++)
        if (map[v] == 0) source[n] = v, map[v] = (uint32_t)n++;
    return n;
}

/* The scene mesh data: the used vertices as indexed, or one vertex per corner with flat normals
 * (no NORMAL). */
static bool to_mesh(gltf_import *im, primitive *p, sl_mesh_data *m) {
    bool flat = !p->nrm;
    int *source = flat ? NULL : malloc(sizeof(int) * (size_t)p->vertex_count);
    uint32_t *map = flat ? NULL : malloc(sizeof(uint32_t) * (size_t)p->vertex_count);
    if (!flat && (!source || !map)) return free(source), free(map), gltf_fail(&im->doc, p->at, "out of memory");
    int nv = flat ? 3 * p->tri_count : compact(p, source, map);
    bool ok = sl_mesh_alloc(m, nv, 3 * p->tri_count) && (!p->uv1 || (m->uvs1 = calloc((size_t)nv * 2, sizeof(float))));
    for (int v = 0; ok && v < nv; v++) {
        int s = flat ? (int)p->tris[v] : source[v];
        memcpy(m->positions + 3 * v, p->pos + 3 * s, 3 * sizeof(float));
        if (p->nrm) memcpy(m->normals + 3 * v, p->nrm + 3 * s, 3 * sizeof(float));
        if (p->tan) memcpy(m->tangents + 4 * v, p->tan + 4 * s, 4 * sizeof(float));
        if (p->uv0) memcpy(m->uvs + 2 * v, p->uv0 + 2 * s, 2 * sizeof(float));
        if (p->uv1) memcpy(m->uvs1 + 2 * v, p->uv1 + 2 * s, 2 * sizeof(float));
    }
    for (int i = 0; ok && i < 3 * p->tri_count; i++) m->indices[i] = flat ? (uint32_t)i : map[p->tris[i]];
    free(source), free(map);
    if (!ok) return gltf_fail(&im->doc, p->at, "out of memory (%d vertices)", nv);
    if (flat) /* the face normal at each corner */
        for (int t = 0; t < p->tri_count; t++) {
            const float *a = m->positions + 9 * t, *b = a + 3, *c = a + 6;
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            for (int k = 0; k < 3; k++) memcpy(m->normals + 9 * t + 3 * k, n, sizeof n);
        }
    if (p->tan && p->nrm) sl_mesh_repair_frames(m); /* unit, orthogonal, w = ±1 */
    else sl_mesh_generate_tangents(m);              /* (and unit normals) */
    sl_mesh_compute_bounds(m);
    return true;
}

bool gltf_import_mesh(gltf_import *im, int index, int range[2]) {
    gltf_doc *d = &im->doc;
    if (im->meshes[index][0] != -1) { /* made before (−2: none of it drawable) */
        range[0] = im->meshes[index][0], range[1] = im->meshes[index][1];
        return true;
    }
    char at[48];
    snprintf(at, sizeof at, "/meshes/%d", index);
    const cJSON *mesh = gltf_item(d, "meshes", index), *prims, *weights, *prim;
    const char *name = NULL;
    if (!cJSON_IsObject(mesh)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_array(d, mesh, at, "primitives", &prims) || !gltf_get_array(d, mesh, at, "weights", &weights) ||
        !gltf_get_string(d, mesh, at, "name", &name))
        return false;
    if (!prims || !cJSON_GetArraySize(prims)) gltf_note(d, at, "no primitives: nothing to draw");
    int pi = 0, count = cJSON_GetArraySize(prims);
    range[0] = im->scene->mesh_count, range[1] = 0;
    cJSON_ArrayForEach(prim, prims) {
        primitive p = {0};
        snprintf(p.at, sizeof p.at, "%s/primitives/%d", at, pi);
        int material = -1;
        bool ok = read_primitive(im, prim, weights, &p) && primitive_material(im, prim, p.at, &material);
        if (ok && p.tri_count) drop_nonfinite(im, &p);
        if (ok && p.pos && !p.tri_count) gltf_note(d, p.at, "no triangle left: not drawn");
        sl_mesh_data m = {0};
        int mi = ok && p.tri_count ? gltf_import_material(im, material) : -1;
        if (mi >= 0 && to_mesh(im, &p, &m)) {
            char mesh_name[700];
            if (name && name[0]) snprintf(mesh_name, sizeof mesh_name, "%.250s/%.300s", d->stem, name);
            else snprintf(mesh_name, sizeof mesh_name, "%.250s/mesh%d", d->stem, index);
            if (count > 1) snprintf(mesh_name + strlen(mesh_name), sizeof mesh_name - strlen(mesh_name), "-%d", pi);
            im->triangles += p.tri_count, im->vertices += p.vertex_count;
            if (sl_scene_add_mesh(im->scene, mesh_name, &m, mi) < 0) ok = gltf_fail(d, p.at, "out of memory");
            else range[1]++;
        }
        sl_mesh_free(&m);
        primitive_free(&p);
        if (d->failed) return false;
        pi++;
    }
    im->meshes[index][0] = range[0], im->meshes[index][1] = range[1];
    if (!range[1]) im->meshes[index][0] = -2; /* made: none drawable */
    return true;
}
