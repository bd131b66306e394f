/* Render graph passes. A pass declares the named resources it reads and writes; the core
 * orders passes by stage, checks that every input is produced earlier, allocates the targets
 * (and re-allocates them on resize), times each pass and skips passes that are inactive, whose
 * declared dependencies (sl_depends, ABI 1.8) or whose signature did not change since they last ran.
 *
 * Resources the core provides:
 *   "color"  RGBA16F (RGBA32F with --float), viewport size: linear HDR radiance. Written by the
 *            core's forward pass (stage OPAQUE). A POST pass that lists "color" both as input and
 *            output gets two different textures (ping-pong); later passes see its output.
 *            ABI 1.18: a pass whose "color" output has width SL_SIZE_OUTPUT is the frame's
 *            upscaler (a TAA upsampler): its "color" input is at the render size (the output's
 *            size times core.render_scale), its output, and "color" in every pass after it, at
 *            the output size, and so is "display" (shown without scaling). See SL_SIZE_OUTPUT.
 *   "depth"  DEPTH32F, from the forward pass, at the forward pass's size: the viewport times
 *            core.ssaa (k × k depth samples per "color" pixel when core.ssaa = k > 1; size a pass's
 *            own reads with glGetTextureLevelParameteriv, not from sl_frame). Convention: OpenGL
 *            window depth d in [0, 1], cleared to 1 (far, also where nothing is drawn), nearer is
 *            smaller (GL_LESS), NDC z = 2d − 1 of the camera's projection (sl_frame.proj): not
 *            reversed-Z, not linear. View-space distance along the view direction, perspective:
 *            proj[14] / (2d − 1 + proj[10]) (column-major indices).
 *   "motion" RG16F (ABI 1.6), from the forward pass, only while an active pass lists it as an
 *            input (otherwise the forward programs do not compute it): per pixel, this frame's
 *            screen position minus the previous frame's of the surface seen there, in UV units
 *            ([0,1] across the viewport), both without projection jitter. Covers camera motion
 *            and VERTEX hooks (evaluated at the previous frame's sl_time too); background
 *            pixels (nothing drawn) hold 0. Same size as "depth".
 *   "normal" RGBA16F (ABI 1.13), same size as "depth", only while an active pass lists it as an
 *            input: xyz the shading normal after the SURFACE hooks in view space (unit, on the
 *            viewer's side), w the GGX α the surface hooks left (1 where none sets it); 0 where
 *            nothing was drawn. GLSL: vec4 sl_normal_target(SlSurface s) in a custom main.
 * The depth pre-pass (ABI 1.13): while an enabled pass at a stage below SL_STAGE_OPAQUE lists
 * "depth" or "normal" as an input, the core's "depth-prepass" runs at SL_STAGE_DEPTH_PREPASS and
 * writes both (every opaque material with its VERTEX and SURFACE hooks, no lighting), so a pass
 * between it and the forward pass can feed the forward pass (ambient occlusion). The forward pass
 * still writes "depth" itself; "normal" keeps the pre-pass's values.
 * After the last pass on "color" the core's display pass clamps to [0,1] and applies the sRGB
 * encoding (a tone-mapping plugin runs before it, at SL_STAGE_TONEMAP). ABI 1.8: when the last
 * writers of "color" are declared display_on_write, they write "display" directly instead
 * (see sl_pass_desc) and no display pass runs; with no post pass that is the forward pass.
 *
 * Texture units a pass may use: host.h, SL_TEXTURE_UNIT_* (its own programs: the material range
 * [0, 16) or units it reserved; never another plugin's).
 */
#ifndef SHADELAB_PASS_H
#define SHADELAB_PASS_H

#ifdef __cplusplus
extern "C" {
#endif

/* A pass's place in the frame. `stage` is an order value: passes run in ascending stage, equal
 * values in plugin load order (and registration order within a plugin), so a pass that must run
 * before or after another plugin's gives itself a value between the landmarks below; any int is
 * valid. The bundled plugins' values are listed in sdk/docs/plugin-guide.md ("Pass order"). */
typedef enum sl_stage {
    SL_STAGE_SHADOW = 100,   /* light-space passes (shadow maps): spotlight-shadow */
    SL_STAGE_DEPTH_PREPASS = 190, /* ABI 1.13 name: the core's "depth-prepass" ("depth", "normal"), only
                                     while a pass before SL_STAGE_OPAQUE reads one of them */
    SL_STAGE_PREPASS = 200,  /* anything the forward pass samples (texture-space lighting): sss */
    SL_STAGE_OPAQUE = 300,   /* the core's forward pass; plugins may add passes after it (envmap's background) */
    SL_STAGE_BEHIND = 370,   /* ABI 1.17 name: the core's "forward-behind" pass (materials with a
                                SCENE_BEHIND hook, shader.h: transmission), over every opaque pass */
    SL_STAGE_BLEND = 380,    /* ABI 1.8 name: the core's "forward-blend" pass (materials with alpha_blend,
                                glTF alphaMode BLEND), over every opaque pass; temporal methods after it */
    SL_STAGE_POST = 400,     /* full-screen passes on linear HDR "color" (bloom, blurs) */
    SL_STAGE_TONEMAP = 450,  /* ABI 1.5 name: HDR → display-referred colour (tonemap's pass) */
    SL_STAGE_DISPLAY_REFERRED = 460, /* ABI 1.5 name: passes on tone-mapped colour (vignette, grain) */
    SL_STAGE_DISPLAY = 1000  /* ABI 1.5 name: the core's display encoding (sRGB); always last */
} sl_stage;

typedef enum sl_format {
    SL_FORMAT_RGBA8 = 1,
    SL_FORMAT_RGBA16F,
    SL_FORMAT_RGBA32F,
    SL_FORMAT_RG16F,
    SL_FORMAT_R32F,
    SL_FORMAT_DEPTH32F
} sl_format;

/* ABI 1.18, sl_target_desc.width: the output's size (the window's, or --size: what is shown),
 * times `scale`; `height` is ignored. The viewport (0) is the render size: the output's times
 * core.render_scale, rounded (the same when the scale is 1). A pass whose "color" output is
 * declared so is the frame's upscaler (above; the first such pass in pass order when several
 * are): it reads "color" at the render size and writes it at the output size, so "depth",
 * "motion" and "normal" stay at the render size, and passes after it get sl_frame.width and
 * height = the output size and targets of size 0 at the output size. While the upscaler does not
 * run (is_active false), the core fills its "color" by a bilinear scale-up of the render-size
 * "color". Switch the declaration with sl_pass_desc.io when the pass upscales only in some modes. */
#define SL_SIZE_OUTPUT (-1)

typedef struct sl_target_desc {
    const char *name;   /* resource name, unique in the graph ("shadow.maps") */
    sl_format format;
    int width, height;  /* 0 = viewport size (times `scale` when scale > 0); SL_SIZE_OUTPUT (1.18) */
    float scale;
    int layers;         /* > 1: a 2D array texture (e.g. one layer per shadow-casting light) */
    bool compare;       /* depth formats: enable GL_COMPARE_REF_TO_TEXTURE (hardware PCF) */
} sl_target_desc;

/* Everything a pass or hook needs to know about the frame being rendered. */
typedef struct sl_frame {
    uint32_t struct_size;
    uint64_t index;          /* frames rendered since start */
    double time;             /* seconds, the `sl_time` uniform (fixed steps with --frames) */
    int width, height;       /* viewport: the render size (see output_width, ABI 1.18) */
    float view[16], proj[16], view_proj[16]; /* column-major, camera */
    float camera_pos[3];
    float scene_min[3], scene_max[3];        /* world-space bounds of all geometry */
    /* Change counters: a pass may use them in its signature to skip work. */
    uint64_t camera_version, geometry_version, lights_version, params_version; /* params_version also
                                                moves on a hot reload and a new debug view */
    int accumulate_index;    /* 0-based frame within an accumulated render; 0 otherwise */
    int accumulate_count;    /* frames being accumulated (1 = none) */
    /* ABI 1.6, temporal antialiasing. jitter: the sub-pixel offset in pixels (x right, y up) that
     * a plugin asked for in begin_frame (host->set_jitter), already in proj and view_proj; 0 when
     * none. prev_view_proj: the previous frame's view_proj as it was rendered (its jitter
     * included); this frame's on the first frame. unjittered_view_proj: view_proj without the
     * jitter (what "motion" is computed with). */
    float jitter[2];
    float prev_view_proj[16];
    float unjittered_view_proj[16];
    /* ABI 1.6: moves with every edit (parameters, material and light values, a hot reload, the
     * debug view) and never by itself: unlike lights_version it stays put while lights animate.
     * A temporal method restarts its history on it (a live change equals a fresh start). ABI 1.18:
     * not with core.render_scale or core.budget, which change the render size (width, height), not
     * the image: a history at the output size goes on across a new render scale. */
    uint64_t edits_version;
    /* ABI 1.9: the frame's sample of the image being averaged, for stochastic shading (sample
     * sequences that continue across frames). sample_count = the frames averaged into what is
     * shown: a plugin's still (host->set_still_frames, e.g. a TAA still of n jittered frames; 1
     * when no plugin averages) times accumulate_count. sample_index in [0, sample_count) =
     * still × accumulate_count + accumulate_index, where still = the frames since the view and
     * every edit last changed (camera, geometry, lights, edits, size), modulo the still's length:
     * n consecutive unchanged frames get n distinct indices, a frame that changes anything gets
     * 0 (so does every frame while the view moves), and with nothing averaging it is
     * accumulate_index. GLSL: int sl_sample_index, sl_sample_count. A pass with
     * SL_DEPENDS_CAMERA re-runs when it moves; one that declares MATERIALS but not CAMERA (shadow
     * maps, texture-space passes) keeps the result of its last run, which saw that run's index:
     * a still does not re-run them frame after frame. */
    int sample_index, sample_count;
    /* ABI 1.18: the output's size (the window's, or --size: what is shown). width and height above
     * are the viewport: the render size (output × core.render_scale), up to and in the upscaler
     * pass, the output size in the passes after it (SL_SIZE_OUTPUT). */
    int output_width, output_height;
} sl_frame;

typedef struct sl_pass_ctx sl_pass_ctx; /* opaque: valid only inside execute() */

/* ABI 1.8: what a pass's result depends on (sl_pass_desc.depends, a bitwise or). 0, the value a
 * plugin built against an older ABI gets, means "not declared": the pass runs every frame. With a
 * declaration the core skips the pass while none of the declared things changed since it last
 * ran, provided its outputs persist: it has run since the graph was last planned (a plugin
 * switched on or off, a resize, a core setting) and no other pass writes any of its outputs (a
 * pass writing "color" in place runs every frame whatever it declares). A pass that also has a
 * `signature` runs when either its declaration or its signature says so (a signature covers what
 * the categories cannot: textures of the plugin's own that it re-made). */
typedef enum sl_depends {
    SL_DEPENDS_LIGHTS = 1u << 0,    /* light values and their animation, and whatever a shadow-stage
                                       pass (stage < SL_STAGE_DEPTH_PREPASS) ran for since (shadow
                                       maps, cascades following the camera); not the core's depth
                                       pre-pass */
    SL_DEPENDS_GEOMETRY = 1u << 1,  /* meshes, node animation, active VERTEX/DISPLACEMENT hooks,
                                       the scene's bounds */
    SL_DEPENDS_CAMERA = 1u << 2,    /* view and projection (jitter included), viewport size */
    SL_DEPENDS_MATERIALS = 1u << 3, /* what the material programs see: material values, composed
                                       programs (recompiles, hot reloads, the debug view) and the
                                       global parameters of the core and of every plugin that adds
                                       shader chunks or a bind callback */
    SL_DEPENDS_OWN_PARAMS = 1u << 4, /* the owning plugin's global parameters */
    SL_DEPENDS_PARAMS = 1u << 5,    /* any edit: every parameter, material and light value, programs
                                       (sl_frame.edits_version) */
    SL_DEPENDS_TIME = 1u << 6,      /* sl_frame.time (every frame while the viewer's clock runs) */
    SL_DEPENDS_INPUTS = 1u << 7,    /* a graph resource it lists in `inputs` was written since */
    SL_DEPENDS_EVERY_FRAME = 1u << 8 /* runs every frame (a history, an accumulation): the same as 0,
                                       but says that the pass was audited */
} sl_depends;

typedef struct sl_pass_desc {
    uint32_t struct_size;           /* sizeof(sl_pass_desc) */
    const char *name;               /* unique pass name; shown in timings ("shadow-maps") */
    sl_stage stage;                 /* order value (see sl_stage); load order among equals */
    const char *const *inputs;      /* NULL-terminated resource names read, or NULL */
    const sl_target_desc *outputs;  /* targets written (allocated by the core) */
    int output_count;
    /* Records the pass. GL context current; outputs are NOT bound: call host->bind_outputs. */
    void (*execute)(void *user, sl_pass_ctx *ctx, const sl_frame *frame);
    /* Optional: false = the pass does not run this frame and costs nothing (e.g. no shadowed
     * light in the scene). Its outputs keep their last contents. */
    bool (*is_active)(void *user, const sl_frame *frame);
    /* Optional: when it returns the value it returned last time the pass ran (and nothing was
     * resized), the pass is skipped and its outputs are reused (with `depends` set, only when
     * that declaration does not ask for a run either). */
    uint64_t (*signature)(void *user, const sl_frame *frame);
    void *user;
    /* ABI 1.8: sl_depends bits (above); 0 = not declared, run every frame. Not tracked: sl_time
     * read by a surface (not VERTEX) hook in the material programs a pass draws with. */
    uint32_t depends;
    /* ABI 1.8: the pass writes its "color" output only through the framebuffer host->bind_outputs
     * binds (draws, clears, blits into it; no image stores, texture copies or reads of that
     * output). When such passes end the frame's chain of "color" writers (nothing after them
     * reads "color"), the core binds its 8-bit "display" target there instead, with the clamp and
     * sRGB encoding applied on write (GL_FRAMEBUFFER_SRGB on an sRGB view), and its separate
     * display pass does not run: one full-screen pass less. The pass does nothing differently;
     * its "color" input, if any, is still the linear colour before it. false (the default, and
     * every plugin built before 1.8): the core's display pass runs after it. */
    bool display_on_write;
    /* ABI 1.12: execute only sets GL state and draws into the framebuffer host->bind_outputs binds
     * (no glClearTexImage, copies, read-backs or blits, and no change to the plugin's own state):
     * run under an empty scissor it rasterises nothing and changes nothing. The core may then run
     * it ahead of its turn (host->compile_ahead) so that a CPU renderer compiles its programs while
     * an earlier pass waits. false (the default): never run but in its turn. */
    bool draws_only;
    /* ABI 1.13, optional: the pass's inputs and outputs as they are now, for a pass whose targets or
     * inputs follow its parameters (a half-resolution option: an output's `scale`; a mode that reads
     * "normal"). Called when the graph is planned and after every parameter edit, GL context
     * current, before begin_frame: sets *inputs (NULL-terminated, or NULL), *outputs and
     * *output_count (arrays the core copies; they need not outlive the call). When they differ
     * from the plan's, the core plans the graph again before the frame: targets re-allocated
     * (their contents lost), passes checked and ordered, and "motion", "normal" and the depth
     * pre-pass produced as the new inputs need. NULL: `inputs` and `outputs` above, always. */
    void (*io)(void *user, const char *const **inputs, const sl_target_desc **outputs, int *output_count);
} sl_pass_desc;

/* host->draw_scene: draw every visible mesh of the scene with a view. */
typedef enum sl_draw_mode {
    SL_DRAW_DEPTH_ONLY = 1, /* core depth program (vertex hooks applied); for shadow maps */
    SL_DRAW_PROGRAM,        /* the given program; the core sets per-object uniforms
                               sl_model (mat4), sl_normal_matrix (mat3), the camera uniforms
                               (sl_view, sl_proj, sl_view_proj, sl_camera_pos of the desc's view),
                               sl_time, sl_frame_index, sl_sample_index, sl_sample_count,
                               sl_viewport_size and sl_uv_space, and binds attributes
                               0 position, 1 normal, 2 tangent (xyz+w), 3 uv */
    SL_DRAW_MATERIALS       /* ABI 1.2: every material's own composed program (its surface
                               hooks, the scene's lights, its uniforms) with the shading model
                               replaced by model_override — e.g. a model returning irradiance
                               for texture-space lighting or only the diffuse part for a
                               screen-space blur. Writes location 0. */
} sl_draw_mode;

typedef struct sl_draw_scene_desc {
    uint32_t struct_size;
    sl_draw_mode mode;
    float view[16], proj[16];        /* column-major */
    struct sl_program *program;      /* SL_DRAW_PROGRAM */
    bool shadow_casters_only;        /* skip materials with cast_shadows = false */
    bool uv_space;                   /* rasterise at uv*2-1 instead of projecting (texture-space
                                        passes); world position still reaches the program */
    int cull;                        /* 0 none, 1 back (default), 2 front */
    /* ABI 1.2, SL_DRAW_MATERIALS: the shading model name to use instead of each material's. */
    const char *model_override;
    /* ABI 1.2, any mode: draw only materials carrying this material key (NULL = all). */
    const char *only_materials_with;
    /* ABI 1.7, SL_DRAW_MATERIALS: a GLSL file of the calling plugin (relative to its resource
     * directory) holding main() and its own outputs, composed into each material's program in
     * place of the core's forward main. Everything the forward fragment stage has is declared
     * before it: SlSurface sl_surface_from_varyings(), sl_run_surface_hooks(s),
     * sl_shade_surface(s), sl_direct_lighting(s), sl_shading_model(s, l, E), sl_lights[], the
     * material's uniforms and, for materials with alpha_cutoff or alpha_blend (#if
     * defined(SL_MAT_HAS_ALPHA_CUTOFF) || defined(SL_ALPHA_BLENDED)), float sl_coverage(s), the
     * coverage the core's main cuts out and blends by (a G-buffer writer, a deferred lighting
     * pass). With `fragment`,
     * model_override may be NULL (the material's own model) and the program defines
     * SL_CUSTOM_MAIN. NULL = the core's main. */
    const char *fragment;
    /* ABI 1.7, SL_DRAW_MATERIALS with `fragment`: instead of its meshes, draw one full-screen
     * triangle per material (sl:fullscreen.vert, v_uv in [0,1]; SL_FULLSCREEN_MATERIAL defined,
     * sl_surface_from_varyings absent: the fragment builds the SlSurface itself, e.g. from a
     * G-buffer) with the material's program and uniforms bound; `uniform int
     * sl_material_index` holds the material's index. The triangle lies at window depth
     * (index + 1) / 1024 and the depth test stays as the pass set it (glDisable(GL_DEPTH_TEST)
     * for none): a pass that wrote (material + 1) / 1024 per pixel into a depth output and sets
     * glDepthFunc(GL_EQUAL) shades each material's pixels only (the others are rejected before
     * the fragment shader runs). Culling is off. */
    bool fullscreen;
} sl_draw_scene_desc;

#ifdef __cplusplus
}
#endif
#endif
