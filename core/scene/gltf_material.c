/* glTF materials (glTF 2.0 §3.9) as scene materials, one per material index of the file: the
 * standard material inputs (<shadelab/params.h>, named after glTF's model), textures as texture
 * values (a path beside the file, or an embedded image's name "<file>#image<N>.<ext>" that the
 * renderer decodes from memory), each texture's sampler, and each slot's UV set and
 * KHR_texture_transform. Material i of the file is scene material im->materials[i]; two materials
 * with one name stay two ("name#2"), which is what keeps extension values on their material. */
#include "log.h"
#include "scene/gltf.h"
#include <shadelab/input.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- images, samplers, textures ------------------------------------------------------------ */

static const char *image_extension(const char *mime, const unsigned char *data, size_t size) {
    if (mime && !strcmp(mime, "image/jpeg")) return "jpg";
    if (mime && !strcmp(mime, "image/png")) return "png";
    if (mime && !strcmp(mime, "image/webp")) return "webp";
    if (size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF) return "jpg";
    if (size >= 12 && !memcmp(data, "RIFF", 4) && !memcmp(data + 8, "WEBP", 4)) return "webp";
    return "png";
}

/* An image held in memory (a bufferView or a data: URI) under "<file>#image<N>.<ext>". */
static bool embedded_image(gltf_import *im, int index, const char *mime, const unsigned char *data, size_t size,
                           char *out, size_t out_size) {
    const char *base = strrchr(im->doc.path, '/');
    snprintf(out, out_size, "%s#image%d.%s", base ? base + 1 : im->doc.path, index, image_extension(mime, data, size));
    if (sl_scene_find_image(im->scene, out)) return true;
    if (sl_scene_add_image(im->scene, out, data, size) < 0) return gltf_fail(&im->doc, NULL, "out of memory");
    return true;
}

/* Image `index` (§3.8.4) as a texture value into out; false after gltf_fail. */
static bool image_value(gltf_import *im, int index, char *out, size_t size) {
    gltf_doc *d = &im->doc;
    char at[48];
    snprintf(at, sizeof at, "/images/%d", index);
    const cJSON *img = gltf_item(d, "images", index);
    const char *uri = NULL, *mime = NULL;
    int view = -1;
    if (!cJSON_IsObject(img)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_string(d, img, at, "uri", &uri) || !gltf_get_string(d, img, at, "mimeType", &mime) ||
        !gltf_get_index(d, img, at, "bufferView", "bufferViews", false, &view))
        return false;
    if ((uri != NULL) == (view >= 0)) return gltf_fail(d, at, "must have exactly one of uri and bufferView");
    if (view >= 0) {
        const unsigned char *bytes;
        size_t len, stride;
        if (!mime) return gltf_fail(d, at, "mimeType is required with a bufferView");
        return gltf_buffer_view(d, view, &bytes, &len, &stride) && embedded_image(im, index, mime, bytes, len, out, size);
    }
    if (!strncmp(uri, "data:", 5)) {
        size_t len = 0;
        unsigned char *bytes = gltf_data_uri(uri, &len);
        char p[64];
        snprintf(p, sizeof p, "%s/uri", at);
        if (!bytes || !len) return free(bytes), gltf_fail(d, p, "not a base64 data: URI");
        const char *semi = strchr(uri, ';');
        char m[64];
        snprintf(m, sizeof m, "%.*s", semi ? (int)(semi - uri - 5) : 0, uri + 5);
        bool ok = embedded_image(im, index, m, bytes, len, out, size);
        free(bytes);
        return ok;
    }
    if (!gltf_uri_path(d, uri, out, size)) {
        char p[64];
        snprintf(p, sizeof p, "%s/uri", at);
        return gltf_fail(d, p, "\"%.200s\" is not a relative file reference shadelab reads", uri);
    }
    char why[160]; /* the one pre-check (<shadelab/input.h>): a FIFO or device is named, never opened */
    errno = 0;
    if (sl_input_file_problem(out, why, sizeof why)) {
        if (errno == ENOENT) SL_WARN("%s: texture '%s' not found (%s)", d->path, out, uri);
        else SL_WARN("%s: texture '%s' (%s) cannot be read: %s", d->path, out, uri, why);
    }
    return true;
}

/* Checks a sampler enum against the values glTF allows; 0 (renderer default) and a note if not. */
static int sampler_enum(gltf_doc *d, const cJSON *smp, const char *at, const char *key, const int *allowed, int n,
                        int fallback) {
    long long v = fallback;
    if (!gltf_get_int(d, smp, at, key, -(1LL << 31), 1LL << 31, &v)) return -1;
    if (!cJSON_GetObjectItemCaseSensitive(smp, key)) return fallback;
    for (int i = 0; i < n; i++)
        if (v == allowed[i]) return (int)v;
    char p[80];
    snprintf(p, sizeof p, "%s/%s", at, key);
    gltf_note(d, p, "%lld is not a value glTF allows: the default used", v);
    return fallback;
}

/* Records texture `t`'s sampler (§3.8.4.2; OpenGL's enum values) under its texture value. */
static bool record_sampler(gltf_import *im, int sampler, const char *value) {
    static const int wraps[] = {33071, 33648, 10497}, mags[] = {9728, 9729},
                     mins[] = {9728, 9729, 9984, 9985, 9986, 9987};
    sl_texture_sampler smp = {.texture = (char *)value, .wrap_s = 10497, .wrap_t = 10497};
    if (sampler >= 0) {
        char at[48];
        snprintf(at, sizeof at, "/samplers/%d", sampler);
        const cJSON *s = gltf_item(&im->doc, "samplers", sampler);
        if (!cJSON_IsObject(s)) return gltf_fail(&im->doc, at, "must be an object");
        smp.wrap_s = sampler_enum(&im->doc, s, at, "wrapS", wraps, 3, 10497);
        smp.wrap_t = sampler_enum(&im->doc, s, at, "wrapT", wraps, 3, 10497);
        smp.mag_filter = sampler_enum(&im->doc, s, at, "magFilter", mags, 2, 0);
        smp.min_filter = sampler_enum(&im->doc, s, at, "minFilter", mins, 6, 0);
        if (smp.wrap_s < 0 || smp.wrap_t < 0 || smp.mag_filter < 0 || smp.min_filter < 0) return false;
    }
    const sl_texture_sampler *known = sl_scene_find_sampler(im->scene, value);
    if (known && (known->wrap_s != smp.wrap_s || known->wrap_t != smp.wrap_t || known->mag_filter != smp.mag_filter ||
                  known->min_filter != smp.min_filter))
        SL_WARN("%s: texture %s is used with two different samplers; the first one is used", im->doc.path, value);
    else if (!known && !sl_scene_set_sampler(im->scene, &smp))
        return gltf_fail(&im->doc, NULL, "out of memory");
    return true;
}

/* Texture `t` (§3.8.4) as a texture value; *usable false (noted) when it has no image read.
 * EXT_texture_webp's source wins over the fallback `source` (OpenImageIO decodes WebP). */
static bool texture_value(gltf_import *im, int t, char *out, size_t size, bool *usable) {
    gltf_doc *d = &im->doc;
    char at[48];
    snprintf(at, sizeof at, "/textures/%d", t);
    const cJSON *tex = gltf_item(d, "textures", t);
    int source = -1, sampler = -1;
    *usable = false;
    if (!cJSON_IsObject(tex)) return gltf_fail(d, at, "must be an object");
    const cJSON *ext, *webp = NULL;
    char ep[80], wp[120];
    snprintf(ep, sizeof ep, "%s/extensions", at);
    snprintf(wp, sizeof wp, "%s/EXT_texture_webp", ep);
    if (!gltf_get_index(d, tex, at, "source", "images", false, &source) ||
        !gltf_get_index(d, tex, at, "sampler", "samplers", false, &sampler) || !gltf_get_object(d, tex, at, "extensions", &ext) ||
        (ext && !gltf_get_object(d, ext, ep, "EXT_texture_webp", &webp)) ||
        (webp && !gltf_get_index(d, webp, wp, "source", "images", true, &source)))
        return false;
    if (source < 0) {
        gltf_note(d, at, "no image shadelab reads (an extension's source only): not used");
        return true;
    }
    if (!image_value(im, source, out, size) || !record_sampler(im, sampler, out)) return false;
    *usable = true;
    return true;
}

/* ---- texture slots ------------------------------------------------------------------------ */

/* A textureInfo (§3.9.2.x) at `at`: the texture value as `input`, its UV set and
 * KHR_texture_transform as a uv map of the material. extra: "scale" or "strength" (or NULL),
 * stored as extra_input when present. */
static bool texture_slot(gltf_import *im, int mi, const cJSON *info, const char *at, const char *input,
                         const char *extra, const char *extra_input) {
    gltf_doc *d = &im->doc;
    int index = -1;
    long long texcoord = 0;
    if (!gltf_get_index(d, info, at, "index", "textures", true, &index) ||
        !gltf_get_int(d, info, at, "texCoord", 0, 1 << 20, &texcoord))
        return false;
    char value[4800];
    bool usable;
    if (!texture_value(im, index, value, sizeof value, &usable)) return false;
    if (!usable) return true;
    sl_material *m = &im->scene->materials[mi];
    if (!sl_prop_set_string(&m->inputs, input, value, 0)) return gltf_fail(d, NULL, "out of memory");
    double amount = 1; /* normalTexture.scale, occlusionTexture.strength: stored when given */
    if (extra && !gltf_get_number(d, info, at, extra, &amount)) return false;
    if (extra && cJSON_GetObjectItemCaseSensitive(info, extra)) sl_prop_set_number(&m->inputs, extra_input, (float)amount, 0);
    sl_uv_mapping map = {.texcoord = (int)texcoord, .scale = {1, 1}};
    const cJSON *ext, *tt = NULL;
    if (!gltf_get_object(d, info, at, "extensions", &ext)) return false;
    char ep[160], tp[200];
    snprintf(ep, sizeof ep, "%s/extensions", at);
    snprintf(tp, sizeof tp, "%s/KHR_texture_transform", ep);
    if (ext && !gltf_get_object(d, ext, ep, "KHR_texture_transform", &tt)) return false;
    bool transformed = false;
    if (tt) {
        double rotation = 0;
        if (!gltf_get_numbers(d, tt, tp, "offset", 2, map.offset, NULL) || !gltf_get_numbers(d, tt, tp, "scale", 2, map.scale, NULL) ||
            !gltf_get_number(d, tt, tp, "rotation", &rotation) || !gltf_get_int(d, tt, tp, "texCoord", 0, 1 << 20, &texcoord))
            return false;
        map.rotation = (float)rotation, map.texcoord = (int)texcoord; /* the extension's texCoord overrides */
        transformed = map.offset[0] != 0 || map.offset[1] != 0 || map.rotation != 0 || map.scale[0] != 1 || map.scale[1] != 1;
    }
    if (map.texcoord > 1) {
        im->unrendered |= GLTF_UNRENDERED_TEXCOORD2;
        map.texcoord = 0;
    }
    if (map.texcoord == 0 && !transformed) return true;
    sl_uv_mapping *grown = realloc(m->uv_maps, sizeof *grown * (size_t)(m->uv_map_count + 1));
    if (!grown) return gltf_fail(d, NULL, "out of memory");
    m->uv_maps = grown;
    if (!(map.input = strdup(input))) return gltf_fail(d, NULL, "out of memory");
    m->uv_maps[m->uv_map_count++] = map;
    return true;
}

/* The object member `key` of obj as a textureInfo slot, if present. */
static bool slot(gltf_import *im, int mi, const cJSON *obj, const char *at, const char *key, const char *input,
                 const char *extra, const char *extra_input) {
    const cJSON *info;
    if (!gltf_get_object(&im->doc, obj, at, key, &info)) return false;
    if (!info) return true;
    char p[160];
    snprintf(p, sizeof p, "%s/%s", at, key);
    return texture_slot(im, mi, info, p, input, extra, extra_input);
}

/* ---- material properties -------------------------------------------------------------------- */

/* A number in [lo, hi] (default when absent); clamped with a note when outside. */
static bool factor(gltf_doc *d, const cJSON *obj, const char *at, const char *key, double lo, double hi, double *v) {
    if (!gltf_get_number(d, obj, at, key, v)) return false;
    if (*v < lo || *v > hi) {
        char p[160];
        snprintf(p, sizeof p, "%s/%s", at, key);
        gltf_note(d, p, "%g is outside [%g, %g]: clamped", *v, lo, hi);
        *v = fmin(fmax(*v, lo), hi);
    }
    return true;
}

/* pbrMetallicRoughness (§3.9.2) and the alpha, emission and side members. */
static bool core_inputs(gltf_import *im, int mi, const cJSON *mat, const char *at) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *pbr;
    char pp[96];
    snprintf(pp, sizeof pp, "%s/pbrMetallicRoughness", at);
    float base[4] = {1, 1, 1, 1}, emissive[3] = {0, 0, 0};
    double metal = 1, rough = 1, cutoff = 0.5;
    const char *mode = "OPAQUE";
    bool double_sided = false;
    if (!gltf_get_object(d, mat, at, "pbrMetallicRoughness", &pbr) ||
        !gltf_get_numbers(d, pbr, pp, "baseColorFactor", 4, base, NULL) || !factor(d, pbr, pp, "metallicFactor", 0, 1, &metal) ||
        !factor(d, pbr, pp, "roughnessFactor", 0, 1, &rough) || !gltf_get_numbers(d, mat, at, "emissiveFactor", 3, emissive, NULL) ||
        !gltf_get_string(d, mat, at, "alphaMode", &mode) || !factor(d, mat, at, "alphaCutoff", 0, 1, &cutoff) ||
        !gltf_get_bool(d, mat, at, "doubleSided", &double_sided))
        return false;
    for (int c = 0; c < 4; c++) base[c] = fminf(fmaxf(base[c], 0.0f), 1.0f);
    sl_prop_set_vec(in, "base_color", base, 3, 0);
    if (base[3] < 1.0f) sl_prop_set_number(in, "opacity", base[3], 0);
    sl_prop_set_string(in, "brdf", "metallic-roughness", 0);
    sl_prop_set_number(in, "metallic", (float)metal, 0);
    sl_prop_set_number(in, "roughness", (float)rough, 0);
    if (emissive[0] > 0 || emissive[1] > 0 || emissive[2] > 0) sl_prop_set_vec(in, "emissive", emissive, 3, 0);
    if (!strcmp(mode, "MASK")) sl_prop_set_number(in, "alpha_cutoff", (float)cutoff, 0); /* cut out by the core */
    else if (!strcmp(mode, "BLEND")) sl_prop_set_bool(in, "alpha_blend", true, 0);        /* sorted and blended */
    else if (strcmp(mode, "OPAQUE")) return gltf_fail(d, at, "alphaMode \"%.20s\" is not OPAQUE, MASK or BLEND", mode);
    if (double_sided) sl_prop_set_bool(in, "double_sided", true, 0);
    return slot(im, mi, pbr, pp, "baseColorTexture", "base_color_texture", NULL, NULL) &&
           slot(im, mi, pbr, pp, "metallicRoughnessTexture", "metallic_roughness_texture", NULL, NULL) &&
           slot(im, mi, mat, at, "normalTexture", "normal_texture", "scale", "normal_scale") &&
           slot(im, mi, mat, at, "occlusionTexture", "occlusion_texture", "strength", "occlusion_strength") &&
           slot(im, mi, mat, at, "emissiveTexture", "emissive_texture", NULL, NULL);
}

/* KHR_materials_clearcoat: the coat's factor, roughness and textures; a factor of 0 (the
 * default) is no coat at all, whatever the textures say. */
static bool clearcoat_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *e;
    char p[160];
    snprintf(p, sizeof p, "%s/KHR_materials_clearcoat", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_clearcoat", &e)) return false;
    double weight = 0, rough = 0;
    if (!e || !factor(d, e, p, "clearcoatFactor", 0, 1, &weight) || !factor(d, e, p, "clearcoatRoughnessFactor", 0, 1, &rough))
        return e == NULL;
    if (weight == 0) return true;
    sl_prop_set_number(in, "clearcoat", (float)weight, 0);
    sl_prop_set_number(in, "clearcoat_roughness", (float)rough, 0);
    return slot(im, mi, e, p, "clearcoatTexture", "clearcoat_texture", NULL, NULL) &&
           slot(im, mi, e, p, "clearcoatRoughnessTexture", "clearcoat_roughness_texture", NULL, NULL) &&
           slot(im, mi, e, p, "clearcoatNormalTexture", "clearcoat_normal_texture", "scale", "clearcoat_normal_scale");
}

/* KHR_materials_specular: the strength and F0 colour of the dielectric's reflection; values
 * that are the defaults (1, [1, 1, 1]) are not published, so such a material pays nothing. */
static bool specular_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *e;
    char p[160];
    snprintf(p, sizeof p, "%s/KHR_materials_specular", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_specular", &e)) return false;
    if (!e) return true;
    double strength = 1;
    float colour[3] = {1, 1, 1};
    if (!factor(d, e, p, "specularFactor", 0, 1, &strength) || !gltf_get_numbers(d, e, p, "specularColorFactor", 3, colour, NULL))
        return false;
    for (int c = 0; c < 3; c++)
        if (!(colour[c] >= 0 && colour[c] <= 1e4)) { /* unbounded above by the schema; F0 is clamped to 1 */
            gltf_note(d, p, "specularColorFactor[%d] %g is not in [0, 1e4]: 1 used", c, colour[c]);
            colour[c] = 1;
        }
    if (strength != 1) sl_prop_set_number(in, "specular", (float)strength, 0);
    if (colour[0] != 1 || colour[1] != 1 || colour[2] != 1) sl_prop_set_vec(in, "specular_color", colour, 3, 0);
    return slot(im, mi, e, p, "specularTexture", "specular_texture", NULL, NULL) &&
           slot(im, mi, e, p, "specularColorTexture", "specular_color_texture", NULL, NULL);
}

/* KHR_materials_sheen: a black sheenColorFactor (the default) is no sheen at all. */
static bool sheen_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *e;
    char p[160];
    snprintf(p, sizeof p, "%s/KHR_materials_sheen", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_sheen", &e)) return false;
    if (!e) return true;
    double rough = 0;
    float colour[3] = {0, 0, 0};
    if (!gltf_get_numbers(d, e, p, "sheenColorFactor", 3, colour, NULL) || !factor(d, e, p, "sheenRoughnessFactor", 0, 1, &rough))
        return false;
    for (int c = 0; c < 3; c++) colour[c] = fminf(fmaxf(colour[c], 0.0f), 1.0f); /* NaN compares false: 0 */
    if (colour[0] == 0 && colour[1] == 0 && colour[2] == 0) return true;
    sl_prop_set_vec(in, "sheen_color", colour, 3, 0);
    sl_prop_set_number(in, "sheen_roughness", (float)rough, 0);
    return slot(im, mi, e, p, "sheenColorTexture", "sheen_color_texture", NULL, NULL) &&
           slot(im, mi, e, p, "sheenRoughnessTexture", "sheen_roughness_texture", NULL, NULL);
}

/* KHR_materials_transmission: the factor and its texture; a factor of 0 (the default) is an
 * opaque material, whatever the texture says. */
static bool transmission_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    const cJSON *e;
    char p[160];
    snprintf(p, sizeof p, "%s/KHR_materials_transmission", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_transmission", &e)) return false;
    double t = 0;
    if (!e || !factor(d, e, p, "transmissionFactor", 0, 1, &t)) return e == NULL;
    if (t == 0) return true;
    sl_prop_set_number(&im->scene->materials[mi].inputs, "transmission", (float)t, 0);
    return slot(im, mi, e, p, "transmissionTexture", "transmission_texture", NULL, NULL);
}

/* KHR_materials_volume: thickness (0, the default, is a thin wall: nothing published), its
 * texture, and the absorption: attenuationDistance (default +inf: none; it must be > 0) and
 * attenuationColor (default white), published only where they absorb. */
static bool volume_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *e;
    char p[160], q[200];
    snprintf(p, sizeof p, "%s/KHR_materials_volume", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_volume", &e)) return false;
    if (!e) return true;
    double thickness = 0, distance = INFINITY;
    float colour[3] = {1, 1, 1};
    bool given = false;
    if (!factor(d, e, p, "thicknessFactor", 0, 1e6, &thickness) || !gltf_get_number(d, e, p, "attenuationDistance", &distance) ||
        !gltf_get_numbers(d, e, p, "attenuationColor", 3, colour, &given))
        return false;
    if (thickness == 0) return true;
    sl_prop_set_number(in, "thickness", (float)thickness, 0);
    if (!slot(im, mi, e, p, "thicknessTexture", "thickness_texture", NULL, NULL)) return false;
    snprintf(q, sizeof q, "%s/attenuationDistance", p);
    if (!(distance > 0)) gltf_note(d, q, "%g must be > 0: no absorption", distance);
    else if (isfinite(distance) && distance <= 1e9) sl_prop_set_number(in, "attenuation_distance", (float)distance, 0);
    for (int c = 0; c < 3; c++) colour[c] = fminf(fmaxf(colour[c], 0.0f), 1.0f); /* NaN compares false: 0 */
    if (given) sl_prop_set_vec(in, "attenuation_color", colour, 3, 0);
    return true;
}

/* KHR_materials_dispersion (20 / Abbe number; 0, the default, is none): published where > 0; ggx
 * applies it to a volume (KHR_materials_volume's thickness), which it builds on. */
static bool dispersion_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    const cJSON *e;
    char p[160];
    snprintf(p, sizeof p, "%s/KHR_materials_dispersion", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_dispersion", &e)) return false;
    double v = 0;
    if (!e || !factor(d, e, p, "dispersion", 0, 100, &v)) return e == NULL;
    if (v > 0) sl_prop_set_number(&im->scene->materials[mi].inputs, "dispersion", (float)v, 0);
    return true;
}

/* KHR_materials_iridescence: a factor of 0 (the default) is no film, nor is a film whose
 * thickness is 0 (the maximum without a thickness texture, both ends with one); the IOR (1.3)
 * and thickness range (100..400 nm) are published where they differ from the defaults. */
static bool iridescence_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *e, *thick_tex;
    char p[160];
    snprintf(p, sizeof p, "%s/KHR_materials_iridescence", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_iridescence", &e)) return false;
    if (!e) return true;
    double w = 0, ior = 1.3, lo = 100, hi = 400;
    if (!factor(d, e, p, "iridescenceFactor", 0, 1, &w) || !factor(d, e, p, "iridescenceIor", 1, 5, &ior) ||
        !factor(d, e, p, "iridescenceThicknessMinimum", 0, 5000, &lo) ||
        !factor(d, e, p, "iridescenceThicknessMaximum", 0, 5000, &hi) ||
        !gltf_get_object(d, e, p, "iridescenceThicknessTexture", &thick_tex))
        return false;
    if (w == 0 || (hi == 0 && (!thick_tex || lo == 0))) return true;
    sl_prop_set_number(in, "iridescence", (float)w, 0);
    if (ior != 1.3) sl_prop_set_number(in, "iridescence_ior", (float)ior, 0);
    if (lo != 100) sl_prop_set_number(in, "iridescence_thickness_minimum", (float)lo, 0);
    if (hi != 400) sl_prop_set_number(in, "iridescence_thickness_maximum", (float)hi, 0);
    return slot(im, mi, e, p, "iridescenceTexture", "iridescence_texture", NULL, NULL) &&
           slot(im, mi, e, p, "iridescenceThicknessTexture", "iridescence_thickness_texture", NULL, NULL);
}

/* KHR_materials_anisotropy: a strength of 0 (the default) is isotropic, whatever else is given
 * (the texture's blue channel multiplies it); the rotation (radians, any finite number) is
 * published reduced to (-2pi, 2pi) where not 0. */
static bool anisotropy_inputs(gltf_import *im, int mi, const cJSON *ext, const char *ep) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *e;
    char p[160];
    snprintf(p, sizeof p, "%s/KHR_materials_anisotropy", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_anisotropy", &e)) return false;
    if (!e) return true;
    double strength = 0, rotation = 0;
    if (!factor(d, e, p, "anisotropyStrength", 0, 1, &strength) || !gltf_get_number(d, e, p, "anisotropyRotation", &rotation))
        return false;
    if (strength == 0) return true;
    sl_prop_set_number(in, "anisotropy_strength", (float)strength, 0);
    rotation = fmod(rotation, 2 * M_PI);
    if (rotation != 0) sl_prop_set_number(in, "anisotropy_rotation", (float)rotation, 0);
    return slot(im, mi, e, p, "anisotropyTexture", "anisotropy_texture", NULL, NULL);
}

/* KHR_materials_emissive_strength, _ior, _unlit and (approximated) _pbrSpecularGlossiness;
 * the layers ggx renders (clearcoat, specular, sheen, transmission, volume, dispersion,
 * iridescence, anisotropy). */
static bool extension_inputs(gltf_import *im, int mi, const cJSON *mat, const char *at) {
    gltf_doc *d = &im->doc;
    sl_prop_list *in = &im->scene->materials[mi].inputs;
    const cJSON *ext, *e;
    char ep[96], p[160];
    snprintf(ep, sizeof ep, "%s/extensions", at);
    if (!gltf_get_object(d, mat, at, "extensions", &ext)) return false;
    if (!ext) return true;
    snprintf(p, sizeof p, "%s/KHR_materials_emissive_strength", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_emissive_strength", &e)) return false;
    double strength = 1, ior = 1.5;
    if (e && !factor(d, e, p, "emissiveStrength", 0, 1e4, &strength)) return false;
    if (e && strength != 1) sl_prop_set_number(in, "emissive_strength", (float)strength, 0);
    snprintf(p, sizeof p, "%s/KHR_materials_ior", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_ior", &e) || (e && !gltf_get_number(d, e, p, "ior", &ior))) return false;
    if (e && ior != 0 && !(ior >= 1 && ior <= 10)) { /* 1 or more, or exactly 0 (F0 = 1) */
        gltf_note(d, p, "ior %g must be 0 or in [1, 10]: 1.5 used", ior);
        ior = 1.5;
    }
    if (e) sl_prop_set_number(in, "ior", (float)ior, 0);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_unlit", &e)) return false;
    if (e) sl_prop_set_bool(in, "unlit", true, 0);
    if (!clearcoat_inputs(im, mi, ext, ep) || !specular_inputs(im, mi, ext, ep) || !sheen_inputs(im, mi, ext, ep) ||
        !transmission_inputs(im, mi, ext, ep) || !volume_inputs(im, mi, ext, ep) ||
        !iridescence_inputs(im, mi, ext, ep) || !anisotropy_inputs(im, mi, ext, ep) ||
        !dispersion_inputs(im, mi, ext, ep))
        return false;
    snprintf(p, sizeof p, "%s/KHR_materials_pbrSpecularGlossiness", ep);
    if (!gltf_get_object(d, ext, ep, "KHR_materials_pbrSpecularGlossiness", &e)) return false;
    if (!e) return true;
    float diffuse[4] = {1, 1, 1, 1};
    double gloss = 1;
    if (!gltf_get_numbers(d, e, p, "diffuseFactor", 4, diffuse, NULL) || !factor(d, e, p, "glossinessFactor", 0, 1, &gloss))
        return false;
    sl_prop_set_vec(in, "base_color", diffuse, 3, 0);
    if (diffuse[3] < 1) sl_prop_set_number(in, "opacity", fmaxf(diffuse[3], 0), 0);
    sl_prop_set_number(in, "metallic", 0, 0);
    sl_prop_set_number(in, "roughness", (float)(1 - gloss), 0);
    return slot(im, mi, e, p, "diffuseTexture", "base_color_texture", NULL, NULL);
}

/* ---- the material ----------------------------------------------------------------------------- */

static bool made_here(const gltf_import *im, int scene_material) {
    for (int i = 0; i < gltf_count(&im->doc, "materials"); i++)
        if (im->materials[i] == scene_material) return true;
    return im->default_material == scene_material;
}

/* "<stem>/<name>"; a material of that name the scene already has (defined in the scene file, or
 * from an earlier import of this file) is reused; one made by this import gets "#2", "#3"… */
static int named_material(gltf_import *im, const char *base, bool *reused) {
    char name[700];
    snprintf(name, sizeof name, "%s", base);
    int existing = sl_scene_find_material(im->scene, name);
    *reused = existing >= 0 && !made_here(im, existing);
    if (*reused) return existing;
    for (int k = 2; existing >= 0; k++) {
        snprintf(name, sizeof name, "%s#%d", base, k);
        existing = sl_scene_find_material(im->scene, name);
    }
    int mi = sl_scene_add_material(im->scene, name, "lambert");
    if (mi >= 0) im->scene->materials[mi].source = strdup(im->doc.path);
    return mi;
}

int gltf_import_material(gltf_import *im, int index) {
    gltf_doc *d = &im->doc;
    char base[600];
    bool reused;
    if (index < 0) { /* the glTF default material: metallic-roughness, white, metal 1, rough 1 */
        if (im->default_material >= 0) return im->default_material;
        snprintf(base, sizeof base, "%.250s/default", d->stem);
        int mi = named_material(im, base, &reused);
        if (mi >= 0 && !reused) {
            float white[3] = {1, 1, 1};
            sl_prop_list *in = &im->scene->materials[mi].inputs;
            sl_prop_set_vec(in, "base_color", white, 3, 0);
            sl_prop_set_string(in, "brdf", "metallic-roughness", 0);
            sl_prop_set_number(in, "metallic", 1, 0);
            sl_prop_set_number(in, "roughness", 1, 0);
        }
        return mi < 0 ? (gltf_fail(d, NULL, "out of memory"), -1) : (im->default_material = mi);
    }
    if (im->materials[index] >= 0) return im->materials[index];
    char at[48];
    snprintf(at, sizeof at, "/materials/%d", index);
    const cJSON *mat = gltf_item(d, "materials", index);
    const char *name = NULL;
    if (!cJSON_IsObject(mat)) return gltf_fail(d, at, "must be an object"), -1;
    if (!gltf_get_string(d, mat, at, "name", &name)) return -1;
    if (name && name[0]) snprintf(base, sizeof base, "%.250s/%.300s", d->stem, name);
    else snprintf(base, sizeof base, "%.250s/material%d", d->stem, index);
    int mi = named_material(im, base, &reused);
    if (mi < 0) return gltf_fail(d, NULL, "out of memory"), -1;
    im->materials[index] = mi;
    if (!reused && !(core_inputs(im, mi, mat, at) && extension_inputs(im, mi, mat, at))) return -1;
    return mi;
}
