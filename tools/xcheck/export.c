/* shadelab-xcheck's exporter (export.h). The conversions, derived in docs/xcheck.md:
 *
 *   directional light  Blender sun, strength = E (both the irradiance at normal incidence)
 *   point light        Blender point, power P = 4π·I (Cycles: I = P/4π W/sr), radius 0
 *   spot light         the same point light, its emission times shadelab's fall-off of the
 *                      angle from the axis (a light node tree): Cycles' own spot has a smoothstep
 *                      edge and an extra cos θ, neither of which shadelab's spots have
 *   area light         Blender area light, power P = 4·L·A (Cycles emits radiance P/4A; measured)
 *   lambert            Diffuse BSDF, roughness 0 (Lambert)
 *   ggx                Diffuse BSDF + the specular lobe of a Principled BSDF (GGX, roughness
 *                      √α: Blender's α = roughness²) with a black base colour, "Specular" =
 *                      F0/0.08, which gives Cycles' dielectric Fresnel of that F0 (exact Fresnel)
 *   ggx (metallic-roughness)  Principled BSDF (base, metallic, roughness, specular = F0/0.08)
 *   mirror             Glossy BSDF, sharp
 *   environment        a lat-long EXR in Blender's own orientation (files are read as Blender
 *                      reads them; envmap's procedural sky is evaluated per direction, its sun
 *                      disk drawn for camera rays by the world's nodes and lighting as a
 *                      Sun lamp, so envmap's sun light is not a lamp too),
 *                      yaw as a rotation of the lookup about the up axis
 * Nothing is approximated silently: what differs is a note (xc_export.notes). */
#include "export.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "envmap/io.h"

typedef struct texture_file { char *value; bool data; cJSON *json; } texture_file;

typedef struct ctx {
    sl_app *app;
    const char *dir;
    xc_export *out;
    texture_file *textures; int texture_count;
    char *err; size_t n;
} ctx;

/* ------------------------------------------------------------------------------ helpers -- */

bool xc_mkdirs(const char *path, char *err, size_t n) {
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s", path);
    for (char *p = tmp + 1;; p++) {
        if (*p == '/' || !*p) {
            char c = *p;
            *p = 0;
            if (mkdir(tmp, 0777) != 0 && errno != EEXIST) {
                snprintf(err, n, "%s: cannot create the directory: %s", tmp, strerror(errno));
                return false;
            }
            *p = c;
            if (!c) break;
        }
    }
    return true;
}

/* glTF's metallic-roughness in Cycles, exported or read by Blender's importer: its Burley diffuse is
 * brighter than Lambert at grazing view on rough surfaces */
#define PRINCIPLED_NOTE                                                                                         \
    "approximated: glTF metallic-roughness as Cycles' Principled BSDF (Burley diffuse instead of Lambert x (1 - " \
    "F); Cycles' normalised dielectric Fresnel instead of Schlick's)"

/* Adds `item` to the note "text (items)", one note per text. */
static void note_item(ctx *c, const char *text, const char *item) {
    size_t len = strlen(text);
    for (int i = 0; i < c->out->note_count; i++) {
        char *old = c->out->notes[i];
        if (strncmp(old, text, len) || strncmp(old + len, " (", 2)) continue;
        size_t n = strlen(old) + strlen(item) + 3;
        char *grown = malloc(n);
        if (!grown) return;
        snprintf(grown, n, "%.*s, %s)", (int)(strlen(old) - 1), old, item);
        free(old);
        c->out->notes[i] = grown;
        return;
    }
    char **grown = realloc(c->out->notes, (c->out->note_count + 1) * sizeof *grown);
    if (!grown) return;
    c->out->notes = grown;
    size_t n = len + strlen(item) + 4;
    c->out->notes[c->out->note_count] = malloc(n);
    if (c->out->notes[c->out->note_count]) snprintf(c->out->notes[c->out->note_count++], n, "%s (%s)", text, item);
}

static void note(ctx *c, const char *fmt, ...) {
    char line[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    for (int i = 0; i < c->out->note_count; i++)
        if (!strcmp(c->out->notes[i], line)) return;
    char **grown = realloc(c->out->notes, (c->out->note_count + 1) * sizeof *grown);
    if (!grown) return;
    c->out->notes = grown;
    c->out->notes[c->out->note_count++] = strdup(line);
}

/* Writes bytes to DIR/name and adds them to the export's hash. */
static bool write_file(ctx *c, const char *name, const void *data, size_t size) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", c->dir, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size) {
        snprintf(c->err, c->n, "%s: cannot write: %s", path, strerror(errno));
        if (f) fclose(f);
        return false;
    }
    if (fclose(f) != 0) {
        snprintf(c->err, c->n, "%s: cannot write: %s", path, strerror(errno));
        return false;
    }
    c->out->hash = sl_tool_hash64(name, strlen(name) + 1, c->out->hash);
    c->out->hash = sl_tool_hash64(data, size, c->out->hash);
    return true;
}

/* Writes float RGBA as a 32-bit EXR through OpenImageIO (via envmap's tool library) and hashes
 * the pixels. */
static bool write_exr(ctx *c, const char *name, const float *rgba, int w, int h) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", c->dir, name);
    if (!em_io_write_exr(path, rgba, w, h, "shadelab-xcheck", c->err, c->n)) return false;
    c->out->hash = sl_tool_hash64(name, strlen(name) + 1, c->out->hash);
    c->out->hash = sl_tool_hash64(rgba, (size_t)w * h * 4 * sizeof(float), c->out->hash);
    return true;
}

static const sl_param *global_param(sl_app *app, const char *id) { return sl_params_find(&app->params, id); }

static bool plugin_on(sl_app *app, const char *id) {
    int i = sl_plugins_find(&app->plugins, id);
    return i >= 0 && sl_plugin_enabled(&app->plugins, i);
}

static float global_float(sl_app *app, const char *id, float fallback) {
    const sl_param *p = global_param(app, id);
    return p ? p->value.f[0] : fallback;
}

static const char *enum_name(const sl_param_desc *d, int i) {
    if (!d->enum_values) return "";
    for (int k = 0; d->enum_values[k]; k++)
        if (k == i) return d->enum_values[k];
    return "";
}

static const char *global_enum(sl_app *app, const char *id) {
    const sl_param *p = global_param(app, id);
    return p ? enum_name(&p->desc, p->value.i) : "";
}

/* A light's value of a plugin key (light_params slot); false when no enabled plugin declares it. */
static bool light_key(sl_app *app, int li, const char *key, float out[3], const char **enum_text) {
    const sl_light *L = &app->scene.lights[li];
    sl_param *q = sl_params_find_key(&app->params, SL_SCOPE_LIGHT, key, L->type);
    if (!q || q->desc.light_slot < 0 || q->desc.light_slot > 7) return false;
    int comps = q->desc.type == SL_PARAM_COLOR || q->desc.type == SL_PARAM_VEC3 ? 3 : 1;
    for (int i = 0; i < comps && q->desc.light_slot + i < 8; i++) out[i] = app->light_params[li][q->desc.light_slot + i];
    if (enum_text) *enum_text = q->desc.type == SL_PARAM_ENUM ? enum_name(&q->desc, (int)out[0]) : "";
    return true;
}

/* Whether an enabled plugin (or the core) declares keys for lights of this type. */
static bool light_type_handled(sl_app *app, const char *type) {
    if (!strcmp(type, "directional") || !strcmp(type, "point")) return true;
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope == SL_SCOPE_LIGHT && q->desc.light_type && !strcmp(q->desc.light_type, type) &&
            plugin_on(app, q->owner))
            return true;
    }
    return false;
}

/* The material's model as rendered: its own when an enabled plugin provides it, else lambert. */
static const char *effective_model(sl_app *app, const sl_material *m) {
    for (int c = 0; c < app->plugins.chunk_count; c++) {
        const sl_chunk_reg *ch = &app->plugins.chunks[c];
        if (ch->d.hook == SL_HOOK_SHADING_MODEL && ch->d.name && !strcmp(ch->d.name, m->model) &&
            sl_plugin_enabled(&app->plugins, ch->owner))
            return m->model;
    }
    return "lambert";
}

static const sl_mat_value *mat_value(sl_app *app, int m, const char *key) {
    const sl_mat_value *v = sl_app_material_value(app, m, key);
    return v && v->present ? v : NULL;
}

static float mat_float(sl_app *app, int m, const char *key, float fallback) {
    const sl_mat_value *v = mat_value(app, m, key);
    return v ? v->v.f[0] : fallback;
}

static const char *mat_enum(sl_app *app, int m, const char *key) {
    const sl_mat_value *v = sl_app_material_value(app, m, key);
    if (!v) return "";
    return enum_name(&app->params.items[v->param].desc, v->v.i);
}

static cJSON *vec(const float *v, int count) {
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < count; i++) cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
    return a;
}

/* Column-major 4×4 whose −Z axis is `forward` (unit), +X the given side (made orthogonal; any
 * when NULL or parallel), at `position`. */
static void frame_matrix(const float forward[3], const float *side, const float position[3], float m[16]) {
    float z[3] = {-forward[0], -forward[1], -forward[2]}, x[3], y[3];
    float s[3] = {1, 0, 0};
    if (side) memcpy(s, side, sizeof s);
    for (int attempt = 0; attempt < 2; attempt++) {
        float d = s[0] * z[0] + s[1] * z[1] + s[2] * z[2];
        for (int i = 0; i < 3; i++) x[i] = s[i] - d * z[i];
        float len = sqrtf(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (len > 1e-4f) {
            for (int i = 0; i < 3; i++) x[i] /= len;
            break;
        }
        s[0] = 0, s[1] = 1, s[2] = 0; /* side along the axis: any other */
        if (fabsf(z[1]) > 0.9f) s[0] = 1, s[1] = 0;
    }
    y[0] = z[1] * x[2] - z[2] * x[1];
    y[1] = z[2] * x[0] - z[0] * x[2];
    y[2] = z[0] * x[1] - z[1] * x[0];
    for (int i = 0; i < 3; i++) m[i] = x[i], m[4 + i] = y[i], m[8 + i] = z[i], m[12 + i] = position[i];
    m[3] = m[7] = m[11] = 0, m[15] = 1;
}

/* ----------------------------------------------------------------------------- textures -- */

static void file_extension(const char *path, char *ext, size_t n) {
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    ext[0] = 0;
    if (!dot || (slash && dot < slash) || strlen(dot + 1) >= n) return;
    for (size_t i = 0; dot[1 + i]; i++) ext[i] = (char)(dot[1 + i] >= 'A' && dot[1 + i] <= 'Z' ? dot[1 + i] + 32 : dot[1 + i]), ext[i + 1] = 0;
}

static bool read_whole(const char *path, unsigned char **data, size_t *size, char *err, size_t n) {
    FILE *f = fopen(path, "rb");
    if (!f) { snprintf(err, n, "%s: %s", path, strerror(errno)); return false; }
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    *data = len >= 0 ? malloc((size_t)len + 1) : NULL;
    bool ok = *data && fread(*data, 1, (size_t)len, f) == (size_t)len;
    fclose(f);
    if (!ok) { free(*data); snprintf(err, n, "%s: cannot read", path); return false; }
    *size = (size_t)len;
    return true;
}

/* The texture `value` (a path, an embedded image or a procedural spec) as a file under assets/:
 * {"file", "colorspace", "extension"}. Colour textures are sRGB-decoded where shadelab decodes
 * them (8/16-bit files not tagged linear); data textures are "Non-Color". NULL on failure. */
static cJSON *export_texture(ctx *c, const char *value, bool data) {
    for (int i = 0; i < c->texture_count; i++)
        if (c->textures[i].data == data && !strcmp(c->textures[i].value, value)) return cJSON_Duplicate(c->textures[i].json, 1);
    sl_app *app = c->app;
    char name[64], ext[16] = "";
    const char *colorspace = data ? "Non-Color" : "Linear";
    int id = c->texture_count;
    if (sl_image_is_procedural(value)) {
        sl_image img = {0};
        /* the renderer makes procedural textures 256² (core/render/scene_gpu.c) */
        if (!sl_image_procedural(&img, value, 256, c->err, c->n)) return NULL;
        snprintf(name, sizeof name, "assets/texture%d.exr", id);
        bool ok = write_exr(c, name, img.pixels, img.width, img.height);
        sl_image_free(&img);
        if (!ok) return NULL;
    } else {
        unsigned char *bytes = NULL;
        size_t size = 0;
        const sl_embedded_image *e = sl_scene_find_image(&app->scene, value);
        char *path = NULL;
        if (e) {
            bytes = malloc(e->size);
            if (!bytes) { snprintf(c->err, c->n, "out of memory"); return NULL; }
            memcpy(bytes, e->data, size = e->size);
        } else {
            path = sl_scene_resolve_path(&app->scene, app->opt.data_dir, value, c->err, c->n);
            if (!path || !read_whole(path, &bytes, &size, c->err, c->n)) { free(path); return NULL; }
        }
        file_extension(e ? e->name : path, ext, sizeof ext);
        sl_image info = {0};
        bool ok = sl_image_load_memory(&info, bytes, size, e ? e->name : path, c->err, c->n);
        if (ok && !data) colorspace = info.source_srgb ? "sRGB" : "Linear";
        sl_image_free(&info);
        free(path);
        snprintf(name, sizeof name, "assets/texture%d.%s", id, ext[0] ? ext : "img");
        ok = ok && write_file(c, name, bytes, size);
        free(bytes);
        if (!ok) return NULL;
    }
    cJSON *t = cJSON_CreateObject();
    cJSON_AddStringToObject(t, "file", name);
    cJSON_AddStringToObject(t, "colorspace", colorspace);
    const sl_texture_sampler *s = sl_scene_find_sampler(&app->scene, value);
    const char *extension = "REPEAT";
    if (s && (s->wrap_s == 0x812F || s->wrap_t == 0x812F)) extension = "EXTEND"; /* GL_CLAMP_TO_EDGE */
    if (s && s->wrap_s != s->wrap_t)
        note(c, "approximated: texture %s: wrap modes differ per axis (Blender has one per image)", value);
    if (s && (s->wrap_s == 0x8370 || s->wrap_t == 0x8370))
        note(c, "approximated: texture %s: mirrored repeat is read as repeat", value);
    cJSON_AddStringToObject(t, "extension", extension);
    texture_file *grown = realloc(c->textures, (c->texture_count + 1) * sizeof *grown);
    if (grown) {
        c->textures = grown;
        c->textures[c->texture_count++] = (texture_file){strdup(value), data, cJSON_Duplicate(t, 1)};
    }
    return t;
}

/* A value for the builder: a constant, or {"texture", "factor", "channel"}. */
static cJSON *textured(ctx *c, const char *map, bool data, cJSON *constant, const char *channel, bool factor_given) {
    if (!map) return constant;
    cJSON *t = export_texture(c, map, data);
    if (!t) { cJSON_Delete(constant); return NULL; }
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToObject(o, "texture", t);
    if (channel) cJSON_AddStringToObject(o, "channel", channel);
    if (factor_given) cJSON_AddItemToObject(o, "factor", constant);
    else cJSON_Delete(constant);
    return o;
}

/* ---------------------------------------------------------------------------- materials -- */

static const char *mat_texture(sl_app *app, int m, const char *key) {
    const sl_mat_value *v = mat_value(app, m, key);
    return v && v->str && v->str[0] ? v->str : NULL;
}

/* ggx's material keys that export_ggx maps; every other one it owns (its layers: clear coat,
 * sheen, specular colour, transmission and volume, dispersion, iridescence, anisotropy) is not. */
static const char *const ggx_mapped[] = {"alpha", "roughness", "roughness_map", "specular", "specular_map",
                                         "eta", "fresnel", "ior", "metallic"};

static bool value_is_default(const sl_param *p, const sl_mat_value *v) {
    const sl_value *d = &p->desc.default_value;
    switch (p->desc.type) {
    case SL_PARAM_TEXTURE: return !v->str || !v->str[0];
    case SL_PARAM_BOOL: return v->v.b == d->b;
    case SL_PARAM_INT: case SL_PARAM_ENUM: return v->v.i == d->i;
    default: return !memcmp(v->v.f, d->f, sizeof d->f);
    }
}

/* A layer of ggx set on the material (a key of ggx's, not mapped, given a value other than its
 * default) is not cross-checked: drawn without it in Cycles, it would be compared silently. */
static void note_unmapped_ggx_keys(ctx *c, int m, bool *checked) {
    sl_app *app = c->app;
    const sl_mat_state *ms = &app->materials[m];
    char text[512];
    int n = snprintf(text, sizeof text, "not cross-checked: ggx's layers not mapped to Cycles: ");
    int start = n;
    for (int i = 0; i < ms->count && n < (int)sizeof text; i++) {
        const sl_mat_value *v = &ms->values[i];
        const sl_param *p = &app->params.items[v->param];
        if (!v->present || strcmp(p->owner, "ggx") || value_is_default(p, v)) continue;
        bool mapped = false;
        for (size_t k = 0; k < sizeof ggx_mapped / sizeof *ggx_mapped; k++) mapped |= !strcmp(p->desc.id, ggx_mapped[k]);
        if (!mapped) n += snprintf(text + n, sizeof text - n, "%s%s", n > start ? ", " : "", p->desc.id);
    }
    if (n == start || n >= (int)sizeof text) return;
    note_item(c, text, app->scene.materials[m].name);
    *checked = false;
}

/* The ggx material's lobes. Returns false only on an error (err set). */
static bool export_ggx(ctx *c, int m, cJSON *j, bool *checked) {
    sl_app *app = c->app;
    const char *name = app->scene.materials[m].name;
    const char *fresnel = mat_enum(app, m, "fresnel");
    bool mr = !strcmp(fresnel, "metallic-roughness");
    /* α: roughness² when the material gives roughness (it wins), else alpha, else the surface's 1 */
    const char *rmap = mat_texture(app, m, "roughness_map");
    float alpha = mat_value(app, m, "roughness") ? powf(mat_float(app, m, "roughness", 1), 2)
                  : mat_value(app, m, "alpha") ? mat_float(app, m, "alpha", 1) : 1.0f;
    if (rmap && !mat_value(app, m, "roughness") && mat_value(app, m, "alpha"))
        note(c, "approximated: material %s: alpha is replaced by roughness_map's green channel in shadelab", name);
    float r = sqrtf(alpha);
    cJSON *rough = textured(c, rmap, true, cJSON_CreateNumber(r), "G", mat_value(app, m, "roughness") != NULL);
    if (!rough) return false;
    note_unmapped_ggx_keys(c, m, checked);
    cJSON_AddItemToObject(j, "roughness", rough);
    if (!strcmp(global_enum(app, "ggx.g1_angle"), "half-vector")) {
        note(c, "not cross-checked: ggx.g1_angle=half-vector (not a normalised BRDF; Cycles' GGX has none)");
        *checked = false;
    }
    bool zero_specular = global_param(app, "ggx.zero_specular") && global_param(app, "ggx.zero_specular")->value.b;
    if (mr) {
        cJSON_AddStringToObject(j, "kind", "principled");
        float metallic = mat_float(app, m, "metallic", 0);
        cJSON *met = textured(c, rmap, true, cJSON_CreateNumber(metallic), "B", true);
        if (!met) return false;
        cJSON_AddItemToObject(j, "metallic", met);
        float ior = mat_float(app, m, "ior", 1.5f), f0 = powf((ior - 1) / (ior + 1), 2);
        if (!mat_value(app, m, "ior")) f0 = 0.04f;
        if (f0 / 0.08f > 1) note(c, "approximated: material %s: F0 %.3f above Principled's 0.08 (ior %.2f)", name, f0, ior);
        cJSON_AddNumberToObject(j, "specular_level", fminf(f0 / 0.08f, 1));
        note_item(c, PRINCIPLED_NOTE, name);
        if (zero_specular) {
            note(c, "not cross-checked: ggx.zero_specular with metallic-roughness materials (%s)", name);
            *checked = false;
        }
        return true;
    }
    cJSON_AddStringToObject(j, "kind", zero_specular ? "diffuse" : "diffuse+specular");
    float eta = mat_float(app, m, "eta", 1.0f / 1.5f);
    if (eta > 1) {
        note(c, "not cross-checked: material %s: eta %.3f > 1 (total internal reflection; a Principled BSDF's "
                "dielectric has none)", name, eta);
        *checked = false;
    }
    float f0 = powf((1 - eta) / (1 + eta), 2);
    if (f0 / 0.08f > 1) {
        note(c, "approximated: material %s: F0 %.3f above Principled's 0.08 (eta %.3f): clamped", name, f0, eta);
    }
    cJSON_AddNumberToObject(j, "specular_level", fminf(f0 / 0.08f, 1));
    if (!strcmp(fresnel, "schlick"))
        note_item(c, "approximated: Schlick's Fresnel as Cycles' exact dielectric Fresnel of the same F0", name);
    const char *smap = mat_texture(app, m, "specular_map");
    cJSON *ks = textured(c, smap, true, cJSON_CreateNumber(mat_float(app, m, "specular", 1)), "R",
                         mat_value(app, m, "specular") != NULL);
    if (!ks) return false;
    cJSON_AddItemToObject(j, "specular_weight", ks);
    return true;
}

static bool export_material(ctx *c, int m, cJSON *list, bool *checked) {
    sl_app *app = c->app;
    const sl_material *mat = &app->scene.materials[m];
    const char *model = effective_model(app, mat);
    cJSON *j = cJSON_CreateObject();
    cJSON_AddItemToArray(list, j);
    cJSON_AddStringToObject(j, "name", mat->name);
    *checked = true;
    /* base colour: the map replaces it, or multiplies it when both are given */
    const sl_mat_value *bc = sl_app_material_value(app, m, "base_color");
    float base[3] = {0.8f, 0.8f, 0.8f};
    if (bc) memcpy(base, bc->v.f, sizeof base);
    bool is_mirror = !strcmp(model, "mirror");
    if (is_mirror && !mat_value(app, m, "base_color")) base[0] = base[1] = base[2] = 1;
    cJSON *color = textured(c, mat_texture(app, m, "base_color_map"), false, vec(base, 3), NULL,
                            mat_value(app, m, "base_color") != NULL);
    if (!color) return false;
    cJSON_AddItemToObject(j, "base_color", color);

    bool unlit = mat_value(app, m, "unlit") && mat_value(app, m, "unlit")->v.b;
    if (unlit) {
        cJSON_AddStringToObject(j, "kind", "none");
        cJSON_AddItemToObject(j, "emission", cJSON_Duplicate(color, 1));
    } else if (!strcmp(model, "lambert")) {
        cJSON_AddStringToObject(j, "kind", "diffuse");
    } else if (!strcmp(model, "ggx")) {
        if (!export_ggx(c, m, j, checked)) return false;
    } else if (is_mirror) {
        cJSON_AddStringToObject(j, "kind", "mirror");
    } else {
        char text[256];
        snprintf(text, sizeof text, "not cross-checked: shading model \"%s\" has no Cycles counterpart (drawn as a "
                 "diffuse of its base colour)", model);
        note_item(c, text, mat->name);
        cJSON_AddStringToObject(j, "kind", "diffuse");
        *checked = false;
    }
    const char *nmap = mat_texture(app, m, "normal_map");
    if (nmap && plugin_on(app, "normal-map")) {
        if (strcmp(mat_enum(app, m, "normal_space"), "tangent")) {
            note(c, "not cross-checked: material %s: object-space normal map", mat->name);
            *checked = false;
        }
        float k = global_float(app, "normal-map.strength", 1) * mat_float(app, m, "normal_strength", 1);
        if (fabsf(k - 1) > 1e-6f)
            note(c, "approximated: material %s: normal-map strength %.3g (shadelab scales xy, Blender blends normals)",
                 mat->name, k);
        if (!strcmp(global_enum(app, "normal-map.green"), "directx")) {
            note(c, "not cross-checked: normal-map.green=directx");
            *checked = false;
        }
        cJSON *t = export_texture(c, nmap, true);
        if (!t) return false;
        cJSON *nm = cJSON_AddObjectToObject(j, "normal_map");
        cJSON_AddItemToObject(nm, "texture", t);
        cJSON_AddNumberToObject(nm, "strength", k);
    }
    const sl_mat_value *em = mat_value(app, m, "emissive");
    if (em && !unlit && (em->v.f[0] > 0 || em->v.f[1] > 0 || em->v.f[2] > 0)) {
        float s = mat_float(app, m, "emissive_strength", 1), e[3] = {em->v.f[0] * s, em->v.f[1] * s, em->v.f[2] * s};
        cJSON *emission = textured(c, mat_texture(app, m, "emissive_map"), false, vec(e, 3), NULL, true);
        if (!emission) return false;
        cJSON_AddItemToObject(j, "emission", emission);
    }
    if (mat_texture(app, m, "occlusion_map"))
        note_item(c, "not cross-checked: occlusion maps (shadelab darkens ambient light by them; Cycles traces "
                     "the occlusion itself)", mat->name);
    if (mat_value(app, m, "opacity") && mat_float(app, m, "opacity", 1) < 1) {
        note(c, "not cross-checked: material %s: opacity below 1", mat->name);
        *checked = false;
    }
    if (mat_value(app, m, "alpha_cutoff")) {
        note(c, "not cross-checked: material %s: alpha cut-out", mat->name);
        *checked = false;
    }
    if (mat->uv_map_count > 0) {
        note(c, "not cross-checked: material %s: texture transforms or a second UV set", mat->name);
        *checked = false;
    }
    return true;
}

/* ------------------------------------------------------------------------------- meshes -- */

static bool export_mesh(ctx *c, int mi, cJSON *list) {
    const sl_mesh *mesh = &c->app->scene.meshes[mi];
    const sl_mesh_data *d = &mesh->data;
    size_t nv = (size_t)d->vertex_count, nt = (size_t)d->index_count / 3;
    size_t floats = nv * 8 + nt * 3;
    float *buf = malloc(floats * sizeof *buf);
    if (!buf) { snprintf(c->err, c->n, "out of memory"); return false; }
    memcpy(buf, d->positions, nv * 3 * sizeof *buf);
    memcpy(buf + nv * 3, d->normals, nv * 3 * sizeof *buf);
    for (size_t v = 0; v < nv; v++) {
        buf[nv * 6 + v * 2] = d->uvs ? d->uvs[v * 2] : 0;
        buf[nv * 6 + v * 2 + 1] = d->uvs ? 1 - d->uvs[v * 2 + 1] : 0; /* Blender's v = 0 is the image's bottom */
    }
    memcpy(buf + nv * 8, d->indices, nt * 3 * sizeof(uint32_t));
    char name[64];
    snprintf(name, sizeof name, "assets/mesh%d.bin", mi);
    bool ok = write_file(c, name, buf, floats * sizeof *buf);
    free(buf);
    if (!ok) return false;
    cJSON *j = cJSON_CreateObject();
    char id[32];
    snprintf(id, sizeof id, "mesh%d", mi);
    cJSON_AddStringToObject(j, "name", id);
    cJSON_AddStringToObject(j, "file", name);
    cJSON_AddNumberToObject(j, "vertex_count", (double)nv);
    cJSON_AddNumberToObject(j, "triangle_count", (double)nt);
    cJSON_AddItemToArray(list, j);
    return true;
}

static bool export_objects(ctx *c, cJSON *root, const bool *mat_checked) {
    sl_app *app = c->app;
    sl_scene *s = &app->scene;
    cJSON *meshes = cJSON_AddArrayToObject(root, "meshes");
    for (int mi = 0; mi < s->mesh_count; mi++)
        if (!export_mesh(c, mi, meshes)) return false;
    cJSON *objects = cJSON_AddArrayToObject(root, "objects");
    for (int ni = 0; ni < s->node_count; ni++) {
        const sl_node *node = &s->nodes[ni];
        for (int k = 0; k < node->mesh_count; k++) {
            int mi = node->meshes[k], mat = s->meshes[mi].material;
            xc_object *grown = realloc(c->out->objects, (c->out->object_count + 1) * sizeof *grown);
            if (!grown) { snprintf(c->err, c->n, "out of memory"); return false; }
            c->out->objects = grown;
            xc_object *o = &c->out->objects[c->out->object_count++];
            memset(o, 0, sizeof *o);
            if (node->mesh_count > 1) snprintf(o->name, sizeof o->name, "%s#%d", node->name, k);
            else snprintf(o->name, sizeof o->name, "%s", node->name);
            snprintf(o->material, sizeof o->material, "%s", mat >= 0 ? s->materials[mat].name : "");
            o->checked = mat >= 0 && mat_checked[mat];
            cJSON *j = cJSON_CreateObject();
            cJSON_AddStringToObject(j, "name", o->name);
            char mesh[32];
            snprintf(mesh, sizeof mesh, "mesh%d", mi);
            cJSON_AddStringToObject(j, "mesh", mesh);
            cJSON_AddStringToObject(j, "material", mat >= 0 ? s->materials[mat].name : "");
            cJSON_AddItemToObject(j, "matrix", vec(node->world, 16));
            cJSON_AddNumberToObject(j, "index", c->out->object_count);
            cJSON_AddItemToArray(objects, j);
        }
    }
    return true;
}

/* ------------------------------------------------------------------------------- lights -- */

static bool export_light(ctx *c, int li, cJSON *list) {
    sl_app *app = c->app;
    const sl_light *L = &app->scene.lights[li];
    /* envmap.sun (envmap.sun_light): the procedural sky's own sun, which the exported sky holds as
     * its disk and lamp (export_sun, docs/xcheck.md): no second lamp doubles it */
    if (L->plugin && !strcmp(app->plugins.items[L->plugin - 1]->id, "envmap")) return true;
    /* a light of type "indirect" stands for light the scene bounces (bounce.indirect; the plugin
     * guide reserves the type for such lights): Cycles traces those bounces itself */
    if (!strcmp(L->type, "indirect")) return true;
    if (!L->enabled) return true;
    if (!light_type_handled(app, L->type)) {
        note(c, "not cross-checked: light %s: type \"%s\" is drawn by no enabled plugin (it lights nothing in "
                "shadelab, nor in the reference)", L->name, L->type);
        return true;
    }
    float pos[3], dir[3], v[3];
    sl_light_at_time(L, app->time, pos, dir);
    bool shadows = plugin_on(app, "spotlight-shadow") && global_param(app, "spotlight-shadow.shadows") &&
                   global_param(app, "spotlight-shadow.shadows")->value.b;
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "name", L->name);
    cJSON_AddItemToObject(j, "color", vec(L->color, 3));
    cJSON_AddBoolToObject(j, "shadow", L->cast_shadows && shadows);
    float m[16];
    if (!strcmp(L->type, "directional")) {
        cJSON_AddStringToObject(j, "blender_type", "SUN");
        cJSON_AddNumberToObject(j, "energy", L->intensity);
        cJSON_AddNumberToObject(j, "angle", 2 * L->angular_radius * M_PI / 180);
        frame_matrix(dir, NULL, pos, m);
    } else if (!strcmp(L->type, "point") || !strcmp(L->type, "spot")) {
        cJSON_AddStringToObject(j, "blender_type", "POINT");
        cJSON_AddNumberToObject(j, "energy", 4 * M_PI * L->intensity);
        if (light_key(app, li, "radius", v, NULL) && v[0] > 0 && L->cast_shadows && shadows) {
            cJSON_AddNumberToObject(j, "radius", v[0]);
            note(c, "approximated: light %s: a sphere of radius %g in Cycles (shadelab shades from its centre and "
                    "uses the radius for the shadow's penumbra)", L->name, v[0]);
        }
        frame_matrix(dir, NULL, pos, m);
        if (!strcmp(L->type, "spot")) {
            const char *falloff = "linear";
            float cone[3] = {30}, inner[3] = {0};
            light_key(app, li, "cone_angle", cone, NULL);
            light_key(app, li, "inner_cone_angle", inner, NULL);
            light_key(app, li, "falloff", v, &falloff);
            cJSON *sp = cJSON_AddObjectToObject(j, "spot");
            cJSON_AddStringToObject(sp, "falloff", falloff);
            double outer = cone[0] * M_PI / 180, in = inner[0] * M_PI / 180;
            cJSON_AddNumberToObject(sp, "cone", outer);
            double scale = 1 / fmax(0.001, cos(in) - cos(outer));
            cJSON_AddNumberToObject(sp, "scale", scale);
            cJSON_AddNumberToObject(sp, "offset", -cos(outer) * scale);
        }
    } else if (!strcmp(L->type, "area")) {
        float wh[3] = {1}, hh[3] = {1}, axis[3] = {1, 0, 0}, two[3] = {0};
        const char *shape = "rect";
        light_key(app, li, "width", wh, NULL);
        light_key(app, li, "height", hh, NULL);
        light_key(app, li, "axis", axis, NULL);
        light_key(app, li, "shape", v, &shape);
        light_key(app, li, "two_sided", two, NULL);
        bool disk = !strcmp(shape, "disk");
        double area = disk ? M_PI * wh[0] * hh[0] / 4 : wh[0] * hh[0];
        cJSON_AddStringToObject(j, "blender_type", "AREA");
        cJSON_AddStringToObject(j, "shape", disk ? "ELLIPSE" : "RECTANGLE");
        float size[2] = {wh[0], hh[0]};
        cJSON_AddItemToObject(j, "size", vec(size, 2));
        cJSON_AddNumberToObject(j, "energy", 4 * L->intensity * area); /* Cycles: L = P / 4A (measured, docs/xcheck.md) */
        cJSON_ReplaceItemInObject(j, "shadow", cJSON_CreateBool(false));
        note(c, "approximated: light %s: area lights cast no shadows in shadelab's real-time path; none in the "
                "reference either", L->name);
        if (two[0] > 0) note(c, "not cross-checked: light %s: two-sided area light (one-sided in the reference)", L->name);
        frame_matrix(dir, axis, pos, m);
    } else {
        note(c, "not cross-checked: light %s: type \"%s\" has no Cycles counterpart here", L->name, L->type);
        cJSON_Delete(j);
        return true;
    }
    cJSON_AddItemToObject(j, "matrix", vec(m, 16));
    cJSON_AddItemToArray(list, j);
    return true;
}

/* --------------------------------------------------------------------------- environment -- */

/* Blender's equirectangular lookup, in shadelab's Y-up frame (Blender's frame is this one turned
 * +90° about X: Blender (x, y, z) = (x, −z, y)): u = 0.5 at +X growing towards +Z, v = 0 up.
 * The direction of the centre of texel (x, y) of a w×h lat-long. */
static void blender_latlong_dir(double u, double v, double d[3]) {
    double phi = (u - 0.5) * 2 * M_PI, theta = v * M_PI; /* phi = atan2(z, x) */
    d[0] = sin(theta) * cos(phi);
    d[1] = cos(theta);
    d[2] = sin(theta) * sin(phi);
}

/* envmap's procedural sky as the scene's parameters set it. */
static em_sky export_sky(sl_app *app) {
    em_sky sky;
    em_sky_default(&sky);
    sky.sun_elevation_deg = global_float(app, "envmap.sun_elevation", sky.sun_elevation_deg);
    sky.sun_azimuth_deg = global_float(app, "envmap.sun_azimuth", sky.sun_azimuth_deg);
    sky.sun_irradiance = global_float(app, "envmap.sun_irradiance", sky.sun_irradiance);
    const sl_param *ground = global_param(app, "envmap.ground_color");
    if (ground) memcpy(sky.ground, ground->value.f, sizeof sky.ground);
    return sky;
}

/* The sky without its sun disk, evaluated per direction of Blender's lat-long (3×3 samples a
 * texel), w×h RGBA. The disk goes to the world's nodes instead (export_sun_disk): in a texture its
 * edge would be blurred over the texels, while shadelab's background box-filters the exact disk
 * over each pixel, as Cycles' pixel does with the disk drawn by nodes. */
static float *sky_latlong(const em_sky *with_sun, int w, int h) {
    em_sky sky = *with_sun;
    sky.sun_irradiance = 0;
    float *px = malloc((size_t)w * h * 4 * sizeof *px);
    if (!px) return NULL;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double sum[3] = {0, 0, 0};
            for (int sy = 0; sy < 3; sy++)
                for (int sx = 0; sx < 3; sx++) {
                    double d[3], L[3];
                    blender_latlong_dir((x + (sx + 0.5) / 3) / w, (y + (sy + 0.5) / 3) / h, d);
                    em_sky_radiance(&sky, d, L);
                    for (int i = 0; i < 3; i++) sum[i] += L[i] / 9;
                }
            float *p = px + ((size_t)y * w + x) * 4;
            for (int i = 0; i < 3; i++) p[i] = (float)fmin(sum[i], 65504.0);
            p[3] = 1;
        }
    return px;
}

/* The sky's sun disk (radiance L, angular radius r), twice. world.sun, in the frame of the
 * lat-long's lookup (Blender's axes, before the map's turn: direction, cos r, L), which
 * xcheck_blender.py draws by the world's nodes for camera rays only; and a Sun lamp of angle 2r and
 * strength L·π·sin²r (the disk's irradiance on a surface facing it) towards R_y(yaw)·sun, which
 * lights every other ray: lit through the world's importance map, the 3° disk left fireflies on
 * diffuse surfaces at 64 samples, while a lamp is sampled by its cone and hit by glossy rays. */
static void export_sun(const em_sky *sky, double yaw, cJSON *w, cJSON *lights) {
    double dir[3], r, L[3];
    em_sky_sun(sky, dir, &r, L);
    double peak = fmax(L[0], fmax(L[1], L[2]));
    if (!(peak > 0)) return;
    cJSON *sun = cJSON_AddObjectToObject(w, "sun");
    float b[3] = {(float)dir[0], (float)-dir[2], (float)dir[1]}, rad[3] = {(float)L[0], (float)L[1], (float)L[2]};
    cJSON_AddItemToObject(sun, "direction", vec(b, 3));
    cJSON_AddNumberToObject(sun, "cos_radius", cos(r));
    cJSON_AddItemToObject(sun, "radiance", vec(rad, 3));
    cJSON *j = cJSON_CreateObject();
    float colour[3] = {(float)(L[0] / peak), (float)(L[1] / peak), (float)(L[2] / peak)}, m[16], zero[3] = {0, 0, 0};
    float forward[3] = {(float)-(dir[0] * cos(yaw) + dir[2] * sin(yaw)), (float)-dir[1],
                        (float)-(-dir[0] * sin(yaw) + dir[2] * cos(yaw))}; /* −R_y(yaw)·sun: the light's travel */
    cJSON_AddStringToObject(j, "name", "sky sun");
    cJSON_AddItemToObject(j, "color", vec(colour, 3));
    cJSON_AddBoolToObject(j, "shadow", true); /* as the world's disk shadowed: the path tracer's truth */
    cJSON_AddStringToObject(j, "blender_type", "SUN");
    cJSON_AddNumberToObject(j, "energy", peak * M_PI * sin(r) * sin(r));
    cJSON_AddNumberToObject(j, "angle", 2 * r);
    frame_matrix(forward, NULL, zero, m);
    cJSON_AddItemToObject(j, "matrix", vec(m, 16));
    cJSON_AddItemToArray(lights, j);
}

static float *core_pattern(void *user, const char *spec, int size, char *err, size_t n) {
    (void)user;
    sl_image img = {0};
    if (!sl_image_procedural(&img, spec, size, err, n)) return NULL;
    return img.pixels; /* RGBA, size², owned by the caller */
}

static bool export_world(ctx *c, cJSON *root, cJSON *lights) {
    sl_app *app = c->app;
    const sl_environment *env = &app->scene.environment;
    /* shadelab looks up R_y(−yaw)·d; about Blender's up axis that is the same angle */
    double yaw = (env->yaw_deg + global_float(app, "envmap.yaw", 0)) * M_PI / 180;
    cJSON *w = cJSON_AddObjectToObject(root, "world");
    float clear[3];
    for (int i = 0; i < 3; i++) clear[i] = env->color[i] * env->intensity;
    bool envmap = plugin_on(app, "envmap");
    bool has_colour = env->color[0] > 0 || env->color[1] > 0 || env->color[2] > 0;
    if (!envmap || (!env->map && has_colour)) {
        cJSON_AddItemToObject(w, "color", vec(clear, 3));
        return true;
    }
    float *px = NULL;
    int width = 0, height = 0;
    if (!env->map) {
        width = 2048, height = 1024;
        em_sky sky = export_sky(app);
        px = sky_latlong(&sky, width, height);
        if (!px) { snprintf(c->err, c->n, "out of memory"); return false; }
        export_sun(&sky, yaw, w, lights);
    } else {
        em_env e = {0};
        bool ok;
        if (em_is_procedural(env->map)) {
            bool constant = false;
            e.kind = EM_ENV_LATLONG;
            ok = em_procedural(env->map, core_pattern, NULL, &e.latlong, &constant, c->err, c->n);
        } else {
            ok = em_env_load(env->map, &em_io_reader, &e, c->err, c->n);
        }
        if (!ok) return false;
        if (e.kind != EM_ENV_LATLONG) {
            note(c, "not cross-checked: environment %s: cube-map layouts (only lat-long maps are exported)", env->map);
            em_env_free(&e);
            cJSON_AddItemToObject(w, "color", vec((float[3]){0, 0, 0}, 3));
            return true;
        }
        width = e.latlong.w, height = e.latlong.h;
        px = e.latlong.px;
        e.latlong.px = NULL;
        em_env_free(&e);
    }
    bool ok = write_exr(c, "assets/environment.exr", px, width, height);
    free(px);
    if (!ok) return false;
    cJSON *map = cJSON_AddObjectToObject(w, "map");
    cJSON_AddStringToObject(map, "file", "assets/environment.exr");
    cJSON_AddStringToObject(map, "colorspace", "Linear");
    cJSON_AddNumberToObject(map, "rotate_z", -yaw);
    cJSON_AddNumberToObject(w, "strength", env->intensity);
    if (global_param(app, "envmap.background") && !global_param(app, "envmap.background")->value.b)
        note(c, "not cross-checked: the background (envmap.background=false)");
    return true;
}

/* -------------------------------------------------------------------------------- camera -- */

static void export_camera(ctx *c, const xc_export_options *o, cJSON *root) {
    sl_app *app = c->app;
    sl_camera_state cam = app->camera;
    cam.aspect = (float)o->width / (float)o->height;
    float view[16], proj[16], m[16];
    sl_camera_matrices(&cam, view, proj);
    /* the camera's world matrix: the inverse of the rigid view matrix, [Rᵀ | −Rᵀt] */
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++) m[col * 4 + row] = view[row * 4 + col];
    for (int row = 0; row < 3; row++)
        m[12 + row] = -(m[row] * view[12] + m[4 + row] * view[13] + m[8 + row] * view[14]);
    m[3] = m[7] = m[11] = 0, m[15] = 1;
    cJSON *j = cJSON_AddObjectToObject(root, "camera");
    cJSON_AddStringToObject(j, "type", cam.orthographic ? "orthographic" : "perspective");
    cJSON_AddNumberToObject(j, "fov_y", cam.fov_y_deg);
    cJSON_AddNumberToObject(j, "ymag", cam.ymag);
    cJSON_AddNumberToObject(j, "near", cam.znear);
    cJSON_AddNumberToObject(j, "far", cam.zfar);
    cJSON_AddItemToObject(j, "matrix", vec(m, 16));
}

/* ------------------------------------------------------------------------------ glTF ---- */

static bool is_gltf_model(const sl_app *app) {
    if (!app->scene.from_model || !app->scene.path) return false;
    char ext[16];
    file_extension(app->scene.path, ext, sizeof ext);
    return !strcmp(ext, "gltf") || !strcmp(ext, "glb");
}

/* Adds a file's bytes to the export's hash. */
static bool hash_file(ctx *c, const char *path) {
    unsigned char *bytes = NULL;
    size_t size = 0;
    if (!read_whole(path, &bytes, &size, c->err, c->n)) return false;
    c->out->hash = sl_tool_hash64(bytes, size, c->out->hash);
    free(bytes);
    return true;
}

/* The model for Blender's own importer: a .glb copied under assets/; a .gltf read where it is (its
 * buffers and images are relative to it), hashed with every file its "uri"s name. */
static bool export_gltf(ctx *c, cJSON *root) {
    const char *path = c->app->scene.path;
    char ext[16];
    file_extension(path, ext, sizeof ext);
    cJSON *g = cJSON_AddObjectToObject(root, "gltf");
    if (!strcmp(ext, "glb")) {
        unsigned char *bytes = NULL;
        size_t size = 0;
        if (!read_whole(path, &bytes, &size, c->err, c->n)) return false;
        bool ok = write_file(c, "assets/model.glb", bytes, size);
        free(bytes);
        cJSON_AddStringToObject(g, "file", "assets/model.glb");
        return ok;
    }
    char *abs = realpath(path, NULL);
    if (!abs) { snprintf(c->err, c->n, "%s: %s", path, strerror(errno)); return false; }
    cJSON_AddStringToObject(g, "file", abs);
    unsigned char *text = NULL;
    size_t size = 0;
    bool ok = read_whole(abs, &text, &size, c->err, c->n);
    if (ok) {
        text[size] = 0;
        c->out->hash = sl_tool_hash64(text, size, c->out->hash);
        cJSON *doc = cJSON_Parse((const char *)text);
        char dir[4096];
        snprintf(dir, sizeof dir, "%s", abs);
        char *slash = strrchr(dir, '/');
        if (slash) *slash = 0;
        const char *lists[2] = {"buffers", "images"};
        for (int l = 0; doc && ok && l < 2; l++) {
            cJSON *item;
            cJSON_ArrayForEach(item, cJSON_GetObjectItemCaseSensitive(doc, lists[l])) {
                const cJSON *uri = cJSON_GetObjectItemCaseSensitive(item, "uri");
                if (!cJSON_IsString(uri) || !strncmp(uri->valuestring, "data:", 5)) continue;
                char file[8192];
                snprintf(file, sizeof file, "%s/%s", dir, uri->valuestring);
                if (!hash_file(c, file)) { ok = false; break; }
            }
        }
        cJSON_Delete(doc);
    }
    free(text);
    free(abs);
    return ok;
}

/* ---------------------------------------------------------------------------------- main -- */

static bool copy_builder(ctx *c, const char *builder) {
    unsigned char *bytes = NULL;
    size_t size = 0;
    if (!read_whole(builder, &bytes, &size, c->err, c->n)) return false;
    bool ok = write_file(c, "xcheck_blender.py", bytes, size);
    free(bytes);
    static const char runner[] =
        "# Written by shadelab-xcheck: builds scene.json (beside this file) in Blender and renders it.\n"
        "#   blender -b --factory-startup --python scene.py -- OUTDIR\n"
        "import os\n"
        "os.environ['XCHECK_DIR'] = os.path.dirname(os.path.abspath(__file__))\n"
        "with open(os.path.join(os.environ['XCHECK_DIR'], 'xcheck_blender.py')) as f:\n"
        "    exec(compile(f.read(), 'xcheck_blender.py', 'exec'))\n";
    return ok && write_file(c, "scene.py", runner, sizeof runner - 1);
}

/* --unoccluded: objects cast no shadows in the reference; each light whose shadow shadelab draws
 * is named. */
static void note_unshadowed(ctx *c, const cJSON *lights) {
    const cJSON *l;
    cJSON_ArrayForEach(l, lights) {
        const cJSON *shadow = cJSON_GetObjectItemCaseSensitive(l, "shadow"),
                    *name = cJSON_GetObjectItemCaseSensitive(l, "name");
        if (cJSON_IsTrue(shadow))
            note(c, "approximated: light %s: its shadow is not in the reference (--unoccluded: objects are seen by "
                    "camera rays only)", cJSON_IsString(name) ? name->valuestring : "?");
    }
}

bool xc_export_scene(sl_app *app, const xc_export_options *o, const char *dir, xc_export *out, char *err, size_t n) {
    memset(out, 0, sizeof *out);
    char assets[4096];
    snprintf(assets, sizeof assets, "%s/assets", dir);
    if (!xc_mkdirs(assets, err, n)) return false;
    ctx c = {.app = app, .dir = dir, .out = out, .err = err, .n = n};
    cJSON *root = cJSON_CreateObject();
    cJSON *render = cJSON_AddObjectToObject(root, "render");
    cJSON_AddNumberToObject(render, "width", o->width);
    cJSON_AddNumberToObject(render, "height", o->height);
    cJSON_AddNumberToObject(render, "samples", o->samples);
    cJSON_AddNumberToObject(render, "bounces", o->bounces);
    if (o->unoccluded) cJSON_AddStringToObject(render, "object_rays", "camera"); /* absent: all rays (cache keys kept) */
    int tm = sl_plugins_find(&app->plugins, "tonemap");
    if (tm >= 0 && app->plugins.items[tm]->ok) { /* shadelab-xcheck switches it off: loaded is what counts */
        cJSON_AddNumberToObject(render, "exposure", global_float(app, "tonemap.exposure", 0));
        note(&c, "not cross-checked: tonemap (operator %s, exposure %g EV): images are compared before tone mapping",
             global_enum(app, "tonemap.operator"), global_float(app, "tonemap.exposure", 0));
    }
    export_camera(&c, o, root);
    bool ok = true;
    int mc = app->scene.material_count;
    bool *checked = calloc(mc + 1, sizeof *checked);
    cJSON *mats = cJSON_AddArrayToObject(root, "materials");
    out->gltf = is_gltf_model(app);
    if (out->gltf) {
        /* geometry and materials: Blender's own reading of the file */
        note(&c, "glTF: geometry and materials as Blender's glTF importer reads the file; lights as shadelab reads "
                 "them (Blender's importer gives spots its own edge)");
        note(&c, "%s", PRINCIPLED_NOTE); /* the importer's materials are Principled BSDFs too */
        cJSON_AddArrayToObject(root, "meshes");
        cJSON_AddArrayToObject(root, "objects");
        ok = export_gltf(&c, root);
    } else {
        for (int m = 0; ok && m < mc; m++) ok = export_material(&c, m, mats, &checked[m]);
        ok = ok && export_objects(&c, root, checked);
    }
    cJSON *lights = cJSON_AddArrayToObject(root, "lights");
    for (int li = 0; ok && li < app->scene.light_count; li++) ok = export_light(&c, li, lights);
    if (ok && o->unoccluded) note_unshadowed(&c, lights);
    ok = ok && export_world(&c, root, lights);
    free(checked);
    if (ok) {
        char *text = cJSON_Print(root);
        ok = text && write_file(&c, "scene.json", text, strlen(text));
        free(text);
    }
    cJSON_Delete(root);
    ok = ok && copy_builder(&c, o->builder);
    for (int i = 0; i < c.texture_count; i++) free(c.textures[i].value), cJSON_Delete(c.textures[i].json);
    free(c.textures);
    if (!ok) xc_export_free(out);
    return ok;
}

bool xc_export_read_objects(xc_export *e, const char *objects_json, char *err, size_t n) {
    unsigned char *text = NULL;
    size_t size = 0;
    if (!read_whole(objects_json, &text, &size, err, n)) return false;
    text[size] = 0;
    cJSON *doc = cJSON_Parse((const char *)text);
    free(text);
    cJSON *list = cJSON_GetObjectItemCaseSensitive(doc, "objects"), *item;
    if (!cJSON_IsArray(list)) {
        snprintf(err, n, "%s: no \"objects\" list", objects_json);
        cJSON_Delete(doc);
        return false;
    }
    int count = cJSON_GetArraySize(list), k = 0;
    free(e->objects);
    e->objects = calloc(count + 1, sizeof *e->objects);
    cJSON_ArrayForEach(item, list) {
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(item, "name"),
                    *mat = cJSON_GetObjectItemCaseSensitive(item, "material");
        xc_object *o = &e->objects[k++]; /* listed in pass-index order, from 1 */
        snprintf(o->name, sizeof o->name, "%s", cJSON_IsString(name) ? name->valuestring : "?");
        snprintf(o->material, sizeof o->material, "%s", cJSON_IsString(mat) ? mat->valuestring : "");
        o->checked = true;
    }
    e->object_count = k;
    cJSON_Delete(doc);
    return true;
}

void xc_export_free(xc_export *e) {
    for (int i = 0; i < e->note_count; i++) free(e->notes[i]);
    free(e->notes);
    free(e->objects);
    memset(e, 0, sizeof *e);
}
