/* The test harness (sdk/include/shadelab/harness.h) over the application object. */
#include <shadelab/harness.h>
#include "app.h"
#include "core_plugin.h"
#include "image/image.h"
#include "log.h"
#include "render/composer.h"
#include "render/renderer.h"
#include <shadelab/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct sl_harness { sl_app app; };

/* The live harness: the GL loader's function pointers and the host's GL app are per process, so a
 * second harness would run on the first one's context (empty compile logs, then a crash). */
static sl_harness *live_harness;

sl_harness *sl_harness_create(const sl_harness_desc *in, char *err, size_t n) {
    if (live_harness) {
        snprintf(err, n, "sl_harness_create: a harness already exists in this process (one GL context per process); "
                 "sl_harness_destroy it first");
        return NULL;
    }
    sl_harness_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    sl_app_options opt = {0};
    opt.width = d.width > 0 ? d.width : 64;
    opt.height = d.height > 0 ? d.height : 64;
    opt.scene_path = d.scene_file;
    opt.scene_text = d.scene_json;
    /* No scene named: the bare scene (scenes/basic.json, compiled in), not the showcase default,
     * which loads five plugins; tests that want the default name it (sl_default_scene_json). */
    if (!opt.scene_path && !opt.scene_text) opt.scene_text = sl_basic_scene_json;
    opt.debug_view = d.debug_view;
    opt.accumulate = d.accumulate;
    opt.float32 = d.float32;
    opt.strict = d.strict;
    opt.backend = SL_BACKEND_OSMESA;
    const char *b = getenv("SHADELAB_TEST_BACKEND");
    if (b && *b && !sl_backend_parse(b, &opt.backend)) {
        snprintf(err, n, "SHADELAB_TEST_BACKEND=%s: unknown backend", b);
        return NULL;
    }
    for (const char *const *p = d.plugins; p && *p && opt.plugin_count < 64; p++) opt.plugins[opt.plugin_count++] = *p;
    for (const char *const *s = d.settings; s && *s && opt.setting_count < 128; s++) opt.settings[opt.setting_count++] = *s;
    sl_harness *h = calloc(1, sizeof *h);
    if (!sl_app_init(&h->app, &opt, err, n) || !sl_app_start_gl(&h->app, err, n)) {
        sl_app_shutdown(&h->app);
        free(h);
        return NULL;
    }
    live_harness = h;
    return h;
}

void sl_harness_destroy(sl_harness *h) {
    if (!h) return;
    sl_app_shutdown(&h->app);
    if (live_harness == h) live_harness = NULL;
    free(h);
}

bool sl_harness_set(sl_harness *h, const char *a, char *err, size_t n) { return sl_app_set(&h->app, a, SL_SRC_GUI, err, n); }
bool sl_harness_set_debug_view(sl_harness *h, const char *v, char *err, size_t n) {
    return sl_app_set_debug_view(&h->app, v, err, n);
}

bool sl_harness_render(sl_harness *h, float *rgba) {
    h->app.time = h->app.frame_index * h->app.opt.fixed_dt;
    h->app.opt.keep_color = rgba != NULL; /* else the last pass may write "display" directly */
    return sl_app_render_frame(&h->app) && (!rgba || sl_app_read_color(&h->app, rgba));
}

/* A value of parameter q as --set text: floats in full (sl_param_format rounds for display). */
static void format_value(const sl_param *q, const sl_value *v, char *text, size_t n) {
    const float *f = v->f;
    if (q->desc.type == SL_PARAM_FLOAT) snprintf(text, n, "%.9g", f[0]);
    else if (q->desc.type == SL_PARAM_COLOR || q->desc.type == SL_PARAM_VEC3) snprintf(text, n, "%.9g,%.9g,%.9g", f[0], f[1], f[2]);
    else sl_param_format(q, v, text, n);
}

/* "light.NAME.KEY" of a core light key (core_plugin.h), formatted by the key's schema */
static bool get_light_key(sl_harness *h, const char *id, char *text, size_t n) {
    char name[512];
    const char *dot = strrchr(id, '.');
    if (strncmp(id, "light.", 6) || !dot || dot - id - 6 <= 0 || (size_t)(dot - id - 6) >= sizeof name) return false;
    snprintf(name, sizeof name, "%.*s", (int)(dot - id - 6), id + 6);
    for (int i = 0; i < h->app.scene.light_count; i++) {
        const sl_light *L = &h->app.scene.lights[i];
        const sl_param *q = sl_params_find_key(&h->app.params, SL_SCOPE_LIGHT, dot + 1, L->type);
        sl_value v;
        if (strcmp(L->name, name) || !q || !sl_core_light_get(L, dot + 1, &v)) continue;
        format_value(q, &v, text, n);
        return true;
    }
    return false;
}

bool sl_harness_get(sl_harness *h, const char *id, char *text, size_t n) {
    if (get_light_key(h, id, text, n)) return true;
    const sl_param *q = sl_params_find(&h->app.params, id);
    if (!q) return false;
    format_value(q, &q->value, text, n);
    return true;
}

bool sl_harness_render_sample(sl_harness *h, int index, int count, float *rgba) {
    if (count < 1 || index < 0 || index >= count) return false;
    sl_renderer_force_sample(&h->app, index, count);
    return sl_harness_render(h, rgba);
}

void sl_harness_set_frame(sl_harness *h, uint64_t frame_index) { h->app.frame_index = frame_index; }

bool sl_harness_set_camera(sl_harness *h, const float position[3], const float target[3]) {
    float d[3] = {position[0] - target[0], position[1] - target[1], position[2] - target[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 1e-6f) || !isfinite(len)) return false;
    sl_camera_state *c = &h->app.camera; /* as the scene's camera does (camera.c), lens kept */
    memcpy(c->target, target, sizeof c->target);
    c->distance = len;
    c->pitch = asinf(fmaxf(-1.f, fminf(1.f, d[1] / len)));
    c->yaw = atan2f(d[0], d[2]);
    c->version++;
    return true;
}

int sl_harness_plugins(sl_harness *h, const char **ids, int max) {
    int n = 0;
    for (int i = 1; i < h->app.plugins.count; i++) {
        if (!h->app.plugins.items[i]->ok) continue;
        if (n < max) ids[n] = h->app.plugins.items[i]->id;
        n++;
    }
    return n;
}

int sl_harness_plugin_params(sl_harness *h, const char *plugin, const sl_param_desc **out, int max) {
    int n = 0;
    for (int i = 0; i < h->app.params.count; i++) {
        const sl_param *q = &h->app.params.items[i];
        if (q->desc.scope != SL_SCOPE_GLOBAL || strcmp(q->owner, plugin) || !strcmp(q->desc.id, "enabled")) continue;
        if (n < max) out[n] = &q->desc;
        n++;
    }
    return n;
}

int sl_harness_plugin_keys(sl_harness *h, const char *plugin, const sl_key_desc **out, int max) {
    const sl_plugins *P = &h->app.plugins;
    int owner = sl_plugins_find((sl_plugins *)P, plugin), n = 0;
    for (int i = 0; i < P->key_count; i++) {
        if (P->keys[i].owner != owner) continue;
        if (n < max) out[n] = &P->keys[i].d;
        n++;
    }
    return n;
}

int sl_harness_plugin_debug_views(sl_harness *h, const char *plugin, const char **names, int max) {
    const sl_plugins *P = &h->app.plugins;
    int owner = sl_plugins_find((sl_plugins *)P, plugin), n = 0;
    for (int i = 0; i < P->chunk_count; i++) {
        const sl_chunk_reg *c = &P->chunks[i];
        if (c->owner != owner || (c->d.hook != SL_HOOK_DEBUG_VIEW && c->d.hook != SL_HOOK_DEBUG_VIEW_LIGHT)) continue;
        if (n < max) names[n] = c->d.name;
        n++;
    }
    return n;
}

bool sl_harness_read_display(sl_harness *h, float *rgba) { return sl_app_read_display(&h->app, rgba); }
bool sl_harness_save(sl_harness *h, const char *path, char *err, size_t n) { return sl_app_save(&h->app, path, err, n); }

/* Pass names outlive the harness and the plugin that registered them: a structure is often
 * compared after its harness is destroyed (plugin unloaded, its strings gone). Interned copies,
 * kept for the life of the process (a few dozen distinct names). */
static const char *intern_pass_name(const char *name) {
    static char *names[256];
    static int count;
    for (int i = 0; i < count; i++)
        if (!strcmp(names[i], name)) return names[i];
    if (count == 256) return "(more than 256 distinct pass names)";
    char *copy = strdup(name);
    if (!copy) return "(out of memory)";
    return names[count++] = copy;
}

void sl_harness_structure_of(sl_harness *h, sl_harness_structure *out) {
    memset(out, 0, sizeof *out);
    const sl_frame_stats *st = sl_renderer_stats(&h->app);
    if (!st) return;
    out->draw_calls = st->draw_calls;
    out->effect_draw_calls = st->draw_calls + st->reused_draw_calls;
    for (int i = 0; i < st->pass_count; i++) {
        if (st->passes[i].ran && out->pass_count < 64) out->passes[out->pass_count++] = intern_pass_name(st->passes[i].name);
        if ((st->passes[i].ran || st->passes[i].reused || st->passes[i].fused_into) && out->effect_count < 64)
            out->in_effect[out->effect_count++] = intern_pass_name(st->passes[i].name);
    }
    out->program_count = st->program_count;
    memcpy(out->program_hashes, st->program_hashes, sizeof out->program_hashes);
}

bool sl_harness_structure_equal(const sl_harness_structure *a, const sl_harness_structure *b) {
    if (a->draw_calls != b->draw_calls || a->pass_count != b->pass_count || a->program_count != b->program_count) return false;
    for (int i = 0; i < a->pass_count; i++)
        if (strcmp(a->passes[i], b->passes[i])) return false;
    for (int i = 0; i < a->program_count; i++)
        if (a->program_hashes[i] != b->program_hashes[i]) return false;
    return true;
}

void sl_harness_compare(const float *a, const float *b, int w, int h, double threshold, sl_compare *out) {
    sl_image_diff d;
    sl_image_compare(a, b, w, h, 4, threshold, &d);
    out->rmse = d.rmse;
    out->psnr = d.psnr;
    out->max_abs = d.max_abs;
    out->mean_abs = d.mean_abs;
    out->nonfinite = d.nonfinite_a + d.nonfinite_b;
    out->pixels_over = d.pixels_over;
}

long sl_harness_count_nonfinite(const float *p, int w, int h) {
    long c = 0;
    for (long i = 0; i < (long)w * h * 4; i++) c += !isfinite(p[i]);
    return c;
}

long sl_harness_count_negative(const float *p, int w, int h) {
    long c = 0;
    for (long i = 0; i < (long)w * h * 4; i++) c += p[i] < 0;
    return c;
}

static unsigned grid_texture(const float *data, int w, int h) {
    unsigned t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, GL_RGBA32F, w, h);
    if (data) glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, data);
    else {
        float *zero = calloc((size_t)w * h * 4, sizeof(float));
        glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, zero);
        free(zero);
    }
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

bool sl_harness_eval_glsl(sl_harness *h, const sl_glsl_eval_desc *in, float *out, char *err, size_t n) {
    sl_glsl_eval_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    if (!d.expression || d.width < 1 || d.height < 1 || d.width > 4096 || d.height > 4096) {
        snprintf(err, n, "eval_glsl: needs an expression and a grid size in 1..4096");
        return false;
    }
    const char *dir = sl_shader_dir();
    if (d.plugin) {
        int idx = sl_plugins_find(&h->app.plugins, d.plugin);
        if (idx < 0 || !h->app.plugins.items[idx]->ok) {
            snprintf(err, n, "eval_glsl: plugin %s is not loaded", d.plugin);
            return false;
        }
        dir = h->app.plugins.items[idx]->resource_dir;
    }
    sl_program p = {0};
    p.label = "glsl unit test";
    sl_sb_append(&p.vs.text, "#version 450 core\n");
    if (!sl_source_include(&p.vs, "sl:fullscreen.vert", err, n)) return false;
    sl_sb_append(&p.fs.text, "#version 450 core\n");
    if (d.defines) {
        char *copy = strdup(d.defines), *save = NULL;
        for (char *l = strtok_r(copy, "\n", &save); l; l = strtok_r(NULL, "\n", &save)) sl_sb_printf(&p.fs.text, "#define %s\n", l);
        free(copy);
    }
    bool ok = sl_source_include(&p.fs, "sl:common.glsl", err, n);
    for (const char *const *f = d.files; ok && f && *f; f++) {
        char path[2048];
        if ((*f)[0] == '/' || !strncmp(*f, "sl:", 3)) snprintf(path, sizeof path, "%s", *f);
        else snprintf(path, sizeof path, "%s/%s", dir, *f);
        ok = sl_source_include(&p.fs, path, err, n);
    }
    if (ok) {
        sl_strbuf def = {0};
        sl_sb_printf(&def, "#define SL_EVAL_EXPRESSION (%s)\n", d.expression);
        sl_source_generated(&p.fs, def.s);
        sl_sb_free(&def);
        ok = sl_source_include(&p.fs, "sl:glsl_eval.frag", err, n);
    }
    p.label = NULL;
    if (ok) ok = sl_program_build(&p, err, n);
    if (ok) {
        unsigned t0 = grid_texture(d.in0, d.width, d.height), t1 = grid_texture(d.in1, d.width, d.height);
        unsigned target, fbo;
        glCreateTextures(GL_TEXTURE_2D, 1, &target);
        glTextureStorage2D(target, 1, GL_RGBA32F, d.width, d.height);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, d.width, d.height);
        glUseProgram(p.id);
        glBindTextureUnit(0, t0);
        glBindTextureUnit(1, t1);
        glUniform1i(glGetUniformLocation(p.id, "sl_eval_in0"), 0);
        glUniform1i(glGetUniformLocation(p.id, "sl_eval_in1"), 1);
        sl_renderer_draw_fullscreen(&h->app, NULL);
        glGetTextureImage(target, 0, GL_RGBA, GL_FLOAT, d.width * d.height * 4 * (int)sizeof(float), out);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glUseProgram(0);
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &target);
        glDeleteTextures(1, &t0);
        glDeleteTextures(1, &t1);
        glDeleteProgram(p.id);
    }
    sl_source_free(&p.vs);
    sl_source_free(&p.fs);
    free(p.error);
    return ok;
}
