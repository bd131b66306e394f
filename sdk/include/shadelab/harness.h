/* Headless test harness for plugin and core tests (link libshadelab_harness / shadelab_core).
 *
 *   sl_harness *h = sl_harness_create(&(sl_harness_desc){ .struct_size = sizeof(sl_harness_desc),
 *       .width = 64, .height = 64, .scene_json = "...", .plugins = (const char *[]){"ggx", NULL} },
 *       err, sizeof err);
 *   float *img = malloc(64 * 64 * 4 * sizeof(float));
 *   sl_harness_render(h, img);                 // linear HDR radiance, rows top to bottom
 *   sl_harness_eval_glsl(h, &eval, out, err, sizeof err);  // GLSL unit tests
 *   sl_harness_destroy(h);
 *
 * One harness (one GL context) at a time per process: sl_harness_create refuses a second one
 * while the first exists (NULL, with a message saying so). Renders use OSMesa unless
 * SHADELAB_TEST_BACKEND names another backend. */
#ifndef SHADELAB_HARNESS_H
#define SHADELAB_HARNESS_H
#include "shadelab.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sl_harness sl_harness;

typedef struct sl_harness_desc {
    uint32_t struct_size;
    int width, height;               /* default 64×64 */
    const char *scene_file;          /* or */
    const char *scene_json;          /* scene as JSON text; both NULL = the bare built-in scene
                                        (scenes/basic.json: three Lambert spheres, no plugin) */
    const char *const *plugins;      /* NULL-terminated plugin names or paths */
    const char *const *settings;     /* NULL-terminated "id=value" (as --set) */
    const char *debug_view;
    int accumulate;                  /* frames averaged per render (>= 1) */
    bool float32;                    /* RGBA32F colour target */
    bool strict;                     /* fail when a plugin fails */
} sl_harness_desc;

sl_harness *sl_harness_create(const sl_harness_desc *desc, char *err, size_t err_size);
void sl_harness_destroy(sl_harness *h);
/* Applies "id=value" between renders (same addressing as --set). */
bool sl_harness_set(sl_harness *h, const char *assignment, char *err, size_t err_size);
bool sl_harness_set_debug_view(sl_harness *h, const char *view, char *err, size_t err_size);
/* The current value of a global parameter ("plugin.param"), or of a core key of a light
 * ("light.NAME.KEY": enabled, intensity, color, direction, …, as the light holds it: a plugin's
 * light's direction, colour and intensity as its plugin last set them, `enabled` the user's
 * switch), as --set text; false when unknown. */
bool sl_harness_get(sl_harness *h, const char *id, char *text, size_t text_size);
/* Pins the frame index of the next render (sl_time = index × the fixed frame time; a render
 * advances it by one), so that a frame after live changes compares with a fresh start. */
void sl_harness_set_frame(sl_harness *h, uint64_t frame_index);
/* ABI 1.7: puts the camera at `position` looking at `target` (world space, up = +Y; lens and
 * clip planes kept), as a scene camera with those keys would; false when they coincide. */
bool sl_harness_set_camera(sl_harness *h, const float position[3], const float target[3]);
/* Ids of the plugins that loaded (not the core), in load order; returns how many there are. */
int sl_harness_plugins(sl_harness *h, const char **ids, int max);
/* A plugin's global parameters (not "enabled"), as declared; returns how many there are. */
int sl_harness_plugin_params(sl_harness *h, const char *plugin, const sl_param_desc **out, int max);
/* A plugin's key bindings; returns how many there are. */
int sl_harness_plugin_keys(sl_harness *h, const char *plugin, const sl_key_desc **out, int max);
/* The debug views a plugin offers (names); returns how many there are. */
int sl_harness_plugin_debug_views(sl_harness *h, const char *plugin, const char **names, int max);
/* Renders one frame; writes linear HDR RGBA (width*height*4 floats, top row first). With rgba
 * NULL (ABI 1.8) the final linear colour is not kept: the last passes may write the display
 * encoding themselves (sl_pass_desc.display_on_write) and the core's display pass is skipped;
 * sl_harness_read_display gives the same image within 1/255. */
bool sl_harness_render(sl_harness *h, float *rgba);
/* Renders one frame as sample `index` of `count` (sl_frame.sample_index/count: what frame
 * `index` of a `count`-frame still or accumulation sees) on its own: temporal methods (TAA)
 * restart their history, nothing is accumulated, so the frame is shown as rendered. The spread
 * of samples 0..count-1 is shadelab-bench's noise measure; a deterministic method gives the
 * same image for every index. False when index is not in [0, count) or the frame fails. */
bool sl_harness_render_sample(sl_harness *h, int index, int count, float *rgba);
/* The display-encoded image of the last render (sRGB, [0,1]). */
bool sl_harness_read_display(sl_harness *h, float *rgba);
bool sl_harness_save(sl_harness *h, const char *path, char *err, size_t err_size);

/* Structure of the last frame, for "unused costs nothing" checks. */
typedef struct sl_harness_structure {
    int draw_calls;
    int pass_count;
    const char *passes[64];          /* names of the passes that ran (valid after the harness is
                                        destroyed: compare structures of different harnesses) */
    int program_count;
    uint64_t program_hashes[256];    /* one per material, in material order */
    /* ABI 1.8: the passes whose outputs this frame uses, in order: those that ran, those
     * skipped because nothing they depend on changed (pass.h, sl_depends) and those whose
     * function ran fused into another pass's draw (ext/post.h). A live change and a fresh start
     * have the same passes in effect, though the live frame may run fewer. */
    int effect_count;
    const char *in_effect[64];
    int effect_draw_calls;           /* ABI 1.8: draw calls of the passes in effect (a skipped
                                        pass's from its last run) */
} sl_harness_structure;
void sl_harness_structure_of(sl_harness *h, sl_harness_structure *out);
/* Same draw calls, passes (names, in order; those that ran) and program hashes. */
bool sl_harness_structure_equal(const sl_harness_structure *a, const sl_harness_structure *b);

/* Image comparison on linear floats (RGB channels). */
typedef struct sl_compare {
    double rmse, psnr, max_abs, mean_abs;
    long nonfinite;                  /* NaN/Inf values in either image */
    long pixels_over;                /* pixels with a channel differing by more than threshold */
} sl_compare;
void sl_harness_compare(const float *a, const float *b, int width, int height, double threshold, sl_compare *out);
/* Counts NaN/Inf values and negative values in an RGBA image. */
long sl_harness_count_nonfinite(const float *rgba, int width, int height);
long sl_harness_count_negative(const float *rgba, int width, int height);

/* GLSL unit tests: evaluates `expression` (a GLSL expression convertible to vec4, reading the
 * per-texel inputs `in0` and `in1`) over a width×height grid, after including `files` from the
 * plugin's resource directory (plugin NULL = the core's shader library), and reads back RGBA32F.
 * This compiles the plugin's own GLSL: compare the result with values computed in C. */
typedef struct sl_glsl_eval_desc {
    uint32_t struct_size;
    const char *plugin;
    const char *const *files;        /* NULL-terminated */
    const char *expression;
    const char *defines;             /* "NAME VALUE" lines */
    int width, height;
    const float *in0, *in1;          /* width*height*4 floats each, or NULL (zeros) */
} sl_glsl_eval_desc;
bool sl_harness_eval_glsl(sl_harness *h, const sl_glsl_eval_desc *desc, float *out, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif
#endif
