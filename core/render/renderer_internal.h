/* The renderer's private ground, shared by its files (nothing outside core/render includes it):
 *   renderer.c     frame loop, change tracking, programs, statistics, lifecycle
 *   scene_gpu.c    the scene on the GPU: meshes, textures, the light buffer, material programs, draws
 *   graph_plan.c   the render graph's plan: pass order by stage, input checks, target allocation
 *   graph_targets.c render targets and their binding (ping-pong pairs, framebuffers)
 *   graph_run.c    executing passes: change signatures, timing, the core's own passes */
#ifndef SL_RENDERER_INTERNAL_H
#define SL_RENDERER_INTERNAL_H
#include "render/renderer.h"
#include "state.h"
#include "render/forward.h"
#include "render/lod.h"
#include "plugin/plugins.h"

/* center: the object-space bounds' centre (blended draws sort on its view depth); lo, hi: the
 * object-space bounds (frustum culling; a deformed mesh is never culled: its pose leaves them),
 * radius: half their diagonal; lod: the index lists of its levels of detail in ibo once lod_built
 * (render/lod.h; index_count is level 0's; a deformed mesh has none) */
typedef struct gpu_mesh {
    unsigned vao, vbo[6], ibo; /* positions, normals, tangents, uvs, uvs1, colors (0: none) */
    int index_count;
    float center[3], lo[3], hi[3], radius;
    struct gpu_deform *deform; /* a deformed mesh's buffers (deform.c), or NULL */
    sl_lod_levels lod; bool lod_built;
} gpu_mesh;
typedef struct gpu_texture { char *key; unsigned id; } gpu_texture;

/* model: NULL = the material's own; fragment (ABI 1.7): a plugin's main, resolved path */
typedef struct override_variant { char *model; sl_forward_variant v; char *fragment; bool fullscreen; } override_variant;

/* SL_DRAW_MATERIALS variants a material keeps (model overrides, plugins' mains), composed on first use */
#define SL_MAX_OVERRIDE_VARIANTS 8

typedef struct material_rt {
    sl_forward_variant forward, depth;
    override_variant overrides[SL_MAX_OVERRIDE_VARIANTS];
    int override_count;
    bool override_overflow_reported;
    unsigned textures[SL_TEXTURE_UNIT_MATERIAL_COUNT];
} material_rt;

typedef struct resource {
    char *name;
    sl_target_desc desc;
    unsigned tex[2];      /* [1] only for ping-ponged "color" */
    int current;          /* which of tex[] holds the latest contents */
    int w, h;
    uint64_t version;     /* bumps each time a pass writes it */
    unsigned srgb_view;   /* "display": an sRGB view of tex[0] for passes writing it on the fly */
} resource;

typedef struct graph_pass {
    const sl_pass_desc *d;
    int owner;            /* plugin index; -1 = core pass */
    bool core_forward, core_display, core_resolve, core_blend, core_prepass, core_behind;
    unsigned fbo;
    uint64_t last_signature; bool has_run;
    uint64_t last_depends; /* key of sl_pass_desc.depends when it last ran (graph_run.c) */
    int last_draws;        /* draw calls of its last run (a skipped pass's are still in effect) */
    double last_ms;       /* time of the last run (for --explain when skipped since) */
    bool broken;          /* disabled at plan time (message given) */
    bool to_display;      /* this frame its "color" output is the sRGB "display" (display_on_write) */
} graph_pass;

struct sl_pass_ctx { graph_pass *pass; int out_slot[8]; int in_slot[16]; };

typedef struct sl_renderer {
    /* ---- the scene on the GPU (scene_gpu.c) ---- */
    gpu_mesh *meshes;
    gpu_texture *textures; int texture_count;
    material_rt *materials;
    int anisotropy;                               /* core.anisotropy applied to the material textures */
    float lod_bias;                               /* the LOD bias applied to them (ABI 1.21) */
    unsigned empty_vao;                           /* for attribute-less full-screen triangles */
    unsigned deform_prog; bool deform_failed;     /* deform.c's compute program (0: not built yet) */

    /* ---- lights (scene_gpu.c): the light buffer, packed by type, and what plugins see ---- */
    unsigned light_buffer;
    sl_light_info *lights; int light_count;
    const char *types[SL_MAX_LIGHT_TYPES]; int ntypes; /* the scene's light types, packing order */
    int type_range[SL_MAX_LIGHT_TYPES][2];        /* each type's [first, end) in the buffer */
    int shadowed_range[SL_MAX_LIGHT_TYPES][2];    /* its shadow casters' [first, end), packed first */
    double seen_light_time;   /* app->time of the packed lights (animated lights repack) */
    uint64_t lights_packed;   /* bumps each time the lights are packed */

    /* ---- programs (renderer.c; composition: forward.c) ---- */
    sl_program_cache cache;                       /* composed forward/depth programs */
    sl_program **programs; int program_count;     /* stand-alone programs (plugins, core) */
    sl_program *display_prog, *accum_prog, *resolve_prog;
    sl_program *view_prog; uint64_t view_key; /* the chosen pass view's display program (graph_run.c) */
    uint64_t programs_version; /* bumps on a hot reload or a new debug view (in params_version) */
    uint64_t compiled_ahead;  /* the forward programs compile_ahead last drew (graph_run.c) */
    /* plugins whose material GLSL failed to compile, with the first message, until app.c switches
     * them off (sl_renderer_failed_plugin); a hot reload keeps last good programs instead */
    struct { int plugin; char *why; } blamed[SL_MAX_PLUGINS];
    int blamed_count;
    bool reloading;        /* in a hot reload: failures keep the last good program ... */
    uint64_t retried;      /* ... but of the plugins it switched on again (bit k: plugin k) */

    /* ---- the render graph (graph_plan.c, graph_targets.c, graph_run.c) ---- */
    resource *res; int res_count;
    graph_pass *passes; int pass_count;
    bool plan_dirty;
    uint64_t plan_key;       /* plugins on/off and core settings the plan was made with (renderer.c) */
    int width, height;        /* the render size (core.render_scale of the output) */
    int out_width, out_height; /* the output's size (ABI 1.18, pass.h: SL_SIZE_OUTPUT) */
    int upscaler;             /* graph index of the upscaler (its "color" output at SL_SIZE_OUTPUT), or -1 */
    int ssaa;                 /* core.ssaa the plan was made with */
    bool rerun_passes;        /* core.rerun_passes the plan was made with: no pass skipped */
    bool blend_planned;       /* the plan holds the "forward-blend" pass (a blended material exists) */
    bool behind_planned;      /* ... the "forward-behind" pass (a material reads the scene behind it) */
    unsigned behind_tex;      /* the captured opaque scene, mipmapped (graph_run.c), and its size */
    int behind_w, behind_h, behind_format;
    sl_pass_desc display_desc; /* the core's display pass (graph_plan.c), active while color_final */
    bool color_final;     /* "color" holds the frame's final linear colour (no pass wrote display) */
    uint64_t shadow_runs;     /* runs of passes before SL_STAGE_PREPASS (SL_DEPENDS_LIGHTS) */
    sl_pass_ctx *current;     /* the pass being executed, for draw_scene */

    /* ---- what the last frame saw (renderer.c): a change recomposes or re-plans ---- */
    uint64_t seen_recompile, seen_materials, seen_lights_version, seen_param_version;
    uint64_t seen_light_owners; /* which plugins owning lights were on (plugin_lights.h) */
    uint64_t plugin_light_moves; /* times a plugin moved its own light (SL_DEPENDS_LIGHTS passes re-run) */
    /* edits of global parameters (sl_frame.edits_version): counted when their values other than
     * the viewport-only ones (sl_graph_viewport_only) changed since the parameters' last version */
    uint64_t param_edits, edits_seen_version, edits_key;
    char *seen_debug_view;

    /* ---- the frame and its sample (renderer.c) ---- */
    sl_frame frame;
    float jitter_req[2];      /* the jitter plugins asked for this frame (ABI 1.6) */
    float lod_bias_req;       /* the texture LOD bias they asked for (ABI 1.21) */
    int still_frames;         /* the frames a still needs (set_still_frames) */
    /* ABI 1.9 sample index: frames since the view or an edit last changed, and what it compares */
    int still_run;
    uint64_t still_key, still_last_frame, frames_run;
    bool still_valid;
    /* sl_renderer_force_sample: the next frame's sample (count 0: none forced), and the fresh
     * starts forced so far (part of edits_version) */
    int forced_index, forced_count;
    uint64_t forced_starts;

    /* ---- what the forward pass writes besides "color" and "depth" when a pass reads it: "normal"
     * (ABI 1.13, or the depth pre-pass writes it), motion vectors (ABI 1.6) and the previous frame ---- */
    bool normal;
    bool prepass;
    bool motion;
    bool have_prev;
    float prev_view_proj[16], prev_unjittered_vp[16];
    double prev_time;
    float (*prev_world)[16]; int prev_world_count; /* each node's world matrix last frame */

    /* ---- timing and statistics (graph_run.c) ---- */
    bool finish_timing;   /* when timing: glFinish around each pass (CPU rasterisers) */
    bool timing;          /* this frame's passes are timed (--bench, --stats, the panel asked) */
    bool timing_next;     /* sl_renderer_request_timing: time the next frame */
    unsigned queries[64]; /* GL timer queries (GPU), each read back before it is reused */
    sl_frame_stats stats;
} sl_renderer;

#define R(app) ((sl_renderer *)(app)->renderer)

/* scene_gpu.c */
void sl_gpu_upload_mesh(gpu_mesh *g, const sl_mesh_data *m);
/* deform.c: mesh mi's deformation buffers (after sl_gpu_upload_mesh; nothing for a static mesh);
 * each frame, before any pass, every deformed mesh posed at the scene's state; freeing */
void sl_deform_upload(sl_app *app, int mi);
void sl_deform_frame(sl_app *app);
void sl_deform_free(gpu_mesh *g);
void sl_gpu_apply_anisotropy(sl_app *app);   /* core.anisotropy onto every material texture */
void sl_gpu_apply_lod_bias(sl_app *app, float bias); /* this frame's LOD bias onto them */
bool sl_gpu_lights_animated(sl_app *app);
void sl_gpu_pack_lights(sl_app *app);        /* the light buffer and sl_host.lights, at app->time */
/* Lights a uniform block holds (SlLight records in GL_MAX_UNIFORM_BLOCK_SIZE, at most 64 KiB). */
int sl_gpu_light_block_capacity(void);
/* The forward programs read sl_lights[] from a uniform block when every light of the scene fits
 * (enabled or not, so a toggle never changes it), else from a storage buffer. */
bool sl_gpu_lights_in_uniform_block(sl_app *app);
void sl_gpu_compose_all(sl_app *app);        /* every material's programs and textures */
/* renderer.c: plugin k's GLSL broke a material program (message err); reported once per plugin */
void sl_renderer_blame_plugin(sl_app *app, int k, const char *err);
/* Which materials a draw takes: every one (those drawn over the scene last, back to front:
 * plugins' draw_scene), the opaque and masked ones (the forward pass), the blended ones (the
 * forward-blend pass) or the opaque ones that read the scene behind them (forward-behind). */
typedef enum sl_gpu_draw_set { SL_GPU_DRAW_ALL, SL_GPU_DRAW_OPAQUE, SL_GPU_DRAW_BLENDED, SL_GPU_DRAW_BEHIND } sl_gpu_draw_set;
void sl_gpu_draw_meshes(sl_app *app, const sl_draw_scene_desc *d, bool depth_only, sl_program *custom, sl_gpu_draw_set set);
/* glTF alphaMode BLEND: the material carries alpha_blend = true; whether any material does */
bool sl_gpu_material_blended(sl_app *app, int m);
bool sl_gpu_scene_has_blended(sl_app *app);
/* whether a material reads the scene behind it (a SCENE_BEHIND hook; blended or not: the capture
 * is made for both, forward-behind draws those not blended) */
bool sl_gpu_scene_has_behind(sl_app *app);
/* the texture unit of "depth" in the forward-blend and forward-behind passes (host.h's layout),
 * and of the captured opaque scene (shaders/scene_behind.glsl) */
#define SL_BLEND_DEPTH_UNIT SL_TEXTURE_UNIT_CORE
#define SL_SCENE_BEHIND_UNIT (SL_TEXTURE_UNIT_CORE + 1)

/* graph_targets.c */
resource *sl_graph_find(sl_renderer *r, const char *name);
/* ABI 1.18: the output-size "color" of the upscaler and every pass after it (pass.h, SL_SIZE_OUTPUT) */
#define SL_OUTPUT_COLOR "color@output"
/* The resource the pass at graph index `at` means by `name`, as an input or an output ("color"
 * after the upscaler is SL_OUTPUT_COLOR; at = pass_count: what the frame ends with). */
const char *sl_graph_name_at(const sl_renderer *r, int at, const char *name, bool output);
resource *sl_graph_resource(sl_renderer *r, const graph_pass *g, const char *name, bool output);
/* Whether pass g reads resource e (one of its inputs names it): a pass writing e ping-pongs. */
bool sl_graph_pass_reads(const sl_renderer *r, const graph_pass *g, const resource *e);
/* Allocates the target as the pass at graph index `at` declares it (its viewport, its name). */
void sl_graph_add_target(sl_renderer *r, const sl_target_desc *d, int at, bool pingpong);
void sl_graph_free(sl_renderer *r);          /* targets, passes and their framebuffers */
bool sl_graph_lists(const char *const *list, const char *name);

/* graph_plan.c: orders passes, checks inputs, allocates targets */
void sl_graph_plan(sl_app *app);
/* graph_plan.c: per frame, which passes write "display" directly (display_on_write at the end of
 * the "color" chain); the core's display pass runs only when none does. [first, end) are the
 * passes that may (accumulated frames: the post passes only). */
void sl_graph_route_display(sl_app *app, int first, bool keep_color);
/* An enabled pass reads "motion": the forward programs compute it (SL_MOTION_VECTORS). */
bool sl_graph_wants_motion(sl_app *app);
/* A pass before the forward pass reads "depth" or "normal": the depth pre-pass runs (ABI 1.13). */
bool sl_graph_wants_prepass(sl_app *app);
/* A pass reads "normal" and no pre-pass writes it: the forward programs do (SL_NORMAL_TARGET). */
bool sl_graph_wants_normal(sl_app *app);

/* graph_run.c: core.render_scale and core.budget, which change what is rendered only through the
 * viewport size and the settings the budget sets: no edit of the image (sl_frame.edits_version) */
bool sl_graph_viewport_only(const sl_param *q);
/* graph_run.c: the chosen debug view when it shows a pass's resource (SL_CHUNK_PASS_VIEW), or NULL */
const sl_chunk_reg *sl_graph_pass_view(sl_app *app);
/* graph_run.c: runs passes [begin, end), timing each */
void sl_graph_run_range(sl_app *app, int begin, int end);
double sl_now_ms(void);
#endif
