/* glTF meshes (glTF 2.0 §3.7.2): each primitive one scene mesh, triangles only. Strips and fans
 * become triangle lists; points and lines are dropped (named); an index past the vertices drops
 * its triangle (named, with the count); a primitive without normals gets flat normals, as §3.7.2.1
 * asks; tangents are the file's, or the project's (core/scene/tangents.c) when it has none; the
 * initial morph weights (node, else mesh) are applied to the base shape and the targets kept with
 * the skin's joints and weights for the GPU (sl_mesh_deform, core/render/deform.c). UVs arrive as written (v = 0 at
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
    float *col;              /* COLOR_0 as RGBA (VEC3: a = 1), or NULL */
    /* morph targets (§3.7.2.2): target_count × vertex_count × 3 displacements (NULL: no target
     * has the attribute); skins (§3.7.3): `influences` joints and weights per vertex (or 0) */
    int target_count;
    float *tpos, *tnrm, *ttan;
    int influences;
    float *joints, *jweights;
    bool is_target;          /* a morph target: its attributes are members of p->at itself */
    uint32_t *tris;          /* 3 per triangle */
    int tri_count;
    /* KHR_draco_mesh_compression: the decoded mesh, its points and the attributes it holds */
    const sl_draco_api *draco;
    void *draco_mesh;
    const cJSON *draco_attrs;
    int draco_points, draco_faces;
} primitive;

static void primitive_free(primitive *p) {
    free(p->pos), free(p->nrm), free(p->tan), free(p->uv0), free(p->uv1), free(p->col), free(p->tris);
    free(p->tpos), free(p->tnrm), free(p->ttan), free(p->joints), free(p->jweights);
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
    const char *members = p->is_target ? "" : "/attributes";
    snprintf(at, sizeof at, "%s%s", p->at, members);
    int index = -1, count = 0;
    *out = NULL;
    if (!gltf_get_index(&im->doc, attrs, at, name, "accessors", false, &index)) return false;
    if (index < 0) return true;
    snprintf(at, sizeof at, "%s%s/%s", p->at, members, name);
    if (p->draco_mesh && cJSON_GetObjectItemCaseSensitive(p->draco_attrs, name)) {
        if (!draco_attribute(im, p, index, name, type, at, out)) return false;
        count = p->draco_points;
    } else if (!(*out = gltf_read_floats(&im->doc, index, type, allowed, at, &count))) {
        return false;
    }
    if (p->vertex_count && count != p->vertex_count) { /* a failed read hands out nothing */
        free(*out);
        *out = NULL;
        return gltf_fail(&im->doc, at, "%d elements, but POSITION has %d (all attributes of a primitive have one count)",
                         count, p->vertex_count);
    }
    p->vertex_count = count;
    return true;
}

/* COLOR_0 (§3.7.2.1): VEC3 or VEC4 of float, normalized unsigned byte or short, as RGBA in p->col
 * (VEC3: alpha 1); linear, multiplying the base colour (§3.9.2). Another type is refused. */
static bool vertex_colors(gltf_import *im, primitive *p, const cJSON *attrs) {
    gltf_doc *d = &im->doc;
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(attrs, "COLOR_0");
    if (!id) return true;
    const cJSON *acc = cJSON_IsNumber(id) ? gltf_item(d, "accessors", id->valueint) : NULL;
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(acc, "type");
    bool rgb = cJSON_IsString(t) && !strcmp(t->valuestring, "VEC3");
    if (cJSON_IsString(t) && !rgb && strcmp(t->valuestring, "VEC4")) {
        char at[128];
        snprintf(at, sizeof at, "%s/attributes/COLOR_0", p->at);
        return gltf_fail(d, at, "accessor %d is %s: COLOR_0 must be VEC3 or VEC4 (glTF 2.0 §3.7.2.1)", id->valueint,
                         t->valuestring);
    }
    float *c = NULL;
    if (!attribute(im, p, attrs, "COLOR_0", rgb ? "VEC3" : "VEC4", GLTF_F32 | GLTF_U8N | GLTF_U16N, &c)) return false;
    if (!c) return true;
    if (!(p->col = rgb ? malloc(sizeof(float) * 4 * (size_t)p->vertex_count + 1) : c))
        return free(c), gltf_fail(d, p->at, "out of memory for COLOR_0");
    int bad = 0;
    for (int v = 0; v < p->vertex_count; v++)
        for (int k = 0; k < 4; k++) { /* a colour is in [0, 1]; a non-finite float one becomes 1 (named) */
            float x = rgb ? (k < 3 ? c[3 * v + k] : 1.0f) : c[4 * v + k];
            bad += !isfinite(x);
            p->col[4 * v + k] = !isfinite(x) ? 1.0f : x < 0 ? 0.0f : x > 1 ? 1.0f : x;
        }
    if (rgb) free(c);
    if (bad) gltf_note(d, p->at, "%d non-finite COLOR_0 component%s drawn as 1", bad, bad > 1 ? "s" : "");
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

/* Target k's attribute `name` into its slot of *all (target_count × vertex_count × 3, made on
 * first use); absent: the slot stays zero. */
static bool target_attribute(gltf_import *im, primitive *p, primitive *tp, const cJSON *t, int k, const char *name,
                             unsigned allowed, float **all) {
    float *v = NULL;
    if (!attribute(im, tp, t, name, "VEC3", allowed, &v)) return false;
    if (!v) return true;
    size_t n = (size_t)p->vertex_count * 3;
    if (!*all && !(*all = calloc(n * (size_t)p->target_count, sizeof(float)))) return free(v), gltf_fail(&im->doc, tp->at, "out of memory");
    memcpy(*all + n * (size_t)k, v, n * sizeof(float));
    free(v);
    return true;
}

/* The morph targets (§3.7.2.2): each target's POSITION, NORMAL and TANGENT displacements, kept for
 * the GPU (sl_mesh_deform), and the base shape moved by the initial weights (rest_weights). */
static bool morph_targets(gltf_import *im, primitive *p, const cJSON *prim, const float *weights, int weight_count, unsigned q) {
    gltf_doc *d = &im->doc;
    const cJSON *targets, *t;
    if (!gltf_get_array(d, prim, p->at, "targets", &targets)) return false;
    if (!(p->target_count = cJSON_GetArraySize(targets))) return true;
    char at[128];
    snprintf(at, sizeof at, "%s/targets", p->at);
    if (weight_count >= 0 && weight_count != p->target_count)
        return gltf_fail(d, at, "%d targets, but the weights (or the mesh's other primitives) have %d: one per target, "
                         "every primitive alike (§3.7.2.2)", p->target_count, weight_count);
    if ((long long)p->target_count * p->vertex_count > GLTF_MAX_MORPH_VALUES)
        return gltf_fail(d, at, "%d targets of %d vertices: over the %d target vertices shadelab keeps per primitive "
                         "(GLTF_MAX_MORPH_VALUES)", p->target_count, p->vertex_count, GLTF_MAX_MORPH_VALUES);
    const unsigned deltas = GLTF_F32 | (q ? GLTF_I8N | GLTF_I16N | GLTF_I8 | GLTF_I16 : 0);
    int k = 0;
    cJSON_ArrayForEach(t, targets) {
        primitive tp = {.vertex_count = p->vertex_count, .is_target = true};
        snprintf(tp.at, sizeof tp.at, "%s/%d", at, k);
        if (!cJSON_IsObject(t)) return gltf_fail(d, tp.at, "must be an object");
        if (cJSON_GetObjectItemCaseSensitive(t, "COLOR_0")) /* allowed by §3.7.2.2, not applied */
            gltf_note(d, tp.at, "COLOR_0 displacements not applied: vertex colours are drawn unmorphed");
        if (!target_attribute(im, p, &tp, t, k, "POSITION", deltas, &p->tpos) ||
            !target_attribute(im, p, &tp, t, k, "NORMAL", deltas, &p->tnrm) ||
            !target_attribute(im, p, &tp, t, k, "TANGENT", deltas, &p->ttan))
            return false;
        k++;
    }
    size_t n = (size_t)p->vertex_count;
    const float *all[3] = {p->tpos, p->tnrm, p->ttan};
    static const char *const names[3] = {"POSITION", "NORMAL", "TANGENT"};
    for (int a = 0; a < 3; a++)
        for (size_t i = 0; all[a] && i < 3 * n * (size_t)p->target_count; i++)
            if (!isfinite(all[a][i])) {
                snprintf(at, sizeof at, "%s/targets/%zu/%s", p->at, i / (3 * n), names[a]);
                return gltf_fail(d, at, "the displacement of vertex %zu is not finite", i % (3 * n) / 3);
            }
    for (int tk = 0; tk < p->target_count && weights; tk++) { /* the base shape at the initial weights */
        float w = weights[tk];
        for (size_t i = 0; w != 0 && i < 3 * n; i++) {
            size_t o = (size_t)tk * 3 * n + i;
            if (p->tpos) p->pos[i] += w * p->tpos[o];
            if (p->tnrm && p->nrm) p->nrm[i] += w * p->tnrm[o];
            if (p->ttan && p->tan) p->tan[i / 3 * 4 + i % 3] += w * p->ttan[o];
        }
    }
    return true;
}

/* The primitive's joints and weights (JOINTS_n, WEIGHTS_n, §3.7.3.3) for a skin of joint_count
 * joints, checked: pairs of sets, at most SL_MAX_INFLUENCE_SETS, indices below joint_count,
 * weights finite and non-negative, each vertex's summing to more than 0 (normalised to 1, named
 * when off by more than 1e-3). */
static bool skin_attributes(gltf_import *im, primitive *p, const cJSON *attrs, int joint_count) {
    gltf_doc *d = &im->doc;
    int sets = 0;
    while (sets < 16) {
        char jn[16], wn[16];
        snprintf(jn, sizeof jn, "JOINTS_%d", sets), snprintf(wn, sizeof wn, "WEIGHTS_%d", sets);
        bool has_j = cJSON_GetObjectItemCaseSensitive(attrs, jn), has_w = cJSON_GetObjectItemCaseSensitive(attrs, wn);
        if (!has_j && !has_w) break;
        char at[160];
        snprintf(at, sizeof at, "%s/attributes/%s", p->at, has_j ? wn : jn);
        if (!has_j || !has_w) return gltf_fail(d, at, "missing: %s comes with %s (§3.7.3.3)", has_j ? jn : wn, has_j ? wn : jn);
        if (sets == SL_MAX_INFLUENCE_SETS) {
            snprintf(at, sizeof at, "%s/attributes/%s", p->at, jn);
            return gltf_fail(d, at, "shadelab reads at most %d JOINTS/WEIGHTS sets (%d joints per vertex, "
                             "SL_MAX_INFLUENCE_SETS)", SL_MAX_INFLUENCE_SETS, 4 * SL_MAX_INFLUENCE_SETS);
        }
        sets++;
    }
    if (!sets) return true;
    int n = p->vertex_count, k4 = 4 * sets;
    p->influences = k4;
    p->joints = malloc(sizeof(float) * (size_t)n * (size_t)k4);
    p->jweights = malloc(sizeof(float) * (size_t)n * (size_t)k4);
    if (!p->joints || !p->jweights) return gltf_fail(d, p->at, "out of memory");
    for (int set = 0; set < sets; set++) {
        char jn[16], wn[16];
        float *j = NULL, *w = NULL;
        snprintf(jn, sizeof jn, "JOINTS_%d", set), snprintf(wn, sizeof wn, "WEIGHTS_%d", set);
        bool ok = attribute(im, p, attrs, jn, "VEC4", GLTF_U8 | GLTF_U16, &j) &&
                  attribute(im, p, attrs, wn, "VEC4", GLTF_F32 | GLTF_U8N | GLTF_U16N, &w);
        for (int v = 0; ok && v < n; v++)
            for (int c = 0; c < 4; c++) {
                p->joints[(size_t)v * k4 + 4 * set + c] = j[4 * v + c];
                p->jweights[(size_t)v * k4 + 4 * set + c] = w[4 * v + c];
            }
        free(j), free(w);
        if (!ok) return false;
    }
    int renormalised = 0;
    for (int v = 0; v < n; v++) {
        double sum = 0;
        for (int c = 0; c < k4; c++) {
            float jv = p->joints[(size_t)v * k4 + c], wv = p->jweights[(size_t)v * k4 + c];
            char at[160];
            snprintf(at, sizeof at, "%s/attributes/%s_%d", p->at, jv >= joint_count ? "JOINTS" : "WEIGHTS", c / 4);
            if (jv >= joint_count)
                return gltf_fail(d, at, "vertex %d's joint %g is not below the skin's %d joints", v, jv, joint_count);
            if (!isfinite(wv) || wv < 0) return gltf_fail(d, at, "vertex %d's weight %g is not finite and non-negative", v, wv);
            sum += wv;
        }
        char at[160];
        snprintf(at, sizeof at, "%s/attributes/WEIGHTS_0", p->at);
        if (!(sum > 0)) return gltf_fail(d, at, "vertex %d's weights sum to 0: it has no joint", v);
        if (fabs(sum - 1) > 1e-3) renormalised++;
        for (int c = 0; c < k4; c++) p->jweights[(size_t)v * k4 + c] = (float)(p->jweights[(size_t)v * k4 + c] / sum);
    }
    if (renormalised) gltf_note(d, p->at, "the weights of %d vertices do not sum to 1: normalised", renormalised);
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

/* How a node uses the mesh: its initial morph weights (node.weights, else mesh.weights; NULL:
 * zeros; count −1: none given) and the joint count of its skin (0: none). */
typedef struct mesh_use { const float *weights; int weight_count; int joint_count; } mesh_use;

/* Reads the primitive at p->at; false after gltf_fail, true with tri_count 0 when it is dropped. */
static bool read_primitive(gltf_import *im, const cJSON *prim, const mesh_use *use, primitive *p) {
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
    if (!vertex_colors(im, p, attrs)) return false;
    if (cJSON_GetObjectItemCaseSensitive(attrs, "JOINTS_0") && !use->joint_count)
        gltf_note(d, p->at, "JOINTS_0 without a skin on the node drawing it: drawn unskinned");
    if (use->joint_count && !skin_attributes(im, p, attrs, use->joint_count)) return false;
    if (use->joint_count && !p->influences) gltf_note(d, p->at, "no JOINTS_0 under a skinned node: drawn unskinned");
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
    bool ok = triangles(im, p, (int)mode, idx, n) && morph_targets(im, p, prim, use->weights, use->weight_count, q);
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

/* Per-vertex rows of `width` floats for the nv vertices kept (vertex v is source[v], or the
 * corner p->tris[v] when source is NULL); NULL when out of memory. */
static float *gather(const primitive *p, const float *rows, int width, int blocks, const int *source, int nv) {
    float *out = malloc(sizeof(float) * (size_t)width * (size_t)nv * (size_t)blocks + 1);
    for (int b = 0; out && b < blocks; b++)
        for (int v = 0; v < nv; v++) {
            size_t s = source ? (size_t)source[v] : p->tris[v];
            memcpy(out + ((size_t)b * nv + v) * width, rows + ((size_t)b * p->vertex_count + s) * width, sizeof(float) * width);
        }
    return out;
}

/* The primitive's deformation (sl_mesh_deform) for the nv vertices kept. */
static bool deform_of(gltf_import *im, const primitive *p, const int *source, int nv, sl_mesh_deform **out) {
    sl_mesh_deform *d = calloc(1, sizeof *d);
    if (!(*out = d)) return gltf_fail(&im->doc, p->at, "out of memory");
    d->skin = -1, d->target_count = p->target_count, d->influences = p->influences;
    bool ok = true;
    if (p->target_count) {
        ok = (d->weights = calloc((size_t)p->target_count, sizeof(float))) && (d->rest_weights = calloc((size_t)p->target_count, sizeof(float)));
        if (p->tpos) ok = ok && (d->target_positions = gather(p, p->tpos, 3, p->target_count, source, nv));
        if (p->tnrm) ok = ok && (d->target_normals = gather(p, p->tnrm, 3, p->target_count, source, nv));
        if (p->ttan) ok = ok && (d->target_tangents = gather(p, p->ttan, 3, p->target_count, source, nv));
    }
    if (p->influences) {
        float *j = gather(p, p->joints, p->influences, 1, source, nv);
        ok = ok && j && (d->joints = malloc(sizeof(uint16_t) * (size_t)nv * (size_t)p->influences)) &&
             (d->joint_weights = gather(p, p->jweights, p->influences, 1, source, nv));
        for (size_t i = 0; ok && i < (size_t)nv * (size_t)p->influences; i++) d->joints[i] = (uint16_t)j[i];
        free(j);
    }
    return ok || gltf_fail(&im->doc, p->at, "out of memory for its morph targets and joints");
}

/* The scene mesh data: the used vertices as indexed, or one vertex per corner with flat normals
 * (no NORMAL); *deform for a primitive with morph targets or joints (else NULL). */
static bool to_mesh(gltf_import *im, primitive *p, sl_mesh_data *m, sl_mesh_deform **deform) {
    bool flat = !p->nrm;
    int *source = flat ? NULL : malloc(sizeof(int) * (size_t)p->vertex_count);
    uint32_t *map = flat ? NULL : malloc(sizeof(uint32_t) * (size_t)p->vertex_count);
    if (!flat && (!source || !map)) return free(source), free(map), gltf_fail(&im->doc, p->at, "out of memory");
    int nv = flat ? 3 * p->tri_count : compact(p, source, map);
    bool ok = sl_mesh_alloc(m, nv, 3 * p->tri_count) && (!p->uv1 || (m->uvs1 = calloc((size_t)nv * 2, sizeof(float)))) &&
              (!p->col || (m->colors = calloc((size_t)nv * 4, sizeof(float))));
    for (int v = 0; ok && v < nv; v++) {
        int s = flat ? (int)p->tris[v] : source[v];
        memcpy(m->positions + 3 * v, p->pos + 3 * s, 3 * sizeof(float));
        if (p->nrm) memcpy(m->normals + 3 * v, p->nrm + 3 * s, 3 * sizeof(float));
        if (p->tan) memcpy(m->tangents + 4 * v, p->tan + 4 * s, 4 * sizeof(float));
        if (p->uv0) memcpy(m->uvs + 2 * v, p->uv0 + 2 * s, 2 * sizeof(float));
        if (p->uv1) memcpy(m->uvs1 + 2 * v, p->uv1 + 2 * s, 2 * sizeof(float));
        if (p->col) memcpy(m->colors + 4 * v, p->col + 4 * s, 4 * sizeof(float));
    }
    for (int i = 0; ok && i < 3 * p->tri_count; i++) m->indices[i] = flat ? (uint32_t)i : map[p->tris[i]];
    if (!ok) return free(source), free(map), gltf_fail(&im->doc, p->at, "out of memory (%d vertices)", nv);
    if (flat) /* the face normal at each corner */
        for (int t = 0; t < p->tri_count; t++) {
            const float *a = m->positions + 9 * t, *b = a + 3, *c = a + 6;
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            for (int k = 0; k < 3; k++) memcpy(m->normals + 9 * t + 3 * k, n, sizeof n);
        }
    ok = !(p->target_count || p->influences) || deform_of(im, p, flat ? NULL : source, nv, deform);
    free(source), free(map);
    if (!ok) return false;
    if (p->tan && p->nrm) sl_mesh_repair_frames(m); /* unit, orthogonal, w = ±1 */
    else sl_mesh_generate_tangents(m);              /* (and unit normals) */
    sl_mesh_compute_bounds(m);
    return true;
}

/* Whether a primitive of the mesh has morph targets (then each node drawing it gets its own copy). */
static bool has_targets(const cJSON *mesh) {
    const cJSON *prim;
    cJSON_ArrayForEach(prim, cJSON_GetObjectItemCaseSensitive(mesh, "primitives"))
        if (cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(prim, "targets")) > 0) return true;
    return false;
}

/* The initial morph weights (node.weights, else mesh.weights) and the skin's joint count. */
static bool mesh_use_of(gltf_import *im, const cJSON *mesh, const char *at, int node, int skin, mesh_use *use, float **owned) {
    gltf_doc *d = &im->doc;
    char np[48], sp[48];
    snprintf(np, sizeof np, "/nodes/%d", node);
    snprintf(sp, sizeof sp, "/skins/%d", skin);
    const cJSON *w = NULL, *joints = NULL, *e;
    if (node >= 0 && !gltf_get_array(d, gltf_item(d, "nodes", node), np, "weights", &w)) return false;
    const char *wat = w ? np : at;
    if (!w && !gltf_get_array(d, mesh, at, "weights", &w)) return false;
    *use = (mesh_use){.weight_count = w ? cJSON_GetArraySize(w) : -1};
    if (w && use->weight_count) {
        if (!(*owned = malloc(sizeof(float) * (size_t)use->weight_count))) return gltf_fail(d, wat, "out of memory");
        int k = 0;
        cJSON_ArrayForEach(e, w) {
            if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) return gltf_fail(d, wat, "weights/%d is not a finite number", k);
            (*owned)[k++] = (float)e->valuedouble;
        }
        use->weights = *owned;
    }
    if (skin >= 0) {
        const cJSON *sk = gltf_item(d, "skins", skin);
        if (!cJSON_IsObject(sk)) return gltf_fail(d, sp, "must be an object");
        if (!gltf_get_array(d, sk, sp, "joints", &joints)) return false;
        if (!(use->joint_count = cJSON_GetArraySize(joints))) return gltf_fail(d, sp, "joints is missing or empty (required)");
    }
    return true;
}

bool gltf_import_mesh(gltf_import *im, int index, int node, int skin, int range[2]) {
    gltf_doc *d = &im->doc;
    const cJSON *mesh = gltf_item(d, "meshes", index);
    bool deformed = skin >= 0 || has_targets(mesh); /* a copy per node: its own weights and pose */
    if (!deformed && im->meshes[index][0] != -1) { /* made before (−2: none of it drawable) */
        range[0] = im->meshes[index][0], range[1] = im->meshes[index][1];
        return true;
    }
    char at[48];
    snprintf(at, sizeof at, "/meshes/%d", index);
    const cJSON *prims, *prim;
    const char *name = NULL;
    if (!cJSON_IsObject(mesh)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_array(d, mesh, at, "primitives", &prims) || !gltf_get_string(d, mesh, at, "name", &name)) return false;
    mesh_use use;
    float *weights = NULL;
    if (!mesh_use_of(im, mesh, at, node, skin, &use, &weights)) return free(weights), false;
    if (!prims || !cJSON_GetArraySize(prims)) gltf_note(d, at, "no primitives: nothing to draw");
    int pi = 0, count = cJSON_GetArraySize(prims);
    range[0] = im->scene->mesh_count, range[1] = 0;
    cJSON_ArrayForEach(prim, prims) {
        primitive p = {0};
        snprintf(p.at, sizeof p.at, "%s/primitives/%d", at, pi);
        int material = -1;
        bool ok = read_primitive(im, prim, &use, &p) && primitive_material(im, prim, p.at, &material);
        if (ok && p.tri_count) drop_nonfinite(im, &p);
        if (ok && p.pos && !p.tri_count) gltf_note(d, p.at, "no triangle left: not drawn");
        if (ok && p.pos && !p.target_count && use.weight_count > 0)
            gltf_note(d, p.at, "no morph targets, but %d weights: drawn without", use.weight_count);
        if (use.weight_count < 0 && p.pos) use.weight_count = p.target_count; /* every primitive: the same count */
        sl_mesh_data m = {0};
        sl_mesh_deform *deform = NULL;
        int mi = ok && p.tri_count ? gltf_import_material(im, material) : -1;
        if (mi >= 0 && to_mesh(im, &p, &m, &deform)) {
            char mesh_name[700];
            if (name && name[0]) snprintf(mesh_name, sizeof mesh_name, "%.250s/%.300s", d->stem, name);
            else snprintf(mesh_name, sizeof mesh_name, "%.250s/mesh%d", d->stem, index);
            if (count > 1) snprintf(mesh_name + strlen(mesh_name), sizeof mesh_name - strlen(mesh_name), "-%d", pi);
            im->triangles += p.tri_count, im->vertices += p.vertex_count;
            int sm = sl_scene_add_mesh(im->scene, mesh_name, &m, mi);
            if (sm < 0) {
                ok = gltf_fail(d, p.at, "out of memory");
            } else {
                range[1]++;
                if (deform) {
                    deform->node = im->nodes[node];
                    deform->skin = p.influences ? skin : -1; /* the glTF skin until gltf_import_skins */
                    for (int t = 0; t < deform->target_count && use.weights; t++)
                        deform->weights[t] = deform->rest_weights[t] = use.weights[t];
                    im->scene->meshes[sm].deform = deform, deform = NULL;
                }
            }
        }
        sl_mesh_deform_free(deform);
        sl_mesh_free(&m);
        primitive_free(&p);
        if (d->failed) return free(weights), false;
        pi++;
    }
    free(weights);
    if (deformed) return true;
    im->meshes[index][0] = range[0], im->meshes[index][1] = range[1];
    if (!range[1]) im->meshes[index][0] = -2; /* made: none drawable */
    return true;
}
