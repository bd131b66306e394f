/* The renderer: GPU scene (meshes, textures, materials), composed programs, the render graph
 * and its timing. Everything here runs with the GL context current. */
#ifndef SL_RENDERER_H
#define SL_RENDERER_H
#include <shadelab/shadelab.h>
#include <stdio.h>

struct sl_app;

/* GL basics (core programs); plugins may load programs after this. */
bool sl_renderer_create(struct sl_app *app, char *err, size_t n);
/* Uploads the scene, composes the material programs and plans the graph (after plugins activate). */
bool sl_renderer_load_scene(struct sl_app *app, char *err, size_t n);
void sl_renderer_destroy(struct sl_app *app);
/* Renders one frame through the graph (sub-frame of an accumulation when app->opt.accumulate > 1). */
bool sl_renderer_frame(struct sl_app *app, int accumulate_index, int accumulate_count);
/* Marks materials/lights/params dirty after a change (recompiles lazily). */
void sl_renderer_invalidate(struct sl_app *app);
/* Times every pass of the next frame (the panel's timing view); app->opt.timings times them all. */
void sl_renderer_request_timing(struct sl_app *app);
/* The render size (w, h: the viewport of the passes up to the upscaler) and the output's size
 * (the window's, or --size: SL_SIZE_OUTPUT targets, and "display" after an upscaler, pass.h). */
void sl_renderer_resize(struct sl_app *app, int w, int h, int out_w, int out_h);
/* Re-reads every shader file and rebuilds programs; keeps the last good program on error. */
int sl_renderer_reload_shaders(struct sl_app *app);

/* Whether the next frame recomposes programs (a recompile parameter, a material, a light or the
 * debug view changed): the viewer shows a status line over the previous image meanwhile. */
bool sl_renderer_compose_pending(struct sl_app *app);
/* Waits until the frames issued so far are rendered (glFinish): the start-up figure of a complete
 * first frame, which without timings only issued its commands. */
void sl_renderer_finish(struct sl_app *app);
/* Shows the last frame's display image in the window again (no rendering). */
void sl_renderer_present(struct sl_app *app);

/* Read-back of the last frame (rows top to bottom). */
bool sl_renderer_read(struct sl_app *app, const char *resource, float *rgba);
/* The size of what sl_renderer_read gives for `resource` (the output size after an upscaler). */
bool sl_renderer_read_size(struct sl_app *app, const char *resource, int *w, int *h);

/* Statistics of the last frame, for --stats, --explain and the structural tests. */
typedef struct sl_pass_stat {
    const char *name; const char *owner; double ms; bool ran;
    bool reused; /* skipped: nothing it declared (or its signature) changed, its outputs are this frame's */
    const char *fused_into; /* not run: its function ran inside this pass's draw (render/post.h) */
} sl_pass_stat;
typedef struct sl_frame_stats {
    sl_pass_stat passes[64]; int pass_count;
    double frame_ms;
    int draw_calls;
    int reused_draw_calls;       /* those of the passes skipped as unchanged, when they last ran */
    long triangles;              /* triangles drawn by the core's scene draws (levels of detail count theirs) */
    int program_count;
    uint64_t program_hashes[256]; /* hash of each composed program in use, sorted */
    const char *timing_mode;     /* "glfinish", "timer-query", or "off" (not asked: pass ms are 0) */
} sl_frame_stats;
const sl_frame_stats *sl_renderer_stats(struct sl_app *app);
/* Per material: the composed program's hash and which chunks it includes (for --explain). */
void sl_renderer_explain(struct sl_app *app, FILE *f);


/* Host-interface implementations (see sdk/include/shadelab/host.h). */
sl_program *sl_renderer_load_program(struct sl_app *app, int owner, const sl_program_desc *desc);
unsigned sl_renderer_program_id(sl_program *p);
/* A plugin whose GLSL failed to compile: a material program its chunks broke, or its own
 * program's first (lazy) compile. Its index, the error (naming file:line) in err; -1 when none.
 * Each plugin's material failure and each program is reported once. Hot-reload failures keep the
 * last good program and are not reported here; a hot reload gives plugins switched off for their
 * GLSL (sl_plugin_rec.glsl_failed) another chance. */
int sl_renderer_failed_plugin(struct sl_app *app, char *err, size_t n);
unsigned sl_renderer_pass_texture(struct sl_app *app, sl_pass_ctx *ctx, const char *name);
sl_status sl_renderer_bind_outputs(struct sl_app *app, sl_pass_ctx *ctx, int layer);
void sl_renderer_draw_scene(struct sl_app *app, sl_pass_ctx *ctx, const sl_draw_scene_desc *d);
void sl_renderer_draw_fullscreen(struct sl_app *app, sl_pass_ctx *ctx);
/* Whether a material's forward program (as composed now) has an active uniform `name`
 * (host->scene_uses_uniform, ABI 1.11). */
bool sl_renderer_materials_use_uniform(struct sl_app *app, const char *name);
/* host->compile_ahead (ABI 1.12): on a CPU renderer, the forward pass's draws under an empty
 * scissor now, so that llvmpipe compiles its programs (at their first draw, on this thread) while
 * the rasteriser works on what the calling pass queued. Once per set of forward programs. */
void sl_renderer_compile_ahead(struct sl_app *app);
const sl_light_info *sl_renderer_lights(struct sl_app *app, int *count);
void sl_renderer_set_jitter(struct sl_app *app, float x, float y);
void sl_renderer_set_still_frames(struct sl_app *app, int frames);
void sl_renderer_set_texture_lod_bias(struct sl_app *app, float bias); /* this frame (ABI 1.21) */
/* The largest frame count a still image needs that a plugin asked for during the last frame
 * (host set_still_frames; TAA's history), at least 1. */
int sl_renderer_still_frames(struct sl_app *app);
/* The scene plays by itself: glTF node animations or animated lights follow the clock. */
bool sl_renderer_scene_animates(struct sl_app *app);
/* The view is at rest: the still is complete (the frames since the view or an edit last changed
 * cover every frame a plugin's still asked for: TAA's history), nothing plays by itself (the
 * above, or a material reading sl_time) and no recompile is pending, so the next frame would
 * show the same image. The window then waits for an event instead of drawing it again. */
bool sl_renderer_at_rest(struct sl_app *app);
/* For measurements (shadelab-bench's noise): the next frame is a fresh start (as after an edit:
 * temporal methods restart their history) rendered as sample `index` of `count`
 * (sl_frame.sample_index/count), with no accumulation. One frame only. */
void sl_renderer_force_sample(struct sl_app *app, int index, int count);
unsigned sl_renderer_material_texture(struct sl_app *app, int material, const char *key);
#endif
