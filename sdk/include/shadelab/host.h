/* The host interface a plugin receives in create(). Every function takes the host pointer the
 * plugin was given (it identifies the plugin). Registration functions may only be called from
 * create(); the rest say when they may be called. All functions are called on the main thread.
 */
#ifndef SHADELAB_HOST_H
#define SHADELAB_HOST_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sl_program sl_program; /* a compiled program owned by the host (hot-reloaded) */

/* ABI 1.10: an image file as host->read_image returns it. */
typedef struct sl_image_file {
    uint32_t struct_size;  /* the caller sets sizeof(sl_image_file) */
    int width, height;
    float *pixels;         /* width*height RGBA floats as stored: integers normalised to [0,1], no
                              colour conversion; grey → RGB, alpha 1 when absent; row 0 at the top.
                              malloc'd: the plugin free()s it */
    int bits;              /* bits per channel in the file (8, 16, 32) */
    int channels;          /* the file's channel count */
    bool is_float;         /* half or float samples */
    bool srgb;             /* integer samples sRGB-encoded (not tagged linear); false for float */
    char description[128]; /* the file's ImageDescription metadata, "" when absent */
    char format[32];       /* the reader that decoded it: "png", "openexr", "hdr"… */
} sl_image_file;

typedef struct sl_key_desc {
    uint32_t struct_size;
    const char *key;          /* "1".."9", "A".."Z", "F1".."F12" */
    const char *description;  /* shown in the panel and --help-keys */
    /* Either toggle/cycle a parameter of this plugin (bool: toggle, enum: next value) … */
    const char *param;
    /* … or call back (main thread, GL context current). */
    void (*on_press)(void *user);
    void *user;
} sl_key_desc;

/* How a plugin's ground truth is rendered (shadelab-bench, --reference). */
typedef struct sl_reference_desc {
    uint32_t struct_size;
    /* Parameter assignments applied on top of the scene, "id=value" separated by spaces:
     * "spotlight-shadow.method=reference spotlight-shadow.samples=256". */
    const char *settings;
    /* > 1: average this many frames (Monte Carlo); sl_frame.accumulate_index varies. */
    int accumulate_frames;
    const char *description; /* one sentence: how the truth is obtained */
} sl_reference_desc;

/* One light of the scene, as the core packs it (read-only to plugins). */
typedef struct sl_light_info {
    uint32_t struct_size;
    const char *name;
    const char *type;          /* "directional", "point", or a plugin light type */
    float position[3];         /* world */
    float direction[3];        /* world, unit, the direction light travels (spot/directional) */
    float color[3];            /* linear RGB times intensity */
    float params[8];           /* light-scope keys packed by their light_slot */
    bool enabled;
    bool cast_shadows;
    int index;                 /* index in the GLSL light buffer; -1 when disabled */
    /* ABI 1.22: the id of the plugin that added the light (add_light), NULL for the scene's own */
    const char *owner;
    /* ABI 1.22: directional lights' disk, its angular radius in degrees (the core's light key
     * angular_radius; before 1.22 spotlight-shadow's) */
    float angular_radius;
} sl_light_info;

/* ABI 1.22: a light a plugin adds to the scene (add_light) — e.g. the sun of envmap's procedural
 * sky, lit and shadowed like the scene's own lights. It is named "<plugin id>.<name>", so users
 * address it as light.<plugin id>.<name>.KEY; `keys` are light keys as a scene gives them
 * ({"angular_radius", "1.5", …, NULL}); one that no loaded plugin declares is skipped in silence. */
typedef struct sl_plugin_light_desc {
    uint32_t struct_size;
    const char *name;          /* [a-z0-9-] */
    const char *type;          /* "directional", "point", or a plugin light type */
    bool cast_shadows;
    const char *const *keys;   /* NULL-terminated key, value pairs, or NULL */
} sl_plugin_light_desc;

/* ABI 1.22: what a plugin sets of its own light each time it changes (set_light): the light's
 * direction, colour and intensity are the plugin's; `enabled` is the plugin's switch, and the
 * light shines while it and the user's light.NAME.enabled are both on. */
typedef struct sl_plugin_light_state {
    uint32_t struct_size;
    bool enabled;
    float position[3];         /* world (point and spot lights) */
    float direction[3];        /* world, the direction light travels (normalised by the host) */
    float color[3];            /* linear RGB */
    float intensity;           /* directional: irradiance E; point/spot: intensity I */
} sl_plugin_light_state;

/* Texture units: the one layout, for the core and every plugin (GL 4.5 guarantees 80 combined
 * units, MAX_COMBINED_TEXTURE_IMAGE_UNITS; one program still samples at most
 * MAX_TEXTURE_IMAGE_UNITS of them).
 *   [0, 16)   a material program's textures (sl_mat_<key>, in the order of its keys), bound by the
 *             core at each material's draw. A pass's own programs may bind their inputs here: the
 *             core rebinds them before every material draw (draw_scene) and keeps nothing there
 *             between passes. A material carrying more texture keys is an error naming the 17th.
 *   [16, 64)  handed out by reserve_texture_unit, from 16 up, each to one plugin for the whole
 *             run: textures bound there stay bound (a plugin's chunk samples them in every material
 *             program). A pass must not bind anything on another plugin's unit.
 *   64, 65    the core's own (the forward-blend pass's "depth"; ABI 1.17: the scene behind,
 *             shader.h). */
#define SL_TEXTURE_UNIT_MATERIAL_FIRST 0
#define SL_TEXTURE_UNIT_MATERIAL_COUNT 16
#define SL_TEXTURE_UNIT_PLUGIN_FIRST 16
#define SL_TEXTURE_UNIT_PLUGIN_COUNT 48
#define SL_TEXTURE_UNIT_CORE 64

typedef struct sl_host sl_host;
struct sl_host {
    uint32_t struct_size;      /* sizeof(sl_host) as the host knows it */
    uint32_t abi_major, abi_minor;
    const char *host_version;

    /* Any time. printf-style; the host prefixes the plugin id. */
    void (*log)(const sl_host *host, sl_log_level level, const char *fmt, ...)
        __attribute__((format(printf, 3, 4)));
    /* Directory holding the plugin's GLSL and data (the directory of its .so). */
    const char *(*resource_dir)(const sl_host *host);

    /* ---- registration: create() only ---- */
    sl_status (*add_param)(const sl_host *host, const sl_param_desc *desc);
    sl_status (*add_shader_chunk)(const sl_host *host, const sl_shader_chunk_desc *desc);
    sl_status (*add_pass)(const sl_host *host, const sl_pass_desc *desc);
    sl_status (*add_key)(const sl_host *host, const sl_key_desc *desc);
    sl_status (*set_reference)(const sl_host *host, const sl_reference_desc *desc);
    /* Called with the GL id of each composed program that contains this plugin's chunks, each
     * time the host binds it for drawing material `material` (index, see material_name): set the
     * plugin's own uniforms and samplers there. Global parameters and material keys are set by
     * the host already. GL context current. */
    sl_status (*set_bind_callback)(const sl_host *host,
                                   void (*bind)(void *user, unsigned program, int material, const sl_frame *frame),
                                   void *user);
    /* A texture unit reserved for this plugin for the whole run (textures it binds in
     * begin_frame/bind stay bound), from the plugin range of SL_TEXTURE_UNIT_* below; -1 with an
     * error naming the plugin when the range is used up. */
    int (*reserve_texture_unit)(const sl_host *host);

    /* ---- queries: any time after create() ---- */
    sl_value (*get_param)(const sl_host *host, const char *id); /* full id "plugin.param" */
    bool (*plugin_enabled)(const sl_host *host, const char *plugin_id);
    /* An extension ("shadelab.shadow-maps/1") provided by an enabled plugin, or NULL. */
    const void *(*get_extension)(const sl_host *host, const char *id);
    /* The scene's lights (stable until the next frame). */
    const sl_light_info *(*lights)(const sl_host *host, int *count);
    /* The scene's materials: count, names, and the value of a material key. material_value
     * returns false when the material does not carry the key (defaults are not "carried");
     * for TEXTURE keys out->s is the spec as written and *resolved_path (when given) receives
     * the file path resolved against the scene and data directories (NULL for procedural specs). */
    int (*material_count)(const sl_host *host);
    const char *(*material_name)(const sl_host *host, int material);
    bool (*material_value)(const sl_host *host, int material, const char *key, sl_value *out,
                           char *resolved_path, size_t path_size);
    /* GL: any time a context is current (activate … deactivate). */
    void *(*gl_get_proc_address)(const char *name);
    bool (*is_gpu)(const sl_host *host);  /* false on llvmpipe/OSMesa */

    /* ---- programs and passes: GL context current ---- */
    /* A stand-alone program from the plugin's files (shader.h, sl_program_desc). It receives no
     * uniform from the core by itself: not the plugin's parameters, not sl_time (set them with
     * glProgramUniform* from sl_frame and get_param; composed material programs are the ones that
     * get them). Drawn by draw_scene SL_DRAW_PROGRAM, the core sets only the per-draw ones listed
     * there (pass.h); draw_fullscreen sets none. Compiled at its first program_id(); a failure
     * switches the plugin off (one message naming file:line). */
    sl_program *(*load_program)(const sl_host *host, const sl_program_desc *desc);
    unsigned (*program_id)(const sl_host *host, sl_program *program); /* 0 if never compiled */
    /* Inside execute(): GL texture of an input or output resource by name. */
    unsigned (*pass_texture)(const sl_host *host, sl_pass_ctx *ctx, const char *name);
    /* Inside execute(): bind a framebuffer with the pass's outputs (layer: for arrays) and set
     * the viewport to their size. */
    sl_status (*bind_outputs)(const sl_host *host, sl_pass_ctx *ctx, int layer);
    void (*draw_scene)(const sl_host *host, sl_pass_ctx *ctx, const sl_draw_scene_desc *desc);
    void (*draw_fullscreen)(const sl_host *host, sl_pass_ctx *ctx); /* bound program, 1 tri */
    /* ABI 1.1. The scene's "environment" (any time after create()): returns its map (resolved path
     * or procedural spec; NULL = none) and fills o = {r, g, b, intensity, yaw in degrees}. */
    const char *(*environment)(const sl_host *host, float o[5]);
    /* ABI 1.3. GL context current, after the scene is uploaded: the GL texture the core loaded
     * for material `material`'s texture key `key` (bound to the program as sl_mat_<key>), or 0
     * when the material does not carry it. Read it, don't delete it. */
    unsigned (*material_texture)(const sl_host *host, int material, const char *key);
    /* ABI 1.6. Directory of the SDK's shader library (what `#include "sl:NAME"` reads: common.glsl,
     * ggx_brdf.glsl, ...), for plugins that hash or read those files themselves. */
    const char *(*shader_dir)(const sl_host *host);
    /* ABI 1.6, begin_frame only: offsets this frame's projection by (x, y) pixels (x right, y up;
     * |x|, |y| <= 0.5) for temporal antialiasing; with core.ssaa = k by (x, y)/k, which moves each
     * of a pixel's k × k samples within its own cell (a still of jittered frames is then the
     * pixel's box filter). Every pass's sl_frame (proj, view_proj, jitter: the offset applied) and
     * the composed programs' sl_proj/sl_view_proj include it; "motion" excludes it. Cleared at
     * the start of every frame. */
    void (*set_jitter)(const sl_host *host, float x, float y);
    /* ABI 1.6, GL context current (activate, begin_frame, passes): a still image of this plugin's
     * output needs `frames` frames rendered at one scene time (a temporal method's history). A
     * headless render without --frames renders the largest count asked for, all at --time; the
     * window renders continuously anyway. Cleared at the start of every frame: ask each frame. */
    void (*set_still_frames)(const sl_host *host, int frames);
    /* ABI 1.7, any time: a procedural texture spec ("checker:8:1,1,1:0,0,0", "constant:r,g,b",
     * "uv", "gradient", "grid:N:r,g,b:r,g,b", the normal-map kinds; scenes/README.md) rendered by
     * the core's one parser, the one materials use: size x size linear RGBA floats, row 0 at the
     * top (size 1..16384). Returns a malloc'd array the plugin free()s, or NULL with a message in
     * err naming the spec, what is wrong and the valid form or range ("checker:0:…": N must be a
     * whole number from 1 to the size). A plugin that takes such specs from users parses them
     * here, so the same text is accepted or refused everywhere. */
    float *(*procedural_image)(const sl_host *host, const char *spec, int size, char *err, size_t err_size);
    /* ABI 1.10, any time: reads an image file through the core's loader (OpenImageIO, the
     * checks every input gets: regular files only, SL_IMAGE_MAX_PIXELS from the header, damaged
     * data refused), so a plugin links no image library of its own. out->struct_size must be
     * set. Returns false with "PATH: cause" in err. */
    bool (*read_image)(const sl_host *host, const char *path, sl_image_file *out, char *err, size_t err_size);
    /* ABI 1.11, GL context current (begin_frame, passes): whether the program of any of the scene's
     * materials, as the forward pass draws it this frame, has an active uniform of this name: the
     * GLSL a plugin contributes reads it there. A plugin prepares in begin_frame what the frame will
     * read (a lazily computed texture, say), before any pass runs, instead of at its first bind in
     * the middle of a pass. Override programs (draw_scene with a fragment) are not included. */
    bool (*scene_uses_uniform)(const sl_host *host, const char *name);
    /* ABI 1.12, in a pass (GL context current): a pass about to wait for the renderer (a read-back,
     * a chain of draws each reading the one before) asks the core to compile the forward pass's
     * programs now. On a CPU renderer (llvmpipe compiles a program at its first draw, on the
     * calling thread) the core draws the forward pass's materials under an empty scissor, in the
     * forward pass's state, so that the compiles overlap the rasteriser's work instead of
     * following it. Nothing is drawn or counted; nothing happens on a GPU, or when the forward
     * programs were compiled ahead already. Call it once every texture the materials bind exists
     * (an empty texture unit is another state, compiled again by the forward pass itself). */
    void (*compile_ahead)(const sl_host *host);
    /* ABI 1.21, begin_frame only: this frame samples the materials' textures (sl_mat_*) with this
     * mip level-of-detail bias (GL_TEXTURE_LOD_BIAS; negative = sharper; clamped to [-4, 4]). A
     * temporal method averaging N jittered frames into a still asks for -0.5·log2(N): each frame
     * then filters the texture over its share of the pixel, so the mean is the pixel's box filter
     * of the texture rather than a mip-blurred one. Cleared at the start of every frame. */
    void (*set_texture_lod_bias)(const sl_host *host, float bias);
    /* ABI 1.22, create() only: adds a light this plugin owns to the scene (sl_plugin_light_desc),
     * disabled until set_light enables it; returns its handle for set_light, or -1 with an error
     * (a name taken, no memory). While the plugin is switched off its lights are off too. */
    int (*add_light)(const sl_host *host, const sl_plugin_light_desc *desc);
    /* ABI 1.22, begin_frame only: the light's state from this frame on. Call it when what the
     * light follows changed (the plugin's parameters: an edit restarts the still anyway), not
     * every frame; an unchanged state costs nothing. false: not this plugin's handle. */
    bool (*set_light)(const sl_host *host, int light, const sl_plugin_light_state *state);
};

#ifdef __cplusplus
}
#endif
#endif
