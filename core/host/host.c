/* The host interface (sdk/include/shadelab/host.h) given to each plugin: the one module that
 * knows both the plugin registry (registrations go to core/plugin) and the renderer (programs,
 * passes, drawing go to core/render). The registry and the renderer know nothing of it. */
#include "host/host.h"
#include "state.h"
#include "log.h"
#include "render/renderer.h"
#include "render/composer.h"
#include "render/post.h"
#include "budget/budget.h"
#include "image/image.h"
#include "plugin_lights.h"
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* Each plugin gets its own table; the app and the plugin's index follow the public struct. */
typedef struct sl_host_impl {
    sl_host host; /* first member: plugins get &impl->host */
    sl_app *app;
    int plugin;   /* index into sl_plugins.items */
} sl_host_impl;

#define HOST_APP(h) (((const sl_host_impl *)(h))->app)
#define HOST_IDX(h) (((const sl_host_impl *)(h))->plugin)
#define HOST_REC(h) (HOST_APP(h)->plugins.items[HOST_IDX(h)])

/* ---------------------------------------------------------------- host interface -------- */

static void host_log(const sl_host *h, sl_log_level level, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sl_logv(level, HOST_REC(h)->id, fmt, ap);
    va_end(ap);
}

static const char *host_resource_dir(const sl_host *h) { return HOST_REC(h)->resource_dir; }
static const char *host_shader_dir(const sl_host *h) { (void)h; return sl_shader_dir(); }








static sl_status host_add_param(const sl_host *h, const sl_param_desc *d) {
    return sl_plugins_add_param(&HOST_APP(h)->plugins, HOST_IDX(h), d);
}
static sl_status host_add_chunk(const sl_host *h, const sl_shader_chunk_desc *d) {
    return sl_plugins_add_chunk(&HOST_APP(h)->plugins, HOST_IDX(h), d);
}
static sl_status host_add_pass(const sl_host *h, const sl_pass_desc *d) {
    return sl_plugins_add_pass(&HOST_APP(h)->plugins, HOST_IDX(h), d);
}
static sl_status host_add_key(const sl_host *h, const sl_key_desc *d) {
    return sl_plugins_add_key(&HOST_APP(h)->plugins, HOST_IDX(h), d);
}
static sl_status host_set_reference(const sl_host *h, const sl_reference_desc *d) {
    return sl_plugins_set_reference(&HOST_APP(h)->plugins, HOST_IDX(h), d);
}
static int host_reserve_unit(const sl_host *h) { return sl_plugins_reserve_unit(&HOST_APP(h)->plugins, HOST_IDX(h)); }
/* Extensions the core provides itself (checked before the plugins'). */
static sl_status post_add_pointwise(const sl_host *h, const sl_pointwise_desc *d) {
    return sl_post_add_pointwise(HOST_APP(h), HOST_IDX(h), d);
}
static sl_status post_accept(const sl_host *h, const char *pass) { return sl_post_accept(HOST_APP(h), HOST_IDX(h), pass); }
static sl_program *post_load_program(const sl_host *h, const sl_program_desc *d) {
    return sl_post_load_program(HOST_APP(h), HOST_IDX(h), d);
}
static sl_status post_bind_outputs_with(const sl_host *h, sl_pass_ctx *c, int layer, const unsigned *t, int count) {
    return sl_post_bind_outputs_with(HOST_APP(h), c, layer, t, count);
}
static const sl_ext_post post_ext = {.struct_size = sizeof post_ext, .add_pointwise = post_add_pointwise,
                                     .accept_pointwise = post_accept, .load_program = post_load_program,
                                     .bind_outputs_with = post_bind_outputs_with};

static sl_status budget_add_model(const sl_host *h, const sl_quality_model *m) {
    return sl_budget_add_model(HOST_APP(h), HOST_IDX(h), m);
}
static const sl_ext_budget budget_ext = {.struct_size = sizeof budget_ext, .add_quality_model = budget_add_model};

static const void *host_get_extension(const sl_host *h, const char *id) {
    if (id && !strcmp(id, SL_EXT_POST)) return &post_ext;
    if (id && !strcmp(id, SL_EXT_BUDGET)) return &budget_ext;
    return sl_plugins_extension(&HOST_APP(h)->plugins, id);
}

static sl_status host_set_bind(const sl_host *h, void (*bind)(void *, unsigned, int, const sl_frame *), void *user) {
    HOST_REC(h)->bind = bind;
    HOST_REC(h)->bind_user = user;
    return SL_OK;
}

static sl_value host_get_param(const sl_host *h, const char *id) {
    sl_param *q = sl_params_find(&HOST_APP(h)->params, id);
    if (!q) {
        SL_WARN("%s: get_param(\"%s\"): no such parameter", HOST_REC(h)->id, id);
        return (sl_value){0};
    }
    return q->value;
}

static bool host_plugin_enabled(const sl_host *h, const char *id) {
    int i = sl_plugins_find(&HOST_APP(h)->plugins, id);
    return i >= 0 && sl_plugin_enabled(&HOST_APP(h)->plugins, i);
}


static const sl_light_info *host_lights(const sl_host *h, int *count) { return sl_renderer_lights(HOST_APP(h), count); }

static int host_material_count(const sl_host *h) { return HOST_APP(h)->scene.material_count; }

static const char *host_material_name(const sl_host *h, int m) {
    sl_app *app = HOST_APP(h);
    return m >= 0 && m < app->scene.material_count ? app->scene.materials[m].name : NULL;
}

static bool host_material_value(const sl_host *h, int m, const char *key, sl_value *out, char *path, size_t n) {
    sl_app *app = HOST_APP(h);
    sl_mat_value *v = sl_app_material_value(app, m, key);
    if (path && n) path[0] = 0;
    if (!v || !v->present) return false;
    if (out) *out = v->v;
    if (path && n && v->str && app->params.items[v->param].desc.type == SL_PARAM_TEXTURE && !sl_image_is_procedural(v->str)) {
        char err[1024];
        char *resolved = sl_scene_resolve_path(&app->scene, app->opt.data_dir, v->str, err, sizeof err);
        if (resolved) snprintf(path, n, "%s", resolved);
        free(resolved);
    }
    return true;
}
static void *host_gl_proc(const char *name);
static sl_app *g_gl_app; /* the app whose context is current (one per process) */
static void *host_gl_proc(const char *name) {
    return g_gl_app && g_gl_app->backend.get_proc_address ? g_gl_app->backend.get_proc_address(name) : NULL;
}
static bool host_is_gpu(const sl_host *h) { return HOST_APP(h)->backend.is_gpu; }
static sl_program *host_load_program(const sl_host *h, const sl_program_desc *d) {
    return sl_renderer_load_program(HOST_APP(h), HOST_IDX(h), d);
}
static unsigned host_program_id(const sl_host *h, sl_program *p) { return sl_post_program_id(HOST_APP(h), p); }
static unsigned host_pass_texture(const sl_host *h, sl_pass_ctx *c, const char *name) {
    return sl_renderer_pass_texture(HOST_APP(h), c, name);
}
static sl_status host_bind_outputs(const sl_host *h, sl_pass_ctx *c, int layer) {
    return sl_renderer_bind_outputs(HOST_APP(h), c, layer);
}
static void host_draw_scene(const sl_host *h, sl_pass_ctx *c, const sl_draw_scene_desc *d) {
    sl_renderer_draw_scene(HOST_APP(h), c, d);
}
static void host_draw_fullscreen(const sl_host *h, sl_pass_ctx *c) {
    sl_post_bind_fused(HOST_APP(h)); /* the uniforms of passes fused into this one (ext/post.h) */
    sl_renderer_draw_fullscreen(HOST_APP(h), c);
}
static unsigned host_material_texture(const sl_host *h, int m, const char *key) {
    return sl_renderer_material_texture(HOST_APP(h), m, key);
}
static void host_set_jitter(const sl_host *h, float x, float y) { sl_renderer_set_jitter(HOST_APP(h), x, y); }
static void host_set_still_frames(const sl_host *h, int frames) { sl_renderer_set_still_frames(HOST_APP(h), frames); }
static void host_set_texture_lod_bias(const sl_host *h, float bias) { sl_renderer_set_texture_lod_bias(HOST_APP(h), bias); }

static const char *host_environment(const sl_host *h, float o[5]) {
    const sl_environment *e = &HOST_APP(h)->scene.environment;
    HOST_APP(h)->environment_read = true;
    memcpy(o, e->color, 3 * sizeof(float)), o[3] = e->intensity, o[4] = e->yaw_deg;
    return e->map;
}
static float *host_procedural_image(const sl_host *h, const char *spec, int size, char *err, size_t n) {
    (void)h;
    sl_image img;
    if (!sl_image_procedural(&img, spec, size, err, n)) return NULL;
    return img.pixels; /* RGBA, size x size: the plugin frees it */
}
static bool host_read_image(const sl_host *h, const char *path, sl_image_file *out, char *err, size_t n) {
    (void)h;
    if (!out || out->struct_size < sizeof *out) {
        snprintf(err, n, "%s: read_image needs an sl_image_file with struct_size set (SDK ABI 1.10)", path ? path : "?");
        return false;
    }
    uint32_t size = out->struct_size;
    memset(out, 0, sizeof *out);
    out->struct_size = size;
    sl_image img;
    if (!sl_image_load(&img, path, err, n)) return false;
    out->width = img.width, out->height = img.height, out->pixels = img.pixels; /* the plugin frees it */
    out->bits = img.source_bits, out->channels = img.source_channels;
    out->is_float = img.source_float, out->srgb = img.source_srgb;
    snprintf(out->description, sizeof out->description, "%s", img.source_description);
    snprintf(out->format, sizeof out->format, "%s", img.source_format);
    return true;
}
static bool host_scene_uses_uniform(const sl_host *h, const char *name) {
    return sl_renderer_materials_use_uniform((sl_app *)HOST_APP(h), name);
}
static int host_add_light(const sl_host *h, const sl_plugin_light_desc *d) {
    char err[512];
    int li = d ? sl_plugin_light_add(HOST_APP(h), HOST_IDX(h), d, err, sizeof err) : -1;
    if (li < 0) host_log(h, SL_LOG_ERROR, "%s", d ? err : "add_light: no description");
    return li;
}
static bool host_set_light(const sl_host *h, int light, const sl_plugin_light_state *s) {
    return s && sl_plugin_light_set(HOST_APP(h), HOST_IDX(h), light, s);
}
static void host_compile_ahead(const sl_host *h) { sl_renderer_compile_ahead((sl_app *)HOST_APP(h)); }
void sl_host_set_gl_app(sl_app *app) { g_gl_app = app; }

sl_host *sl_host_make(sl_app *app, int index) {
    sl_host_impl *impl = calloc(1, sizeof *impl);
    impl->app = app;
    impl->plugin = index;
    sl_host *h = &impl->host;
    h->struct_size = sizeof *h;
    h->abi_major = SL_ABI_MAJOR;
    h->abi_minor = SL_ABI_MINOR;
    h->host_version = SL_VERSION;
    h->log = host_log;
    h->resource_dir = host_resource_dir;
    h->add_param = host_add_param;
    h->add_shader_chunk = host_add_chunk;
    h->add_pass = host_add_pass;
    h->add_key = host_add_key;
    h->set_reference = host_set_reference;
    h->set_bind_callback = host_set_bind;
    h->reserve_texture_unit = host_reserve_unit;
    h->get_param = host_get_param;
    h->plugin_enabled = host_plugin_enabled;
    h->get_extension = host_get_extension;
    h->lights = host_lights;
    h->material_count = host_material_count;
    h->material_name = host_material_name;
    h->material_value = host_material_value;
    h->gl_get_proc_address = host_gl_proc;
    h->is_gpu = host_is_gpu;
    h->load_program = host_load_program;
    h->program_id = host_program_id;
    h->pass_texture = host_pass_texture;
    h->bind_outputs = host_bind_outputs;
    h->draw_scene = host_draw_scene;
    h->draw_fullscreen = host_draw_fullscreen;
    h->material_texture = host_material_texture;
    h->set_jitter = host_set_jitter;
    h->set_still_frames = host_set_still_frames;
    h->environment = host_environment;
    h->shader_dir = host_shader_dir;
    h->procedural_image = host_procedural_image;
    h->read_image = host_read_image;
    h->scene_uses_uniform = host_scene_uses_uniform;
    h->compile_ahead = host_compile_ahead;
    h->set_texture_lod_bias = host_set_texture_lod_bias;
    h->add_light = host_add_light;
    h->set_light = host_set_light;
    return &impl->host;
}

