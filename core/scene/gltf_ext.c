/* What assimp (Debian's 5.2) does not expose of a glTF 2.0 file, read from its JSON with cJSON:
 * the extensions it requires and uses. A required extension shadelab does not render is an
 * error naming it (glTF 2.0 §3.12: a loader must not load such a file as if it understood it);
 * a used one is a warning. The JSON is the .gltf text, or a .glb's first chunk (glTF 2.0 §4.4,
 * "GLB File Format Specification": 12-byte header, then chunks of length, type "JSON", data). */
#include "log.h"
#include "scene/scene.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Extensions the import renders as their authors meant (the rest: warned or refused). */
static const char *const understood[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                        "KHR_texture_transform", "KHR_materials_ior", "KHR_materials_unlit"};

static bool is_understood(const char *name) {
    for (size_t i = 0; i < sizeof understood / sizeof *understood; i++)
        if (!strcmp(understood[i], name)) return true;
    return false;
}

/* The glTF JSON of the file at path (malloc'd, NUL-terminated), or NULL when it has none. */
static char *gltf_json(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char h[20];
    char *text = NULL;
    size_t n = fread(h, 1, sizeof h, f);
    if (n == sizeof h && !memcmp(h, "glTF", 4)) {
        uint32_t len = (uint32_t)h[12] | (uint32_t)h[13] << 8 | (uint32_t)h[14] << 16 | (uint32_t)h[15] << 24;
        if (!memcmp(h + 16, "JSON", 4) && len > 0 && len < (256u << 20) && (text = malloc((size_t)len + 1))) {
            if (fread(text, 1, len, f) == len) text[len] = 0;
            else free(text), text = NULL;
        }
    } else if (n > 0) {
        fseek(f, 0, SEEK_END);
        long size = ftell(f);
        if (size > 0 && size < (256L << 20) && (text = malloc((size_t)size + 1))) {
            fseek(f, 0, SEEK_SET);
            if (fread(text, 1, (size_t)size, f) == (size_t)size) text[size] = 0;
            else free(text), text = NULL;
        }
    }
    fclose(f);
    return text;
}

/* Lists the names in `arr` that shadelab does not understand into out ("A, B"); their count. */
static int not_understood(const cJSON *arr, char *out, size_t size) {
    int count = 0;
    size_t u = 0;
    out[0] = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, arr) {
        if (!cJSON_IsString(e) || is_understood(e->valuestring)) continue;
        if (u < size) u += snprintf(out + u, size - u, "%s%s", count ? ", " : "", e->valuestring);
        count++;
    }
    return count;
}

void *sl_gltf_read_json(const char *path) {
    char *text = gltf_json(path);
    if (!text) return NULL;
    cJSON *root = cJSON_Parse(text);
    free(text);
    return root;
}

void sl_gltf_free_json(void *json) { cJSON_Delete(json); }

bool sl_gltf_check_extensions(const void *json, const char *path, char *err, size_t err_size) {
    const cJSON *root = json;
    if (!root) return true; /* assimp reports what is wrong with the file */
    char list[1024];
    int n = not_understood(cJSON_GetObjectItemCaseSensitive(root, "extensionsRequired"), list, sizeof list);
    if (n) {
        snprintf(err, err_size, "%s: the file requires glTF extension%s shadelab does not support: %s", path,
                 n > 1 ? "s" : "", list);
        return false;
    }
    if (not_understood(cJSON_GetObjectItemCaseSensitive(root, "extensionsUsed"), list, sizeof list))
        SL_WARN("%s: uses glTF extensions shadelab does not render (ignored, the file shows without them): %s", path,
                list);
    return true;
}

/* Material extensions assimp 5.2 does not expose, for glTF material `index` (assimp keeps the
 * file's material order): KHR_materials_emissive_strength, KHR_materials_ior, KHR_materials_unlit. */
void sl_gltf_material_inputs(const void *json, unsigned index, sl_prop_list *inputs) {
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(json, "materials");
    const cJSON *mat = cJSON_IsArray(mats) ? cJSON_GetArrayItem(mats, (int)index) : NULL;
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(mat, "extensions");
    const cJSON *es = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_emissive_strength"),
                                                       "emissiveStrength");
    if (cJSON_IsNumber(es) && es->valuedouble >= 0 && es->valuedouble <= 1e4)
        sl_prop_set_number(inputs, "emissive_strength", (float)es->valuedouble, 0);
    /* KHR_materials_ior: 1 or more, or exactly 0 (F0 = 1); default 1.5 */
    const cJSON *ior = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_ior"), "ior");
    if (cJSON_IsNumber(ior) && (ior->valuedouble == 0 || (ior->valuedouble >= 1 && ior->valuedouble <= 10)))
        sl_prop_set_number(inputs, "ior", (float)ior->valuedouble, 0);
    else if (ior)
        SL_WARN("material %u: KHR_materials_ior.ior must be 0 or in [1, 10]: ignored (1.5)", index);
    if (cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_unlit")))
        sl_prop_set_bool(inputs, "unlit", true, 0);
}

/* A number member, or fallback when absent or not a finite number. */
static float number_or(const cJSON *obj, const char *key, float fallback) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    return cJSON_IsNumber(n) && isfinite(n->valuedouble) && fabs(n->valuedouble) < 1e6 ? (float)n->valuedouble : fallback;
}

/* Each textureInfo's UV set (texCoord) and KHR_texture_transform (offset, rotation, scale and its
 * texCoord override; the extension's defaults 0, 0, 1), for glTF material `index`, as the
 * material's uv_maps keyed by the standard input the texture feeds. Slots read with UV set 0
 * untransformed get none. A texCoord beyond 1 is read as 0 (*unsupported_texcoord set). */
void sl_gltf_uv_mappings(const void *json, unsigned index, sl_material *m, bool *unsupported_texcoord) {
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(json, "materials");
    const cJSON *mat = cJSON_IsArray(mats) ? cJSON_GetArrayItem(mats, (int)index) : NULL;
    if (!cJSON_IsObject(mat)) return;
    const cJSON *pbr = cJSON_GetObjectItemCaseSensitive(mat, "pbrMetallicRoughness");
    const struct { const cJSON *info; const char *input; } slots[] = {
        {cJSON_GetObjectItemCaseSensitive(pbr, "baseColorTexture"), "base_color_texture"},
        {cJSON_GetObjectItemCaseSensitive(pbr, "metallicRoughnessTexture"), "metallic_roughness_texture"},
        {cJSON_GetObjectItemCaseSensitive(mat, "normalTexture"), "normal_texture"},
        {cJSON_GetObjectItemCaseSensitive(mat, "occlusionTexture"), "occlusion_texture"},
        {cJSON_GetObjectItemCaseSensitive(mat, "emissiveTexture"), "emissive_texture"},
    };
    for (size_t k = 0; k < sizeof slots / sizeof *slots; k++) {
        const cJSON *info = slots[k].info;
        if (!cJSON_IsObject(info)) continue;
        sl_uv_mapping map = {.texcoord = (int)number_or(info, "texCoord", 0), .scale = {1, 1}};
        const cJSON *tt = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(info, "extensions"),
                                                          "KHR_texture_transform");
        bool transformed = false;
        if (cJSON_IsObject(tt)) {
            const cJSON *off = cJSON_GetObjectItemCaseSensitive(tt, "offset");
            const cJSON *scale = cJSON_GetObjectItemCaseSensitive(tt, "scale");
            for (int c = 0; c < 2; c++) {
                const cJSON *o = cJSON_GetArrayItem(off, c), *s = cJSON_GetArrayItem(scale, c);
                if (cJSON_IsArray(off) && cJSON_IsNumber(o) && isfinite(o->valuedouble)) map.offset[c] = (float)o->valuedouble;
                if (cJSON_IsArray(scale) && cJSON_IsNumber(s) && isfinite(s->valuedouble)) map.scale[c] = (float)s->valuedouble;
            }
            map.rotation = number_or(tt, "rotation", 0);
            map.texcoord = (int)number_or(tt, "texCoord", (float)map.texcoord); /* overrides textureInfo's */
            transformed = map.offset[0] != 0 || map.offset[1] != 0 || map.rotation != 0 || map.scale[0] != 1 ||
                          map.scale[1] != 1;
        }
        if (map.texcoord < 0 || map.texcoord > 1) {
            if (unsupported_texcoord) *unsupported_texcoord = true;
            map.texcoord = 0;
        }
        if (map.texcoord == 0 && !transformed) continue;
        sl_uv_mapping *grown = realloc(m->uv_maps, sizeof *grown * (size_t)(m->uv_map_count + 1));
        if (!grown) return;
        m->uv_maps = grown;
        map.input = strdup(slots[k].input);
        if (!map.input) return;
        m->uv_maps[m->uv_map_count++] = map;
    }
}

/* ---- animations (glTF 2.0 §3.11): channels of the first animation, read from the JSON and the
 * binary buffers (assimp 5.2 does not keep the interpolation, nor CUBICSPLINE's tangents) ---- */

static int b64(int c) {
    return c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26 : c >= '0' && c <= '9' ? c - '0' + 52
         : c == '+' ? 62 : c == '/' ? 63 : -1;
}

/* Buffer `index`'s bytes (malloc'd): a .glb's BIN chunk (no uri), a data: URI (base64) or a file
 * beside the glTF. NULL when unreadable or shorter than its byteLength. */
static unsigned char *load_buffer(const cJSON *root, const char *path, int index, size_t *size) {
    const cJSON *buf = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(root, "buffers"), index);
    const cJSON *len = cJSON_GetObjectItemCaseSensitive(buf, "byteLength");
    const cJSON *uri = cJSON_GetObjectItemCaseSensitive(buf, "uri");
    if (!cJSON_IsNumber(len) || len->valuedouble < 1 || len->valuedouble > (double)(1u << 31)) return NULL;
    size_t want = (size_t)len->valuedouble, n = 0;
    unsigned char *out = NULL;
    if (cJSON_IsString(uri) && !strncmp(uri->valuestring, "data:", 5)) {
        const char *comma = strchr(uri->valuestring, ',');
        if (!comma || !strstr(uri->valuestring, ";base64,")) return NULL;
        size_t l = strlen(comma + 1);
        out = malloc(l / 4 * 3 + 3);
        unsigned acc = 0;
        int bits = 0;
        for (const char *c = comma + 1; out && *c && *c != '='; c++) {
            int v = b64((unsigned char)*c);
            if (v < 0) continue;
            acc = acc << 6 | (unsigned)v, bits += 6;
            if (bits >= 8) out[n++] = (unsigned char)(acc >> (bits -= 8));
        }
    } else {
        char file[4200];
        FILE *f = NULL;
        if (cJSON_IsString(uri)) {
            const char *slash = strrchr(path, '/');
            snprintf(file, sizeof file, "%.*s%s", slash ? (int)(slash - path + 1) : 0, path, uri->valuestring);
            f = fopen(file, "rb");
        } else if ((f = fopen(path, "rb"))) { /* GLB: skip the header and the JSON chunk */
            unsigned char h[20];
            uint32_t jl = 0;
            if (fread(h, 1, 20, f) == 20 && !memcmp(h, "glTF", 4) && !memcmp(h + 16, "JSON", 4))
                jl = (uint32_t)h[12] | (uint32_t)h[13] << 8 | (uint32_t)h[14] << 16 | (uint32_t)h[15] << 24;
            unsigned char c[8];
            if (!jl || fseek(f, 20 + (long)jl, SEEK_SET) || fread(c, 1, 8, f) != 8 || memcmp(c + 4, "BIN", 4)) {
                fclose(f);
                return NULL;
            }
        }
        if (!f) return NULL;
        out = malloc(want);
        n = out ? fread(out, 1, want, f) : 0;
        fclose(f);
    }
    if (!out || n < want) {
        free(out);
        return NULL;
    }
    *size = want;
    return out;
}

/* Accessor `index` as floats (count × comps; normalized integer components per §3.11's table
 * for rotations), or NULL when malformed or out of its buffer. */
static float *read_accessor(const cJSON *root, const char *path, int index, int comps, int *count) {
    const cJSON *acc = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(root, "accessors"), index);
    const cJSON *view = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(root, "bufferViews"),
                                           (int)number_or(acc, "bufferView", -1));
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(acc, "type");
    int n = (int)number_or(acc, "count", -1), ct = (int)number_or(acc, "componentType", 0);
    int want = comps == 1 ? !strcmp(cJSON_IsString(type) ? type->valuestring : "", "SCALAR")
             : comps == 3 ? !strcmp(cJSON_IsString(type) ? type->valuestring : "", "VEC3")
                          : !strcmp(cJSON_IsString(type) ? type->valuestring : "", "VEC4");
    int csize = ct == 5126 ? 4 : ct == 5122 || ct == 5123 ? 2 : ct == 5120 || ct == 5121 ? 1 : 0;
    if (!view || !want || n < 1 || n > (1 << 24) || !csize) return NULL;
    size_t size = 0;
    unsigned char *bytes = load_buffer(root, path, (int)number_or(view, "buffer", 0), &size);
    if (!bytes) return NULL;
    size_t offset = (size_t)number_or(view, "byteOffset", 0) + (size_t)number_or(acc, "byteOffset", 0);
    size_t stride = (size_t)number_or(view, "byteStride", 0);
    if (!stride) stride = (size_t)(csize * comps);
    float *out = NULL;
    if (offset + stride * (size_t)(n - 1) + (size_t)(csize * comps) <= size && (out = malloc(sizeof(float) * n * comps))) {
        for (int i = 0; i < n; i++)
            for (int c = 0; c < comps; c++) {
                const unsigned char *p = bytes + offset + stride * (size_t)i + (size_t)(csize * c);
                float v = 0;
                if (ct == 5126) memcpy(&v, p, 4);
                else if (ct == 5121) v = p[0] / 255.0f;
                else if (ct == 5120) v = fmaxf((signed char)p[0] / 127.0f, -1.0f);
                else {
                    uint16_t u = (uint16_t)(p[0] | p[1] << 8);
                    v = ct == 5123 ? u / 65535.0f : fmaxf((int16_t)u / 32767.0f, -1.0f);
                }
                out[i * comps + c] = isfinite(v) ? v : 0;
            }
    }
    free(bytes);
    *count = n;
    return out;
}

/* The first animation's channels onto scene nodes (node_map: glTF node → scene node, −1 none),
 * with the animated nodes' rest TRS. Returns false (a warning said why) when nothing is played. */
bool sl_gltf_import_animations(const void *json, const char *path, sl_scene *scene, const int *node_map, int node_count) {
    const cJSON *root = json;
    const cJSON *anims = cJSON_GetObjectItemCaseSensitive(root, "animations");
    const cJSON *anim = cJSON_GetArrayItem(anims, 0);
    if (!cJSON_IsObject(anim)) return false;
    if (cJSON_GetArraySize(anims) > 1)
        SL_WARN("%s: %d animations; the first one is played", path, cJSON_GetArraySize(anims));
    const cJSON *samplers = cJSON_GetObjectItemCaseSensitive(anim, "samplers"), *ch;
    const cJSON *nodes = cJSON_GetObjectItemCaseSensitive(root, "nodes");
    int skipped = 0;
    cJSON_ArrayForEach(ch, cJSON_GetObjectItemCaseSensitive(anim, "channels")) {
        const cJSON *target = cJSON_GetObjectItemCaseSensitive(ch, "target");
        const cJSON *tpath = cJSON_GetObjectItemCaseSensitive(target, "path");
        const cJSON *smp = cJSON_GetArrayItem(samplers, (int)number_or(ch, "sampler", -1));
        int gn = (int)number_or(target, "node", -1);
        const char *p = cJSON_IsString(tpath) ? tpath->valuestring : "";
        int kind = !strcmp(p, "translation") ? SL_ANIM_TRANSLATION : !strcmp(p, "rotation") ? SL_ANIM_ROTATION
                 : !strcmp(p, "scale") ? SL_ANIM_SCALE : -1;
        const cJSON *ip = cJSON_GetObjectItemCaseSensitive(smp, "interpolation");
        const char *is = cJSON_IsString(ip) ? ip->valuestring : "LINEAR";
        int interp = !strcmp(is, "STEP") ? SL_ANIM_STEP : !strcmp(is, "CUBICSPLINE") ? SL_ANIM_CUBICSPLINE
                   : !strcmp(is, "LINEAR") ? SL_ANIM_LINEAR : -1;
        const cJSON *gnode = cJSON_GetArrayItem(nodes, gn);
        if (kind < 0 || interp < 0 || gn < 0 || gn >= node_count || node_map[gn] < 0 || !smp ||
            cJSON_GetObjectItemCaseSensitive(gnode, "matrix")) { /* weights (morph targets) and the rest */
            skipped++;
            continue;
        }
        int comps = kind == SL_ANIM_ROTATION ? 4 : 3, nt = 0, nv = 0;
        float *times = read_accessor(root, path, (int)number_or(smp, "input", -1), 1, &nt);
        float *values = read_accessor(root, path, (int)number_or(smp, "output", -1), comps, &nv);
        bool ok = times && values && nv == nt * (interp == SL_ANIM_CUBICSPLINE ? 3 : 1);
        for (int k = 1; ok && k < nt; k++) ok = times[k] > times[k - 1];
        sl_anim_channel *grown = ok ? realloc(scene->anim_channels, sizeof *grown * (size_t)(scene->anim_channel_count + 1)) : NULL;
        if (!grown) {
            free(times), free(values);
            skipped++;
            continue;
        }
        scene->anim_channels = grown;
        scene->anim_channels[scene->anim_channel_count++] =
            (sl_anim_channel){.node = node_map[gn], .path = kind, .interpolation = interp, .key_count = nt, .times = times, .values = values};
        if (times[nt - 1] > scene->anim_duration) scene->anim_duration = times[nt - 1];
        bool known = false;
        for (int a = 0; a < scene->anim_node_count; a++) known |= scene->anim_nodes[a].node == node_map[gn];
        sl_anim_node *an = known ? NULL : realloc(scene->anim_nodes, sizeof *an * (size_t)(scene->anim_node_count + 1));
        if (an) {
            scene->anim_nodes = an;
            sl_anim_node rest = {.node = node_map[gn], .r = {0, 0, 0, 1}, .s = {1, 1, 1}};
            const cJSON *t = cJSON_GetObjectItemCaseSensitive(gnode, "translation");
            const cJSON *r = cJSON_GetObjectItemCaseSensitive(gnode, "rotation");
            const cJSON *s = cJSON_GetObjectItemCaseSensitive(gnode, "scale");
            for (int c = 0; c < 4; c++) {
                const cJSON *tc = cJSON_GetArrayItem(t, c), *rc = cJSON_GetArrayItem(r, c), *sc = cJSON_GetArrayItem(s, c);
                if (c < 3 && cJSON_IsNumber(tc)) rest.t[c] = (float)tc->valuedouble;
                if (cJSON_IsNumber(rc)) rest.r[c] = (float)rc->valuedouble;
                if (c < 3 && cJSON_IsNumber(sc)) rest.s[c] = (float)sc->valuedouble;
            }
            scene->anim_nodes[scene->anim_node_count++] = rest;
        }
    }
    if (skipped)
        SL_WARN("%s: %d animation channel%s not played (morph target weights, nodes given by a matrix, or malformed)",
                path, skipped, skipped > 1 ? "s" : "");
    return scene->anim_channel_count > 0;
}

int sl_gltf_node_count(const void *json) {
    return cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(json, "nodes"));
}

/* The default scene's root nodes ("scene", else scene 0). */
int sl_gltf_scene_roots(const void *json, int *roots, int max) {
    const cJSON *scenes = cJSON_GetObjectItemCaseSensitive(json, "scenes");
    const cJSON *sc = cJSON_GetArrayItem(scenes, (int)number_or(json, "scene", 0)), *e;
    int n = 0;
    cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(sc, "nodes")) if (n < max && cJSON_IsNumber(e)) roots[n++] = e->valueint;
    return n;
}

/* Node `node`'s children (indices) and its name (NULL when unnamed). */
int sl_gltf_node_children(const void *json, int node, int *children, int max, const char **name) {
    const cJSON *nd = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(json, "nodes"), node), *e;
    const cJSON *nm = cJSON_GetObjectItemCaseSensitive(nd, "name");
    *name = cJSON_IsString(nm) && nm->valuestring[0] ? nm->valuestring : NULL;
    int n = 0;
    cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(nd, "children")) if (n < max && cJSON_IsNumber(e)) children[n++] = e->valueint;
    return n;
}
