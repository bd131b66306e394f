/* The frame loop, change tracking, programs, statistics and lifecycle of the renderer.
 * See renderer.h (its interface) and renderer_internal.h (how its files divide the work). */
#include "render/texture_prefetch.h"
#include "render/renderer_internal.h"
#include "plugin_lights.h"
#include "render/post.h"
#include "log.h"
#include "startup.h"
#include <shadelab/gl.h>
#include <stdlib.h>
#include <string.h>
#include <cglm/cglm.h>
#include <sys/stat.h>

/* ------------------------------------------------------------------ programs -------- */

sl_program *sl_renderer_load_program(sl_app *app, int owner, const sl_program_desc *in) {
    sl_renderer *r = R(app);
    sl_program_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    if (!d.vertex || !d.fragment) {
        SL_ERROR("load_program: vertex and fragment files are required");
        return NULL;
    }
    char err[16384] = "";
    const char *dir = owner >= 0 ? app->plugins.items[owner]->resource_dir : sl_shader_dir();
    /* Lazy creation (docs/design-notes.md): the files are read now (a missing one is an error
     * here), the GLSL compiles at the program's first program_id(), i.e. when a pass that uses it
     * first runs. On llvmpipe a compile costs real CPU, and many programs never run (fxaa while
     * TAA is chosen, a plugin's variant for a mode not in use). */
    sl_program *p = sl_program_from_files_deferred(dir, d.vertex, d.fragment, d.defines, err, sizeof err);
    if (!p->deferred && !p->id) SL_ERROR("%s", err);
    p->owner = owner;
    sl_program **grown = realloc(r->programs, (r->program_count + 1) * sizeof *r->programs);
    if (!grown) {
        SL_ERROR("program %s: out of memory", d.fragment);
        return p; /* usable; not freed with the renderer */
    }
    r->programs = grown;
    r->programs[r->program_count++] = p;
    return p;
}

unsigned sl_renderer_program_id(sl_program *p) { return sl_program_id(p); }

void sl_renderer_blame_plugin(sl_app *app, int k, const char *err) {
    sl_renderer *r = R(app);
    for (int i = 0; i < r->blamed_count; i++)
        if (r->blamed[i].plugin == k) return; /* the same chunk breaks every material: one message */
    if (r->blamed_count == SL_MAX_PLUGINS) return; /* one entry per plugin at most */
    r->blamed[r->blamed_count].plugin = k;
    r->blamed[r->blamed_count++].why = strdup(err);
}

int sl_renderer_failed_plugin(sl_app *app, char *err, size_t n) {
    sl_renderer *r = R(app);
    if (r && r->blamed_count) {
        int k = r->blamed[0].plugin;
        snprintf(err, n, "%s", r->blamed[0].why);
        free(r->blamed[0].why);
        memmove(r->blamed, r->blamed + 1, --r->blamed_count * sizeof r->blamed[0]);
        return k;
    }
    for (int i = 0; r && i < r->program_count; i++) {
        sl_program *p = r->programs[i];
        if (p->owner < 1 || p->id || p->deferred || !p->error || p->failure_reported) continue;
        p->failure_reported = true;
        snprintf(err, n, "%s: %s", p->label ? p->label : "program", p->error);
        return p->owner;
    }
    return -1;
}

/* Plugins switched off because their GLSL failed to compile get another chance at a hot reload
 * (the files may be fixed): on again, their programs' failures reportable again. */
static void retry_failed_plugins(sl_app *app) {
    sl_renderer *r = R(app);
    for (int k = 1; k < app->plugins.count; k++) {
        sl_plugin_rec *rec = app->plugins.items[k];
        if (!rec->glsl_failed) continue;
        rec->glsl_failed = false;
        rec->ok = true;
        free(rec->disabled_reason);
        rec->disabled_reason = NULL;
        app->params.version++;
        app->params.recompile_version++;
        r->plan_dirty = true;
        if (k < 64) r->retried |= 1ull << k;
        for (int i = 0; i < r->program_count; i++)
            if (r->programs[i]->owner == k) r->programs[i]->failure_reported = false;
    }
}

int sl_renderer_reload_shaders(sl_app *app) {
    sl_renderer *r = R(app);
    int failures = 0;
    char err[16384];
    r->programs_version++;
    retry_failed_plugins(app);
    r->reloading = true;
    for (int i = 0; i < r->program_count; i++) {
        sl_program *p = r->programs[i];
        const char *dir = p->owner >= 0 ? app->plugins.items[p->owner]->resource_dir : sl_shader_dir();
        if (!sl_program_rebuild_files(p, dir, err, sizeof err)) { SL_ERROR("%s", err); failures++; }
    }
    /* composed programs: recompose everything; failures keep the previous variant program */
    int before = sl_log_count(SL_LOG_ERROR);
    for (int i = 0; i < r->cache.count; i++) r->cache.items[i]->stale = true; /* compiled from old files */
    sl_gpu_compose_all(app);
    r->reloading = false;
    r->retried = 0;
    failures += sl_log_count(SL_LOG_ERROR) - before;
    /* Stamp the files' current mtimes on every source, including programs whose rebuild failed
     * and cache entries no longer in use: otherwise their stale mtimes make the poll reload (and
     * re-print the error) every time, forever. A later edit changes the mtime again. */
    for (int i = 0; i < r->program_count + r->cache.count; i++) {
        sl_program *p = i < r->program_count ? r->programs[i] : r->cache.items[i - r->program_count];
        sl_source *src[4] = {&p->vs, &p->fs, &p->tcs, &p->tes};
        for (int k = 0; k < 4; k++)
            for (int f = 1; f < src[k]->file_count; f++) {
                struct stat st;
                if (stat(src[k]->files[f], &st) == 0) src[k]->mtimes[f] = st.st_mtime;
            }
    }
    return failures;
}

static bool any_source_changed(sl_renderer *r) {
    for (int i = 0; i < r->program_count; i++)
        if (sl_source_changed(&r->programs[i]->vs) || sl_source_changed(&r->programs[i]->fs)) return true;
    for (int i = 0; i < r->cache.count; i++)
        if (sl_source_changed(&r->cache.items[i]->vs) || sl_source_changed(&r->cache.items[i]->fs) ||
            sl_source_changed(&r->cache.items[i]->tcs) || sl_source_changed(&r->cache.items[i]->tes))
            return true;
    return false;
}


/* ------------------------------------------------------------------ frame ----------- */

/* What the graph's plan is made of besides the size: which plugins are on and the core's
 * settings (core.ssaa). A parameter change that leaves it alone keeps the plan, its targets and
 * what they hold, so passes whose declared dependencies did not move stay skipped (pass.h,
 * sl_depends). */
static uint64_t plan_key(sl_app *app) {
    uint64_t h = 0;
    for (int i = 0; i < app->plugins.count; i++) {
        bool on = sl_plugin_enabled(&app->plugins, i);
        h = sl_hash64(&on, sizeof on, h);
    }
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope != SL_SCOPE_GLOBAL || strcmp(q->owner, "core")) continue;
        h = sl_hash64(&q->value.b, sizeof q->value.b, h);
        h = sl_hash64(&q->value.i, sizeof q->value.i, h);
        h = sl_hash64(q->value.f, sizeof q->value.f, h);
    }
    return h;
}

static void recompose(sl_app *app) {
    sl_renderer *r = R(app);
    /* a new debug view changes every program's output without any other version moving */
    if ((r->seen_debug_view == NULL) != (app->debug_view == NULL) ||
        (app->debug_view && strcmp(app->debug_view, r->seen_debug_view)))
        r->programs_version++;
    sl_gpu_compose_all(app);
    free(r->seen_debug_view);
    r->seen_debug_view = app->debug_view ? strdup(app->debug_view) : NULL;
    r->seen_recompile = app->params.recompile_version;
    r->seen_materials = app->materials_version;
}

static void refresh(sl_app *app) {
    sl_renderer *r = R(app);
    /* a plugin owning lights switched on or off: its lights with it (plugin_lights.h). Not on the
     * first frame, which packs every light anyway: a version moved there would read as motion to
     * the frame-time budget, which samples the versions before this */
    uint64_t owners = sl_plugin_lights_owners_on(app);
    if (owners != r->seen_light_owners && r->frames_run) app->lights_version++;
    r->seen_light_owners = owners;
    bool compose = sl_renderer_compose_pending(app); /* before the lights' version is marked seen */
    bool lights_changed = r->seen_lights_version != app->lights_version;
    if (lights_changed || (sl_gpu_lights_animated(app) && r->seen_light_time != app->time)) sl_gpu_pack_lights(app);
    r->seen_light_time = app->time;
    /* node TRS animations (glTF): the nodes posed at this frame's time */
    if (app->scene.anim_channel_count) sl_scene_animate(&app->scene, app->time);
    sl_deform_frame(app); /* skinned and morphing meshes posed for every pass of the frame */
    if (compose) recompose(app);
    r->seen_lights_version = app->lights_version;
    /* a material became blended or stopped being (alpha_blend): the forward-blend pass comes or goes */
    if (sl_gpu_scene_has_blended(app) != r->blend_planned) r->plan_dirty = true;
    /* ... a material got or lost a SCENE_BEHIND hook: the forward-behind pass comes or goes */
    if (sl_gpu_scene_has_behind(app) != r->behind_planned) r->plan_dirty = true;
    if (r->seen_param_version != app->params.version) {
        /* enabling/disabling a plugin changes the pass list */
        uint64_t key = plan_key(app);
        if (key != r->plan_key) r->plan_dirty = true;
        r->plan_key = key;
        /* passes whose inputs or outputs follow their parameters (sl_pass_desc.io, ABI 1.13) */
        for (int i = 0; i < app->plugins.pass_count; i++)
            if (sl_plugins_update_pass_io(&app->plugins, i)) r->plan_dirty = true;
        r->seen_param_version = app->params.version;
        sl_gpu_apply_anisotropy(app);
    }
    if (r->plan_dirty) sl_graph_plan(app);
}

/* Edits of global parameters since the start, not counting the viewport-only ones (a new render
 * scale is no edit of the image: a temporal method keeps its history, pass.h, edits_version). */
static uint64_t param_edits(sl_app *app) {
    sl_renderer *r = R(app);
    if (app->params.version == r->edits_seen_version) return r->param_edits;
    uint64_t h = 0;
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope != SL_SCOPE_GLOBAL || sl_graph_viewport_only(q)) continue;
        h = sl_hash64(q->full_id, strlen(q->full_id), h);
        h = sl_hash64(&q->value.b, sizeof q->value.b, h);
        h = sl_hash64(&q->value.i, sizeof q->value.i, h);
        h = sl_hash64(q->value.f, sizeof q->value.f, h);
        if (q->value.s) h = sl_hash64(q->value.s, strlen(q->value.s), h);
    }
    if (h != r->edits_key || !r->edits_seen_version) r->param_edits++;
    r->edits_key = h;
    r->edits_seen_version = app->params.version;
    return r->param_edits;
}

static void fill_frame(sl_app *app, int acc_index, int acc_count) {
    sl_renderer *r = R(app);
    sl_frame *f = &r->frame;
    f->struct_size = sizeof *f;
    f->index = app->frame_index;
    f->time = app->time;
    f->width = r->width;
    f->height = r->height;
    f->output_width = r->out_width;
    f->output_height = r->out_height;
    app->camera.aspect = (float)r->width / (float)(r->height ? r->height : 1);
    sl_camera_matrices(&app->camera, f->view, f->proj);
    glm_mat4_mul((vec4 *)f->proj, (vec4 *)f->view, (vec4 *)f->view_proj);
    sl_camera_position(&app->camera, f->camera_pos);
    memcpy(f->scene_min, app->scene.bounds_min, 12);
    memcpy(f->scene_max, app->scene.bounds_max, 12);
    f->camera_version = app->camera.version;
    /* geometry changes every frame when a vertex hook (displacement, animation over sl_time)
     * is active; otherwise only when the scene is reloaded */
    bool animated = false;
    for (int i = 0; i < app->plugins.chunk_count && !animated; i++)
        animated = app->plugins.chunks[i].d.hook == SL_HOOK_VERTEX && sl_plugin_enabled(&app->plugins, app->plugins.chunks[i].owner);
    animated = animated || app->scene.anim_channel_count > 0; /* animated nodes move geometry too */
    f->geometry_version = animated ? app->frame_index + 1 : 0;
    f->lights_version = r->lights_packed; /* changes with every edit and every animated frame */
    /* + programs reloaded or a new debug view: what a pass shows may change */
    f->params_version = app->params.version + app->materials_version + r->programs_version;
    f->edits_version = param_edits(app) + app->materials_version + r->programs_version + app->lights_version +
                       r->forced_starts;
    f->accumulate_index = acc_index;
    f->accumulate_count = acc_count;
    /* temporal antialiasing (ABI 1.6): the previous frame's camera, the unjittered view-projection,
     * then the jitter plugins asked for in begin_frame (apply_jitter) */
    memcpy(f->unjittered_view_proj, f->view_proj, sizeof f->view_proj);
    memcpy(f->prev_view_proj, r->have_prev ? r->prev_view_proj : f->view_proj, sizeof f->view_proj);
    f->jitter[0] = f->jitter[1] = 0;
}

/* Offsets proj and view_proj by the requested jitter in pixels: NDC += 2·jitter/size, i.e. the
 * rows x and y of the projection gain the w row times the offset (perspective or orthographic).
 * With core.ssaa = k the offset is divided by k: the k × k samples of a pixel cover it already,
 * and the jitter moves each within its own cell, so a still of jittered frames is the pixel's box
 * filter (a whole pixel's jitter moved the grid across the neighbours: a box filtered by a box,
 * two pixels wide). sl_frame.jitter is the offset applied. */
static void apply_jitter(sl_renderer *r) {
    sl_frame *f = &r->frame;
    float k = r->ssaa > 1 ? (float)r->ssaa : 1.0f;
    float jx = r->jitter_req[0] / k, jy = r->jitter_req[1] / k;
    float tx = 2.0f * jx / (float)(f->width ? f->width : 1);
    float ty = 2.0f * jy / (float)(f->height ? f->height : 1);
    if (tx == 0 && ty == 0) return;
    for (int c = 0; c < 4; c++) {
        f->proj[c * 4 + 0] += tx * f->proj[c * 4 + 3];
        f->proj[c * 4 + 1] += ty * f->proj[c * 4 + 3];
    }
    glm_mat4_mul((vec4 *)f->proj, (vec4 *)f->view, (vec4 *)f->view_proj);
    f->jitter[0] = jx;
    f->jitter[1] = jy;
}

/* ABI 1.9, sl_frame.sample_index: counts the frames since the view or an edit last changed (what
 * a TAA still averages: consecutive frames with the same camera, geometry, lights, edits and
 * size; the jitter is not part of it, it is applied after). Called once per frame, before the
 * plugins' begin_frame. */
static void still_count(sl_renderer *r) {
    const sl_frame *f = &r->frame;
    uint64_t v[] = {f->camera_version, f->geometry_version, f->lights_version, f->edits_version,
                    (uint64_t)f->width << 32 | (uint32_t)f->height};
    uint64_t key = sl_hash64(v, sizeof v, 0);
    key = sl_hash64(f->view, sizeof f->view, key);
    key = sl_hash64(f->proj, sizeof f->proj, key);
    bool same = r->still_valid && key == r->still_key && r->still_last_frame + 1 == r->frames_run;
    r->still_run = same && r->still_run < (1 << 30) ? r->still_run + 1 : 0;
    r->still_key = key;
    r->still_last_frame = r->frames_run;
    r->still_valid = true;
}

/* The sample fields of sub-frame acc_index of acc_count, once the plugins asked for their still. */
static void fill_sample(sl_renderer *r, int acc_index, int acc_count) {
    if (r->forced_count > 0) {
        r->frame.sample_count = r->forced_count;
        r->frame.sample_index = r->forced_index;
        return;
    }
    int still = r->still_frames > 1 ? r->still_frames : 1;
    r->frame.sample_count = still * acc_count;
    r->frame.sample_index = (r->still_run % still) * acc_count + acc_index;
}

void sl_renderer_set_jitter(sl_app *app, float x, float y) {
    sl_renderer *r = R(app);
    if (!r || !(x == x) || !(y == y)) return;
    r->jitter_req[0] = x < -0.5f ? -0.5f : x > 0.5f ? 0.5f : x;
    r->jitter_req[1] = y < -0.5f ? -0.5f : y > 0.5f ? 0.5f : y;
}

void sl_renderer_set_texture_lod_bias(sl_app *app, float bias) {
    sl_renderer *r = R(app);
    if (r && bias == bias) r->lod_bias_req = bias < -4 ? -4 : bias > 4 ? 4 : bias;
}

void sl_renderer_set_still_frames(sl_app *app, int frames) {
    sl_renderer *r = R(app);
    if (r && frames > r->still_frames) r->still_frames = frames > 4096 ? 4096 : frames;
}

void sl_renderer_force_sample(sl_app *app, int index, int count) {
    sl_renderer *r = R(app);
    if (!r || count < 1 || index < 0 || index >= count) return;
    r->forced_index = index;
    r->forced_count = count;
    r->forced_starts++;
}

int sl_renderer_still_frames(sl_app *app) {
    sl_renderer *r = R(app);
    return r && r->still_frames > 1 ? r->still_frames : 1;
}

bool sl_renderer_scene_animates(sl_app *app) { return app->scene.anim_channel_count || sl_gpu_lights_animated(app); }

bool sl_renderer_at_rest(sl_app *app) {
    sl_renderer *r = R(app);
    return r && r->still_valid && r->still_run + 1 >= sl_renderer_still_frames(app) && !sl_renderer_compose_pending(app) &&
           !sl_renderer_scene_animates(app) && !sl_renderer_materials_use_uniform(app, "sl_time");
}

/* A plugin set its own light in begin_frame (host set_light, ABI 1.22): this frame is lit by the
 * new state. The frame's versions stay as the plugins saw them in begin_frame (what moved the
 * light, an edit, changed them already; a version that moved now would look like motion to a
 * temporal method in the next frame and restart its still); passes that depend on the lights
 * see the move through plugin_light_moves (graph_run.c). */
static void plugin_lights_moved(sl_app *app) {
    sl_renderer *r = R(app);
    app->plugin_lights_moved = false;
    recompose(app); /* a plugin light that came or went changes the programs' light types */
    uint64_t packed = r->lights_packed;
    sl_gpu_pack_lights(app);
    r->lights_packed = packed;
    r->plugin_light_moves++;
}

bool sl_renderer_frame(sl_app *app, int unused_index, int unused_count) {
    sl_renderer *r = R(app);
    if (!r) return false;
    refresh(app);
    double t0 = sl_now_ms();
    r->stats.pass_count = 0;
    r->stats.draw_calls = r->stats.reused_draw_calls = 0;
    r->stats.triangles = 0;
    r->timing = app->opt.timings || r->timing_next;
    r->timing_next = false;
    r->stats.timing_mode = !r->timing ? "off" : r->finish_timing ? "glfinish" : "timer-query";
    r->jitter_req[0] = r->jitter_req[1] = 0;
    r->lod_bias_req = 0;
    r->still_frames = 0;
    fill_frame(app, 0, 1);
    r->frames_run++;
    still_count(r);
    r->frame.sample_index = 0, r->frame.sample_count = 1; /* set once the plugins asked (below) */
    for (int i = 1; i < app->plugins.count; i++) {
        sl_plugin_rec *pr = app->plugins.items[i];
        if (pr->active && pr->desc.begin_frame && sl_plugin_enabled(&app->plugins, i)) pr->desc.begin_frame(pr->user, &r->frame);
    }
    if (app->plugin_lights_moved) plugin_lights_moved(app);
    if (sl_startup_recording()) sl_startup_mark("frame %d: plugins' begin_frame", (int)app->frame_index);
    apply_jitter(r);
    sl_gpu_apply_lod_bias(app, r->lod_bias_req);
    int count = app->opt.accumulate > 1 && !r->forced_count ? app->opt.accumulate : 1;
    fill_sample(r, 0, count);
    int post_begin = r->pass_count;
    for (int i = 0; i < r->pass_count; i++)
        if (r->passes[i].d->stage >= SL_STAGE_POST) { post_begin = i; break; }
    /* which passes write "display" directly this frame (accumulated frames: only post passes) */
    sl_graph_route_display(app, count > 1 ? post_begin : 0, app->opt.keep_color);
    sl_post_route(app, count > 1 ? post_begin : 0); /* pointwise passes fused into the pass before */
    if (count == 1) {
        sl_graph_run_range(app, 0, r->pass_count);
    } else {
        /* average the linear HDR colour of `count` sub-frames before any post pass */
        static const sl_target_desc mean_desc = {.name = "accumulate.mean", .format = SL_FORMAT_RGBA32F};
        sl_graph_add_target(r, &mean_desc, post_begin, true); /* the size of "color" there */
        resource *mean = sl_graph_find(r, "accumulate.mean");
        resource *color = sl_graph_find(r, sl_graph_name_at(r, post_begin, "color", false));
        unsigned fbo;
        glCreateFramebuffers(1, &fbo);
        for (int k = 0; k < count; k++) {
            fill_frame(app, k, count);
            fill_sample(r, k, count);
            apply_jitter(r);
            for (int i = 0; i < post_begin; i++) r->passes[i].has_run = false; /* sub-frames differ */
            sl_graph_run_range(app, 0, post_begin);
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, mean->tex[1 - mean->current], 0);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, mean->w, mean->h);
            unsigned accum = sl_program_id(r->accum_prog);
            glUseProgram(accum);
            glBindTextureUnit(0, color->tex[color->current]);
            glBindTextureUnit(1, mean->tex[mean->current]);
            glUniform1i(glGetUniformLocation(accum, "sl_color"), 0);
            glUniform1i(glGetUniformLocation(accum, "sl_previous_mean"), 1);
            glUniform1f(glGetUniformLocation(accum, "sl_weight"), 1.0f / (k + 1));
            sl_renderer_draw_fullscreen(app, NULL);
            mean->current = 1 - mean->current;
        }
        /* the mean becomes "color" for the post passes */
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color->tex[color->current], 0);
        unsigned src;
        glCreateFramebuffers(1, &src);
        glNamedFramebufferTexture(src, GL_COLOR_ATTACHMENT0, mean->tex[mean->current], 0);
        glBlitNamedFramebuffer(src, fbo, 0, 0, mean->w, mean->h, 0, 0, color->w, color->h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glDeleteFramebuffers(1, &src);
        glDeleteFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        color->version++;
        fill_frame(app, 0, 1);
        fill_sample(r, 0, 1);
        apply_jitter(r);
        sl_graph_run_range(app, post_begin, r->pass_count);
    }
    /* programs in use, for the structural zero-cost checks */
    r->stats.program_count = 0;
    for (int m = 0; m < app->scene.material_count && r->stats.program_count < 255; m++) {
        sl_program *p = r->materials[m].forward.program;
        if (p) r->stats.program_hashes[r->stats.program_count++] = p->hash;
    }
    r->stats.frame_ms = sl_now_ms() - t0;
    r->forced_count = 0; /* sl_renderer_force_sample: one frame */
    memcpy(r->prev_view_proj, r->frame.view_proj, sizeof r->prev_view_proj);
    memcpy(r->prev_unjittered_vp, r->frame.unjittered_view_proj, sizeof r->prev_unjittered_vp);
    r->prev_time = r->frame.time;
    /* each node's world matrix this frame: the previous model matrix of the next frame's motion
     * vectors (glTF node animations move nodes) */
    if (r->prev_world_count != app->scene.node_count) {
        free(r->prev_world);
        r->prev_world = calloc(app->scene.node_count + 1, sizeof *r->prev_world);
        r->prev_world_count = app->scene.node_count;
    }
    for (int i = 0; i < app->scene.node_count; i++) memcpy(r->prev_world[i], app->scene.nodes[i].world, sizeof r->prev_world[i]);
    r->have_prev = true;
    app->frame_index++;
    sl_renderer_present(app);
    return true;
}

void sl_renderer_finish(sl_app *app) {
    if (app->gl_ready) glFinish();
}

void sl_renderer_present(sl_app *app) {
    sl_renderer *r = R(app);
    resource *disp = r ? sl_graph_find(r, "display") : NULL;
    if (!app->backend.has_window || !disp) return;
    unsigned src;
    glCreateFramebuffers(1, &src);
    glNamedFramebufferTexture(src, GL_COLOR_ATTACHMENT0, disp->tex[disp->current], 0);
    /* the window's size: larger than the image when core.render_scale < 1 (scaled up, bilinear) */
    int w = app->backend.width, h = app->backend.height;
    bool same = w == disp->w && h == disp->h;
    glBlitNamedFramebuffer(src, 0, 0, 0, disp->w, disp->h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, same ? GL_NEAREST : GL_LINEAR);
    glDeleteFramebuffers(1, &src);
}

bool sl_renderer_compose_pending(sl_app *app) {
    sl_renderer *r = R(app);
    if (!r) return false;
    bool view_changed = (r->seen_debug_view == NULL) != (app->debug_view == NULL) ||
                        (app->debug_view && strcmp(app->debug_view, r->seen_debug_view));
    return view_changed || r->seen_lights_version != app->lights_version ||
           r->seen_recompile != app->params.recompile_version || r->seen_materials != app->materials_version;
}

const sl_frame_stats *sl_renderer_stats(sl_app *app) { return R(app) ? &R(app)->stats : NULL; }

/* What the frame ended with under `name` ("color" after an upscaler: its output-size one). */
static resource *final_resource(sl_renderer *r, const char *name) {
    return r ? sl_graph_find(r, sl_graph_name_at(r, r->pass_count, name, false)) : NULL;
}

bool sl_renderer_read_size(sl_app *app, const char *name, int *w, int *h) {
    resource *e = final_resource(R(app), name);
    if (e) *w = e->w, *h = e->h;
    return e != NULL;
}

bool sl_renderer_read(sl_app *app, const char *name, float *rgba) {
    sl_renderer *r = R(app);
    resource *e = final_resource(r, name);
    if (!e) return false;
    if (!strcmp(name, "color") && !r->color_final) {
        SL_ERROR("the last frame wrote \"display\" directly and kept no final \"color\" (set keep_color before "
                 "rendering to read the linear image)");
        return false;
    }
    size_t row = (size_t)e->w * 4;
    float *tmp = malloc(row * e->h * sizeof(float));
    glGetTextureImage(e->tex[e->current], 0, GL_RGBA, GL_FLOAT, (int)(row * e->h * sizeof(float)), tmp);
    for (int y = 0; y < e->h; y++) memcpy(rgba + row * y, tmp + row * (e->h - 1 - y), row * sizeof(float));
    free(tmp);
    /* the display is opaque: passes writing it on the fly leave alpha as they wrote it (no mask,
     * graph_targets.c) */
    if (!strcmp(name, "display"))
        for (size_t i = 0; i < (size_t)e->w * e->h; i++) rgba[i * 4 + 3] = 1.0f;
    return true;
}

void sl_renderer_request_timing(sl_app *app) {
    if (R(app)) R(app)->timing_next = true;
}

void sl_renderer_invalidate(sl_app *app) {
    if (R(app)) R(app)->plan_dirty = true;
}

void sl_renderer_resize(sl_app *app, int w, int h, int out_w, int out_h) {
    sl_renderer *r = R(app);
    if (!r || w < 1 || h < 1 || out_w < 1 || out_h < 1) return;
    if (out_w != r->out_width || out_h != r->out_height) r->plan_dirty = true; /* SL_SIZE_OUTPUT targets */
    r->out_width = out_w;
    r->out_height = out_h;
    if (w == r->width && h == r->height) return;
    r->width = w;
    r->height = h;
    r->plan_dirty = true;
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *pr = app->plugins.items[i];
        if (pr->active && pr->desc.resize) pr->desc.resize(pr->user, w, h);
    }
}

void sl_renderer_explain(sl_app *app, FILE *f) {
    sl_renderer *r = R(app);
    fprintf(f, "passes (in order; ms from the last frame, %s timing):\n", r->stats.timing_mode);
    for (int i = 0; i < r->pass_count; i++) {
        graph_pass *g = &r->passes[i];
        const sl_pass_stat *st = NULL;
        for (int k = 0; k < r->stats.pass_count; k++)
            if (!strcmp(r->stats.passes[k].name, g->d->name)) st = &r->stats.passes[k];
        bool ran = st && st->ran;
        if (st && st->fused_into) {
            fprintf(f, "  %-24s %-18s fused into %s (its function runs in that pass's draw)\n", g->d->name,
                    g->owner >= 0 ? app->plugins.items[g->owner]->id : "core", st->fused_into);
            continue;
        }
        fprintf(f, "  %-24s %-18s %s %8.3f ms%s\n", g->d->name, g->owner >= 0 ? app->plugins.items[g->owner]->id : "core",
                g->broken ? "BROKEN " : ran ? "ran    " : "skipped", ran ? st->ms : g->last_ms,
                ran || g->broken ? "" : g->has_run ? " (when it last ran; unchanged since)" : " (inactive: never ran)");
    }
    fprintf(f, "materials (program hash: chunks):\n");
    for (int m = 0; m < app->scene.material_count; m++) {
        material_rt *mr = &r->materials[m];
        fprintf(f, "  %-20s %016llx  %s\n", app->scene.materials[m].name,
                mr->forward.program ? (unsigned long long)mr->forward.program->hash : 0ull, mr->forward.chunks ? mr->forward.chunks : "");
    }
    int distinct = 0;
    for (int i = 0; i < r->cache.count; i++) distinct += r->cache.items[i]->id != 0;
    fprintf(f, "composed programs compiled: %d; draw calls last frame: %d; frame %.3f ms\n", distinct, r->stats.draw_calls,
            r->stats.frame_ms);
    fprintf(f, "plugins:\n");
    for (int i = 0; i < app->plugins.count; i++)
        fprintf(f, "  %-20s %s\n", app->plugins.items[i]->id,
                !app->plugins.items[i]->ok ? "disabled (error)" : sl_plugin_enabled(&app->plugins, i) ? "enabled" : "off (costs nothing)");
}

/* ------------------------------------------------------------------ lifecycle ------- */

bool sl_renderer_create(sl_app *app, char *err, size_t n) {
    sl_renderer *r = calloc(1, sizeof *r);
    app->renderer = (struct sl_renderer *)r;
    r->width = r->out_width = app->backend.width;
    r->height = r->out_height = app->backend.height;
    r->upscaler = -1;
    r->finish_timing = app->opt.finish_timing || !app->backend.is_gpu;
    glGenQueries(64, r->queries);
    glCreateVertexArrays(1, &r->empty_vao);
    /* vertex colours (location 6, scene_gpu.c): a mesh without them drawn by a program that reads
     * them gets the attribute's current value, context state set once here: white (1, 1, 1, 1),
     * where a generic attribute's default is (0, 0, 0, 1) */
    glVertexAttrib4f(6, 1, 1, 1, 1);
    /* created lazily like every stand-alone program: most frames never display to a window,
     * accumulate or resolve supersampling */
    r->display_prog = sl_program_from_files_deferred(NULL, "sl:fullscreen.vert", "sl:display.frag", NULL, err, n);
    if (!r->display_prog->deferred) return false;
    r->accum_prog = sl_program_from_files_deferred(NULL, "sl:fullscreen.vert", "sl:accumulate.frag", NULL, err, n);
    if (!r->accum_prog->deferred) return false;
    r->resolve_prog = sl_program_from_files_deferred(NULL, "sl:fullscreen.vert", "sl:resolve.frag", NULL, err, n);
    if (!r->resolve_prog->deferred) return false;
    /* the core's own programs hot-reload like plugin programs */
    r->programs = malloc(3 * sizeof *r->programs);
    r->programs[0] = r->display_prog;
    r->programs[1] = r->accum_prog;
    r->programs[2] = r->resolve_prog;
    r->display_prog->owner = r->accum_prog->owner = r->resolve_prog->owner = -1;
    r->program_count = 3;
    return true;
}

bool sl_renderer_load_scene(sl_app *app, char *err, size_t n) {
    sl_renderer *r = R(app);
    sl_scene *s = &app->scene;
    r->meshes = calloc(s->mesh_count + 1, sizeof *r->meshes);
    for (int i = 0; i < s->mesh_count; i++) {
        sl_gpu_upload_mesh(&r->meshes[i], &s->meshes[i].data);
        sl_deform_upload(app, i);
    }
    r->materials = calloc(s->material_count + 1, sizeof *r->materials);
    sl_gpu_pack_lights(app);
    r->seen_lights_version = app->lights_version;
    /* known before the first composition, so that the plan does not compose every material
     * again with motion vectors (a second GLSL compile of each program at start-up) */
    r->motion = sl_graph_wants_motion(app);
    r->normal = sl_graph_wants_normal(app);
    sl_gpu_compose_all(app);
    sl_texture_prefetch_finish(app); /* every texture the scene uses is loaded: join, free the rest */
    r->seen_recompile = app->params.recompile_version;
    r->seen_materials = app->materials_version;
    r->seen_param_version = app->params.version;
    r->plan_key = plan_key(app);
    r->seen_debug_view = app->debug_view ? strdup(app->debug_view) : NULL;
    /* a program a plugin broke is made again without it before the first frame (app.c) */
    for (int m = 0; m < s->material_count && !r->blamed_count; m++)
        if (!r->materials[m].forward.program) {
            snprintf(err, n, "material \"%s\": its program failed to compile (see above)", s->materials[m].name);
            return false;
        }
    sl_graph_plan(app);
    return true;
}

bool sl_renderer_poll_reload(sl_app *app) {
    sl_renderer *r = R(app);
    if (!r || !any_source_changed(r)) return false;
    int failures = sl_renderer_reload_shaders(app);
    SL_INFO("shaders changed on disk: reloaded (%d failed, last good programs kept)", failures);
    return true;
}

void sl_renderer_destroy(sl_app *app) {
    sl_renderer *r = R(app);
    if (!r) return;
    sl_graph_free(r);
    if (r->behind_tex) glDeleteTextures(1, &r->behind_tex); /* the scene behind's capture (graph_run.c) */
    for (int i = 0; r->meshes && i < app->scene.mesh_count; i++) {
        gpu_mesh *g = &r->meshes[i];
        sl_deform_free(g);
        glDeleteVertexArrays(1, &g->vao);
        glDeleteBuffers(6, g->vbo);
        glDeleteBuffers(1, &g->ibo);
    }
    free(r->meshes);
    for (int i = 0; i < r->texture_count; i++) {
        glDeleteTextures(1, &r->textures[i].id);
        free(r->textures[i].key);
    }
    free(r->textures);
    for (int m = 0; r->materials && m < app->scene.material_count; m++) {
        free(r->materials[m].forward.chunks);
        free(r->materials[m].depth.chunks);
        for (int k = 0; k < r->materials[m].override_count; k++) {
            free(r->materials[m].overrides[k].model);
            free(r->materials[m].overrides[k].fragment);
            free(r->materials[m].overrides[k].v.chunks);
        }
    }
    free(r->materials);
    for (int i = 0; i < r->cache.count; i++) sl_program_free(r->cache.items[i]);
    free(r->cache.items);
    for (int i = 0; i < r->program_count; i++) sl_program_free(r->programs[i]);
    sl_program_free(r->view_prog);
    free(r->programs);
    glDeleteVertexArrays(1, &r->empty_vao);
    if (r->deform_prog) glDeleteProgram(r->deform_prog);
    if (r->light_buffer) glDeleteBuffers(1, &r->light_buffer);
    glDeleteQueries(64, r->queries);
    free(r->lights);
    free(r->prev_world);
    free(r->seen_debug_view);
    for (int i = 0; i < r->blamed_count; i++) free(r->blamed[i].why);
    free(r);
    app->renderer = NULL;
}

