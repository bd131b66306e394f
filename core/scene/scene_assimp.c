/* Mesh files assimp reads (PLY, FBX, Collada, 3DS…; glTF has the project's own reader,
 * core/scene/gltf_*.c, and OBJ too, core/scene/obj_reader.c) imported into the scene graph.
 *
 * What comes along: the node hierarchy with its transforms, triangle meshes (positions,
 * normals, UVs, tangents), materials (base colour factor and texture, normal texture,
 * metallic/roughness factors, opacity), lights and cameras.
 *
 * UVs: assimp hands out UVs with v = 0 at the BOTTOM of the image;
 * the scene convention is v = 0 at the top (scene.h), so v becomes 1 − v here. Tangent frames
 * (and normals a file lacks) are the project's own (core/scene/tangents.c), not assimp's.
 *
 * Names: the imported root and its descendants are named "<prefix>/<assimp node name>", with
 * prefix the parent node's name (or the file stem at the top level); lights and cameras
 * "<prefix>/<name>"; materials "<file stem>/<material name>", and a material of that name that
 * already exists (defined in the scene, or imported before) is reused rather than duplicated.
 * Names are made unique with a "#2", "#3"… suffix where needed. */
#include "log.h"
#include "scene/scene.h"
#include <shadelab/input.h>

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/light.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct importer {
    sl_scene *scene;
    const struct aiScene *ai;
    const char *path;
    char stem[256];
    char dir[4096];     /* absolute directory of the file */
    char prefix[512];
    int *mesh_map;      /* ai mesh index → scene mesh index (−1: skipped) */
    int *material_map;  /* ai material index → scene material index */
    const struct aiNode **ai_nodes; /* visited ai nodes … */
    int *scene_nodes;               /* … and the scene nodes made from them */
    int node_count, node_cap;
    char *err;
    size_t err_size;
    unsigned unsupported; /* UNSUPPORTED_* bits: what of the file is not rendered as authored */
    int warned_raw;
} importer;

enum {
    UNSUPPORTED_TEXCOORD1 = 1u << 0,
    UNSUPPORTED_METAL_CHANNEL = 1u << 1,
    UNSUPPORTED_MASK = 1u << 2,
    UNSUPPORTED_UNUSED_3 = 1u << 3, /* was alphaMode BLEND: blended since (alpha_blend) */
    UNSUPPORTED_DOUBLE_SIDED = 1u << 4,
    UNSUPPORTED_SKIN = 1u << 5,
    UNSUPPORTED_MORPH = 1u << 6,
    UNSUPPORTED_ANIMATION = 1u << 7,
};

static bool fail(importer *im, const char *fmt, const char *arg) {
    if (im->err && im->err_size) snprintf(im->err, im->err_size, fmt, im->path, arg);
    return false;
}

/* "base", "base#2", "base#3"… the first one that `taken` does not know. */
static void unique_name(char *out, size_t size, const char *base, const sl_scene *s,
                        int (*taken)(const sl_scene *, const char *)) {
    snprintf(out, size, "%s", base);
    for (int i = 2; taken(s, out) >= 0 && i < INT_MAX; i++) snprintf(out, size, "%s#%d", base, i);
}

static void mat_vec(const float m[16], const float v[3], float w, float out[3]) {
    for (int r = 0; r < 3; r++) out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * w;
}

static void normalize(float v[3]) {
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0 && isfinite(l)) v[0] /= l, v[1] /= l, v[2] /= l;
}

/* ---- materials --------------------------------------------------------------------------- */

/* The texture value for an embedded image (assimp hands them out as "*N"): the image's bytes join the scene under "<file>#image<N>.<format>", the
 * name the renderer decodes it by (sl_scene_find_image). NULL when the image is unusable. */
static const char *embedded_texture(importer *im, const char *ref, char *out, size_t size) {
    const struct aiScene *ai = im->ai;
    long index = -1;
    if (ref[0] == '*') {
        char *end;
        index = strtol(ref + 1, &end, 10);
        if (*end || index < 0 || index >= (long)ai->mNumTextures) index = -1;
    } else { /* assimp also finds embedded images by their file name */
        const char *b = strrchr(ref, '/');
        b = b ? b + 1 : ref;
        for (unsigned i = 0; i < ai->mNumTextures && index < 0; i++) {
            const char *f = ai->mTextures[i]->mFilename.data, *fb = strrchr(f, '/');
            if (ai->mTextures[i]->mFilename.length && !strcmp(fb ? fb + 1 : f, b)) index = i;
        }
    }
    if (index < 0) return NULL;
    const struct aiTexture *t = ai->mTextures[index];
    if (t->mHeight != 0 || !t->pcData || t->mWidth == 0) {
        if (!im->warned_raw++)
            SL_WARN("%s: embedded texture %s is stored as raw texels, which shadelab does not read (skipped)",
                    im->path, ref);
        return NULL;
    }
    char hint[16];
    snprintf(hint, sizeof hint, "%s", t->achFormatHint[0] ? t->achFormatHint : "png");
    for (char *c = hint; *c; c++) *c = (char)(*c >= 'A' && *c <= 'Z' ? *c - 'A' + 'a' : *c);
    if (!strcmp(hint, "jpeg")) snprintf(hint, sizeof hint, "jpg");
    const char *base = strrchr(im->path, '/');
    snprintf(out, size, "%s#image%ld.%s", base ? base + 1 : im->path, index, hint);
    if (!sl_scene_find_image(im->scene, out) && sl_scene_add_image(im->scene, out, t->pcData, t->mWidth) < 0)
        return NULL;
    return out;
}

/* A texture of the material as a texture value: an embedded image's name, or a path the
 * renderer can open (absolute, relative to the mesh file). Records what the importer cannot
 * honour yet (texCoord 1, non-repeat samplers) for the file's summary warning. */
static bool texture_path(importer *im, const struct aiMaterial *mat, enum aiTextureType type,
                         char *out, size_t size) {
    struct aiString p;
    unsigned uv = 0;
    if (aiGetMaterialTextureCount(mat, type) == 0) return false;
    if (aiGetMaterialTexture(mat, type, 0, &p, NULL, &uv, NULL, NULL, NULL, NULL) != aiReturn_SUCCESS)
        return false;
    if (p.length == 0) return false;
    if (uv != 0) im->unsupported |= UNSUPPORTED_TEXCOORD1;
    if (p.data[0] == '*' || im->ai->mNumTextures) {
        char name[1200];
        if (embedded_texture(im, p.data, name, sizeof name)) {
            snprintf(out, size, "%s", name);
            return true;
        }
        if (p.data[0] == '*') return false;
    }
    if (!strncmp(p.data, "data:", 5)) return false; /* a data: URI assimp did not decode */
    if (p.data[0] == '/') snprintf(out, size, "%s", p.data);
    else snprintf(out, size, "%s/%s", im->dir, p.data);
    char why[160]; /* the one pre-check (<shadelab/input.h>): a FIFO or device is named, never opened */
    errno = 0;
    if (sl_input_file_problem(out, why, sizeof why)) {
        if (errno == ENOENT) SL_WARN("%s: texture '%s' not found (%s)", im->path, out, p.data);
        else SL_WARN("%s: texture '%s' (%s) cannot be read: %s", im->path, out, p.data, why);
    }
    return true;
}

static float material_float(const struct aiMaterial *mat, const char *key, unsigned type, unsigned index, float fallback,
                            bool *found) {
    ai_real f;
    unsigned n = 1;
    bool ok = aiGetMaterialFloatArray(mat, key, type, index, &f, &n) == aiReturn_SUCCESS && n == 1 && isfinite(f);
    if (found) *found = ok;
    return ok ? (float)f : fallback;
}

/* The scene material for ai material i, created on first use (files often carry unused
 * defaults); −1 when out of memory. What the asset says is published as standard material
 * inputs (scene.h, sl_material.inputs; names from glTF 2.0), never as a plugin's keys: the app
 * writes them into the keys plugins declare for them. glTF materials are metallic-roughness
 * materials, defaults included (metallic 1, roughness 1); other formats' plain diffuse
 * materials publish only a colour and a texture. */
static int material_for(importer *im, unsigned i) {
    if (i >= im->ai->mNumMaterials) {
        int mi = sl_scene_find_material(im->scene, "default");
        return mi >= 0 ? mi : sl_scene_add_material(im->scene, "default", "lambert");
    }
    if (im->material_map[i] >= 0) return im->material_map[i];
    const struct aiMaterial *mat = im->ai->mMaterials[i];
    struct aiString ainame;
    char name[600];
    if (aiGetMaterialString(mat, AI_MATKEY_NAME, &ainame) == aiReturn_SUCCESS && ainame.length)
        snprintf(name, sizeof name, "%.250s/%.300s", im->stem, ainame.data);
    else
        snprintf(name, sizeof name, "%s/material%u", im->stem, i);
    int existing = sl_scene_find_material(im->scene, name);
    if (existing >= 0) return im->material_map[i] = existing;
    int mi = sl_scene_add_material(im->scene, name, "lambert");
    if (mi < 0) return -1;
    im->material_map[i] = mi;
    sl_material *sm = &im->scene->materials[mi];
    sm->source = strdup(im->path);
    sl_prop_list *in = &sm->inputs;
    struct aiColor4D c;
    if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) == aiReturn_SUCCESS ||
        aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == aiReturn_SUCCESS) {
        float rgb[3] = {c.r, c.g, c.b};
        sl_prop_set_vec(in, "base_color", rgb, 3, 0);
        if (c.a < 1.0f && c.a >= 0.0f) sl_prop_set_number(in, "opacity", c.a, 0);
    }
    char tex[4096 + 1024];
    if (texture_path(im, mat, aiTextureType_BASE_COLOR, tex, sizeof tex) ||
        texture_path(im, mat, aiTextureType_DIFFUSE, tex, sizeof tex))
        sl_prop_set_string(in, "base_color_texture", tex, 0);
    bool has_metal = false, has_rough = false, found;
    float metal = material_float(mat, AI_MATKEY_METALLIC_FACTOR, 1.0f, &has_metal);
    float rough = material_float(mat, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f, &has_rough);
    if (has_metal || has_rough) {
        sl_prop_set_string(in, "brdf", "metallic-roughness", 0);
        sl_prop_set_number(in, "metallic", fminf(fmaxf(metal, 0.0f), 1.0f), 0);
        sl_prop_set_number(in, "roughness", fminf(fmaxf(rough, 0.0f), 1.0f), 0);
        if (texture_path(im, mat, aiTextureType_DIFFUSE_ROUGHNESS, tex, sizeof tex)) {
            sl_prop_set_string(in, "metallic_roughness_texture", tex, 0); /* B = metal, G = rough */
        }
    }
    if (texture_path(im, mat, aiTextureType_NORMALS, tex, sizeof tex)) sl_prop_set_string(in, "normal_texture", tex, 0);
    if (texture_path(im, mat, aiTextureType_LIGHTMAP, tex, sizeof tex)) sl_prop_set_string(in, "occlusion_texture", tex, 0);
    if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_EMISSIVE, &c) == aiReturn_SUCCESS && (c.r > 0 || c.g > 0 || c.b > 0)) {
        float rgb[3] = {c.r, c.g, c.b};
        sl_prop_set_vec(in, "emissive", rgb, 3, 0);
        float strength = material_float(mat, AI_MATKEY_EMISSIVE_INTENSITY, 1.0f, &found);
        if (found && strength != 1.0f) sl_prop_set_number(in, "emissive_strength", strength, 0);
    }
    if (texture_path(im, mat, aiTextureType_EMISSIVE, tex, sizeof tex)) sl_prop_set_string(in, "emissive_texture", tex, 0);
    if (!sl_prop_find(in, "opacity")) {
        float opacity = material_float(mat, AI_MATKEY_OPACITY, 1.0f, &found);
        if (found && opacity < 1.0f && opacity >= 0.0f) sl_prop_set_number(in, "opacity", opacity, 0);
    }
    int two_sided = 0;
    unsigned n = 1;
    if (aiGetMaterialIntegerArray(mat, AI_MATKEY_TWOSIDED, &two_sided, &n) == aiReturn_SUCCESS && two_sided)
        sl_prop_set_bool(in, "double_sided", true, 0);
    return mi;
}

/* ---- meshes ------------------------------------------------------------------------------ */

static int import_mesh(importer *im, unsigned index) {
    const struct aiMesh *am = im->ai->mMeshes[index];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || am->mNumFaces == 0 || am->mNumVertices == 0) {
        SL_WARN("%s: mesh '%s' has no triangles (points or lines only): skipped", im->path, am->mName.data);
        return -1;
    }
    unsigned tris = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++) tris += am->mFaces[f].mNumIndices == 3;
    sl_mesh_data d;
    if (am->mNumVertices > (1u << 26) || tris > (1u << 26) ||
        !sl_mesh_alloc(&d, (int)am->mNumVertices, (int)(3 * tris))) {
        SL_WARN("%s: mesh '%s' is too large (%u vertices): skipped", im->path, am->mName.data, am->mNumVertices);
        return -1;
    }
    for (unsigned v = 0; v < am->mNumVertices; v++) {
        const struct aiVector3D *p = &am->mVertices[v];
        if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z)) {
            SL_WARN("%s: mesh '%s' has a non-finite vertex position (vertex %u): skipped", im->path,
                    am->mName.data, v);
            sl_mesh_free(&d);
            return -1;
        }
        d.positions[3 * v] = p->x, d.positions[3 * v + 1] = p->y, d.positions[3 * v + 2] = p->z;
        if (am->mNormals) {
            d.normals[3 * v] = am->mNormals[v].x;
            d.normals[3 * v + 1] = am->mNormals[v].y;
            d.normals[3 * v + 2] = am->mNormals[v].z;
        }
        if (am->mTextureCoords[0]) {
            d.uvs[2 * v] = am->mTextureCoords[0][v].x;
            d.uvs[2 * v + 1] = 1.0f - am->mTextureCoords[0][v].y; /* bottom-left → top-left origin */
        }
    }
    if (am->mTextureCoords[1]) { /* glTF TEXCOORD_1: kept only where the file has it */
        d.uvs1 = malloc(sizeof(float) * 2 * am->mNumVertices);
        for (unsigned v = 0; d.uvs1 && v < am->mNumVertices; v++) {
            d.uvs1[2 * v] = am->mTextureCoords[1][v].x;
            d.uvs1[2 * v + 1] = 1.0f - am->mTextureCoords[1][v].y;
        }
    }
    if (am->mColors[0]) { /* glTF COLOR_0, OBJ/PLY vertex colours: kept only where the file has them */
        d.colors = malloc(sizeof(float) * 4 * am->mNumVertices);
        for (unsigned v = 0; d.colors && v < am->mNumVertices; v++) {
            d.colors[4 * v] = am->mColors[0][v].r, d.colors[4 * v + 1] = am->mColors[0][v].g;
            d.colors[4 * v + 2] = am->mColors[0][v].b, d.colors[4 * v + 3] = am->mColors[0][v].a;
        }
    }
    uint32_t *ix = d.indices;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *face = &am->mFaces[f];
        if (face->mNumIndices != 3) continue;
        bool ok = true;
        for (int k = 0; k < 3; k++) ok = ok && face->mIndices[k] < am->mNumVertices;
        if (!ok) continue;
        for (int k = 0; k < 3; k++) *ix++ = face->mIndices[k];
    }
    d.index_count = (int)(ix - d.indices);
    /* normals the file lacks (left zero) become area-weighted vertex normals; tangents from the
     * UVs (orthogonal to the normals without UVs) */
    sl_mesh_generate_tangents(&d);
    sl_mesh_compute_bounds(&d);
    char name[600];
    if (am->mName.length) snprintf(name, sizeof name, "%.250s/%.300s", im->stem, am->mName.data);
    else snprintf(name, sizeof name, "%s/mesh%u", im->stem, index);
    int material = material_for(im, am->mMaterialIndex);
    if (material < 0) {
        sl_mesh_free(&d);
        return -1;
    }
    return sl_scene_add_mesh(im->scene, name, &d, material);
}

/* ---- nodes ------------------------------------------------------------------------------- */

static bool import_node(importer *im, const struct aiNode *an, int parent, int depth) {
    if (depth > SL_SCENE_MAX_DEPTH) {
        char msg[64];
        snprintf(msg, sizeof msg, "%d", SL_SCENE_MAX_DEPTH);
        return fail(im, "%s: the node hierarchy is deeper than %s levels", msg);
    }
    char base[1200], name[1300];
    snprintf(base, sizeof base, "%.500s/%.600s", im->prefix, an->mName.length ? an->mName.data : "node");
    unique_name(name, sizeof name, base, im->scene, sl_scene_find_node);
    int ni = sl_scene_add_node(im->scene, name, parent);
    if (ni < 0) return fail(im, "%s: %s", "out of memory");
    const struct aiMatrix4x4 *m = &an->mTransformation; /* row-major */
    float local[16] = {m->a1, m->b1, m->c1, m->d1, m->a2, m->b2, m->c2, m->d2,
                       m->a3, m->b3, m->c3, m->d3, m->a4, m->b4, m->c4, m->d4};
    for (int i = 0; i < 16; i++)
        if (!isfinite(local[i])) return fail(im, "%s: node '%s' has a non-finite transform", an->mName.data);
    memcpy(im->scene->nodes[ni].local, local, sizeof local);
    for (unsigned k = 0; k < an->mNumMeshes; k++) {
        unsigned mi = an->mMeshes[k];
        if (mi >= im->ai->mNumMeshes || im->mesh_map[mi] < 0) continue;
        if (!sl_scene_node_add_mesh(im->scene, ni, im->mesh_map[mi])) return fail(im, "%s: %s", "out of memory");
    }
    if (im->node_count == im->node_cap) {
        int cap = im->node_cap ? 2 * im->node_cap : 64;
        const struct aiNode **a = realloc(im->ai_nodes, sizeof(*a) * (size_t)cap);
        if (!a) return fail(im, "%s: %s", "out of memory");
        im->ai_nodes = a;
        int *s = realloc(im->scene_nodes, sizeof(int) * (size_t)cap);
        if (!s) return fail(im, "%s: %s", "out of memory");
        im->scene_nodes = s;
        im->node_cap = cap;
    }
    im->ai_nodes[im->node_count] = an;
    im->scene_nodes[im->node_count++] = ni;
    for (unsigned c = 0; c < an->mNumChildren; c++)
        if (!import_node(im, an->mChildren[c], ni, depth + 1)) return false;
    return true;
}

/* The world matrix of the scene node made from the ai node called `name` (identity if none). */
static const float *node_world(importer *im, const struct aiString *name) {
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    for (int i = 0; i < im->node_count; i++)
        if (strcmp(im->ai_nodes[i]->mName.data, name->data) == 0)
            return im->scene->nodes[im->scene_nodes[i]].world;
    return identity;
}

/* ---- lights and cameras ------------------------------------------------------------------- */

static bool import_lights(importer *im) {
    for (unsigned i = 0; i < im->ai->mNumLights; i++) {
        const struct aiLight *al = im->ai->mLights[i];
        const char *type = al->mType == aiLightSource_DIRECTIONAL ? "directional"
                         : al->mType == aiLightSource_POINT       ? "point"
                         : al->mType == aiLightSource_SPOT        ? "spot"
                                                                  : NULL;
        if (!type) {
            SL_WARN("%s: light '%s' is of a type shadelab does not import (area/ambient): skipped",
                    im->path, al->mName.data);
            continue;
        }
        char base[1200], name[1300];
        snprintf(base, sizeof base, "%.500s/%.600s", im->prefix, al->mName.length ? al->mName.data : "light");
        unique_name(name, sizeof name, base, im->scene, sl_scene_find_light);
        int li = sl_scene_add_light(im->scene, name, type);
        if (li < 0) return fail(im, "%s: %s", "out of memory");
        sl_light *l = &im->scene->lights[li];
        const float *w = node_world(im, &al->mName);
        float p[3] = {al->mPosition.x, al->mPosition.y, al->mPosition.z};
        float d[3] = {al->mDirection.x, al->mDirection.y, al->mDirection.z};
        mat_vec(w, p, 1.0f, l->position);
        mat_vec(w, d, 0.0f, l->direction);
        normalize(l->direction);
        if (!(fabsf(l->direction[0]) + fabsf(l->direction[1]) + fabsf(l->direction[2]) > 0.5f)) {
            l->direction[0] = 0, l->direction[1] = 0, l->direction[2] = -1;
        }
        /* colour × intensity arrives premultiplied: split it into a unit-max colour and I or E */
        float c[3] = {al->mColorDiffuse.r, al->mColorDiffuse.g, al->mColorDiffuse.b};
        float peak = fmaxf(c[0], fmaxf(c[1], c[2]));
        if (peak > 0.0f && isfinite(peak)) {
            for (int k = 0; k < 3; k++) l->color[k] = fmaxf(c[k], 0.0f) / peak;
            l->intensity = peak;
        } else {
            l->intensity = 0.0f;
        }
        if (al->mType == aiLightSource_SPOT) {
            sl_prop_set_number(&l->props, "cone_angle", (float)(al->mAngleOuterCone * 180.0 / M_PI), 0);
            sl_prop_set_number(&l->props, "inner_cone_angle", (float)(al->mAngleInnerCone * 180.0 / M_PI), 0);
            sl_prop_set_string(&l->props, "falloff", "gltf", 0);
        }
    }
    return true;
}

static bool import_cameras(importer *im) {
    for (unsigned i = 0; i < im->ai->mNumCameras; i++) {
        const struct aiCamera *ac = im->ai->mCameras[i];
        char base[1200], name[1300];
        snprintf(base, sizeof base, "%.500s/%.600s", im->prefix, ac->mName.length ? ac->mName.data : "camera");
        unique_name(name, sizeof name, base, im->scene, sl_scene_find_camera);
        int ci = sl_scene_add_camera(im->scene, name);
        if (ci < 0) return fail(im, "%s: %s", "out of memory");
        sl_camera *c = &im->scene->cameras[ci];
        const float *w = node_world(im, &ac->mName);
        float p[3] = {ac->mPosition.x, ac->mPosition.y, ac->mPosition.z};
        float look[3] = {ac->mLookAt.x, ac->mLookAt.y, ac->mLookAt.z};
        float up[3] = {ac->mUp.x, ac->mUp.y, ac->mUp.z};
        float dir[3];
        mat_vec(w, p, 1.0f, c->position);
        mat_vec(w, look, 0.0f, dir);
        mat_vec(w, up, 0.0f, c->up);
        normalize(dir);
        normalize(c->up);
        for (int k = 0; k < 3; k++) c->target[k] = c->position[k] + dir[k];
        /* assimp documents mHorizontalFOV as the HALF horizontal angle; mAspect = width/height
         * (0 when unknown) */
        double hfov = ac->mHorizontalFOV, aspect = ac->mAspect > 0 ? ac->mAspect : 1.0;
        double vfov = 2.0 * atan(tan(hfov) / aspect);
        vfov *= 180.0 / M_PI;
        if (vfov > 0.5 && vfov < 179.0) c->fov_y_deg = (float)vfov;
        /* orthographic (assimp 5.2: mOrthographicWidth = half width, mAspect = width / height, hfov 0) */
        if (ac->mOrthographicWidth > 0 && isfinite(ac->mOrthographicWidth)) {
            c->orthographic = true;
            c->xmag = ac->mOrthographicWidth;
            c->ymag = (float)(ac->mOrthographicWidth / aspect);
        }
        if (ac->mClipPlaneNear > 0 && isfinite(ac->mClipPlaneNear)) c->znear = ac->mClipPlaneNear;
        if (ac->mClipPlaneFar > c->znear && isfinite(ac->mClipPlaneFar)) c->zfar = ac->mClipPlaneFar;
    }
    return true;
}

/* One warning listing what of the file is not rendered as its author made it. */
static void warn_unsupported(importer *im) {
    for (unsigned i = 0; i < im->ai->mNumMeshes; i++) {
        if (im->ai->mMeshes[i]->mNumBones) im->unsupported |= UNSUPPORTED_SKIN;
        if (im->ai->mMeshes[i]->mNumAnimMeshes) im->unsupported |= UNSUPPORTED_MORPH;
    }
    if (im->ai->mNumAnimations) im->unsupported |= UNSUPPORTED_ANIMATION;
    static const char *const what[] = {
        "texCoord beyond 1 (those textures sample UV set 0)",
        "(unused)",
        "(unused)",
        "(unused)",
        "(unused)",
        "skins (the bind pose is shown)",
        "morph targets (the base shape is shown)",
        "animations (the rest pose is shown)",
    };
    char list[1024] = "";
    size_t u = 0;
    for (unsigned b = 0; b < sizeof what / sizeof *what; b++)
        if ((im->unsupported & (1u << b)) && u < sizeof list)
            u += snprintf(list + u, sizeof list - u, "%s%s", u ? "; " : "", what[b]);
    if (u) SL_WARN("%s: not rendered as authored: %s", im->path, list);
}


/* assimp's file access (every file it opens): the special files it was refused, each warned
 * about once (assimp asks for a file several times) */
typedef struct refused_io {
    struct { dev_t dev; ino_t ino; } refused[8];
    int refused_count;
} refused_io;

static size_t io_read(struct aiFile *f, char *buf, size_t size, size_t count) {
    return fread(buf, size, count, (FILE *)f->UserData);
}
static size_t io_write(struct aiFile *f, const char *buf, size_t size, size_t count) {
    (void)f, (void)buf, (void)size, (void)count;
    return 0;
}
static size_t io_tell(struct aiFile *f) { return (size_t)ftell((FILE *)f->UserData); }
static size_t io_size(struct aiFile *f) {
    struct stat st;
    return fstat(fileno((FILE *)f->UserData), &st) == 0 ? (size_t)st.st_size : 0;
}
static enum aiReturn io_seek(struct aiFile *f, size_t offset, enum aiOrigin origin) {
    int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    return fseek((FILE *)f->UserData, (long)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}
static void io_flush(struct aiFile *f) { (void)f; }
static struct aiFile *io_open(struct aiFileIO *io, const char *name, const char *mode) {
    refused_io *a = (refused_io *)io->UserData;
    const char *path = name;
    if (strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+')) return NULL; /* an importer only reads */
    /* every file assimp opens (the model and the files it names) is
     * refused unless regular, without blocking on a FIFO (<shadelab/input.h>) */
    char why[600];
    int fd = sl_open_input_file(path, why, sizeof why);
    FILE *fp = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!fp) {
        struct stat st;
        bool seen = false;
        if (fd >= 0) close(fd);
        else if (errno == EINVAL && stat(path, &st) == 0) {
            for (int i = 0; i < a->refused_count; i++)
                seen |= a->refused[i].dev == st.st_dev && a->refused[i].ino == st.st_ino;
            if (!seen && a->refused_count < 8) a->refused[a->refused_count].dev = st.st_dev, a->refused[a->refused_count++].ino = st.st_ino;
            if (!seen) SL_WARN("%s", why);
        }
        return NULL;
    }
    struct aiFile *f = calloc(1, sizeof *f);
    if (!f) {
        fclose(fp);
        return NULL;
    }
    f->ReadProc = io_read, f->WriteProc = io_write, f->TellProc = io_tell, f->FileSizeProc = io_size;
    f->SeekProc = io_seek, f->FlushProc = io_flush, f->UserData = (aiUserData)fp;
    return f;
}
static void io_close(struct aiFileIO *io, struct aiFile *f) {
    (void)io;
    if (!f) return;
    fclose((FILE *)f->UserData);
    free(f);
}

/* ---- entry ------------------------------------------------------------------------------- */

bool sl_scene_import_assimp(sl_scene *scene, const char *path, int parent_node, char *err, size_t err_size) {
    if (err && err_size) err[0] = 0;
    importer im = {.scene = scene, .path = path, .err = err, .err_size = err_size};
    if (parent_node < -1 || parent_node >= scene->node_count) return fail(&im, "%s: %s", "invalid parent node");

    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(im.stem, sizeof im.stem, "%s", base);
    char *dot = strrchr(im.stem, '.');
    if (dot && dot != im.stem) *dot = 0;
    char *abs = realpath(path, NULL);
    snprintf(im.dir, sizeof im.dir, "%s", abs ? abs : path);
    free(abs);
    char *slash = strrchr(im.dir, '/');
    if (slash) *slash = 0;
    else snprintf(im.dir, sizeof im.dir, ".");
    snprintf(im.prefix, sizeof im.prefix, "%s", parent_node >= 0 ? scene->nodes[parent_node].name : im.stem);

    struct aiPropertyStore *store = aiCreatePropertyStore();
    if (store) /* drop the point and line primitives SortByPType splits off */
        aiSetImportPropertyInteger(store, AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    /* Only what assimp must do. Normals a file lacks and every tangent frame come from the
     * project's own code (sl_mesh_generate_tangents: area-weighted normals over the indexed
     * triangles, Lengyel tangents), linear in the mesh: assimp's GenSmoothNormals and
     * CalcTangentSpace sort every vertex spatially (SpatialSort), which made a 10 M-triangle
     * binary PLY take 97 s and 3.9 GB (issue 14; tools/import/bench_import.sh measures it). */
    unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                     aiProcess_ValidateDataStructure | aiProcess_FindInvalidData;
    /* binary PLY arrives indexed (its faces index a vertex list): joining identical vertices (a
     * sort of every vertex) finds nothing to join and costs a third of the import (measured on
     * 2 M-triangle glTF files before glTF had its own reader: 25.3 s with it, 16.6 s without) */
    const char *ext = strrchr(path, '.');
    if (ext && !strcasecmp(ext, ".ply")) flags &= ~(unsigned)aiProcess_JoinIdenticalVertices;
    refused_io refused = {0};
    struct aiFileIO io = {.OpenProc = io_open, .CloseProc = io_close, .UserData = (aiUserData)&refused};
    /* progress for large files: what is being read, and how long it took */
    struct stat fst;
    bool large = stat(path, &fst) == 0 && fst.st_size > (16 << 20);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (large) SL_INFO("%s: importing %.1f MB with assimp…", path, fst.st_size / 1048576.0);
    im.ai = aiImportFileExWithProperties(path, flags, &io, store);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    unsigned long long tris = 0;
    for (unsigned i = 0; im.ai && i < im.ai->mNumMeshes; i++) tris += im.ai->mMeshes[i]->mNumFaces;
    if (im.ai && tris > SL_IMPORT_MAX_TRIANGLES) {
        aiReleaseImport(im.ai);
        im.ai = NULL;
        if (store) aiReleasePropertyStore(store);
        char why[200];
        snprintf(why, sizeof why, "%llu triangles, over the import budget of %d (SL_IMPORT_MAX_TRIANGLES, about 3 GB "
                 "with the GPU copy): refused", tris, SL_IMPORT_MAX_TRIANGLES);
        return fail(&im, "%s: %s", why);
    }
    if (large && im.ai) {
        SL_INFO("%s: imported %u meshes, %llu triangles, %u embedded images in %.1f s", path, im.ai->mNumMeshes, tris,
                im.ai->mNumTextures, (t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) * 1e-9);
    }
    if (store) aiReleasePropertyStore(store);
    if (!im.ai) {
        const char *why = aiGetErrorString();
        if (why && strstr(why, "No meshes remaining")) /* assimp's words for: every mesh was dropped */
            return fail(&im, "%s: %s", "no mesh left to draw: every mesh holds points or lines only (shadelab draws "
                                       "triangles) or invalid data such as non-finite positions (assimp: No meshes "
                                       "remaining)");
        return fail(&im, "%s: assimp could not import it: %s", why && why[0] ? why : "unknown error");
    }
    bool ok = true;
    if (!im.ai->mRootNode) ok = fail(&im, "%s: %s", "the file has no scene (no root node)");
    if (ok) {
        im.mesh_map = calloc(im.ai->mNumMeshes + 1, sizeof(int));
        im.material_map = malloc(sizeof(int) * (im.ai->mNumMaterials + 1));
        if (!im.mesh_map || !im.material_map) ok = fail(&im, "%s: %s", "out of memory");
        for (unsigned i = 0; ok && i < im.ai->mNumMaterials; i++) im.material_map[i] = -1;
        for (unsigned i = 0; ok && i < im.ai->mNumMeshes; i++) im.mesh_map[i] = import_mesh(&im, i);
    }
    if (ok) ok = import_node(&im, im.ai->mRootNode, parent_node, 0);
    if (ok) {
        sl_scene_update_transforms(scene);
        ok = import_lights(&im) && import_cameras(&im);
    }
    if (ok) {
        bool any = false;
        for (unsigned i = 0; i < im.ai->mNumMeshes; i++) any = any || im.mesh_map[i] >= 0;
        if (!any && im.ai->mNumLights == 0 && im.ai->mNumCameras == 0)
            SL_WARN("%s: the file contains no triangle meshes", path);
        warn_unsupported(&im);
    }
    free(im.mesh_map);
    free(im.material_map);
    free(im.ai_nodes);
    free(im.scene_nodes);
    aiReleaseImport(im.ai);
    return ok;
}
