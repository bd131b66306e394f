/* Extension "shadelab.post/1": full-screen passes that share one draw. Provided by the core.
 *
 * On a CPU rasteriser a full-screen pass costs a read and a write of every pixel whatever it
 * computes, so a chain of small post passes (a TAA resolve, its copy into "color", a tone curve)
 * costs more in memory traffic than in arithmetic. This extension lets such passes run in one
 * draw without knowing each other:
 *
 *   - A *pointwise* pass maps each pixel of "color" on its own (tone curves, exposure, colour
 *     grading): its only input and its only output are "color". It offers that map as a GLSL
 *     function with add_pointwise().
 *   - A pass that *accepts* pointwise passes (accept_pointwise()) writes "color" last through
 *     programs loaded with load_program() below, whose fragment shader passes what it writes to
 *         vec3 sl_pointwise_epilogue(vec3 color, ivec2 pixel)
 *     (declared by the core before the fragment file; the identity when nothing is fused).
 *
 * Each frame, when the active passes that follow an accepting pass (in pass order, before any
 * other active pass) are pointwise, the core fuses them into it: their functions run, in order,
 * inside its epilogue, their execute() is not called, and --explain lists them as "fused into"
 * it. Fusing changes no image beyond rounding: the fused functions see the accepting pass's
 * value before it is stored in a 16-bit target. Passes whose results are averaged over the
 * sub-frames of --accumulate are never fused with the passes after the average.
 *
 *     #include <shadelab/ext/post.h>
 *     const sl_ext_post *post = host->get_extension(host, SL_EXT_POST);
 *     if (post) post->add_pointwise(host, &(sl_pointwise_desc){.struct_size = sizeof(sl_pointwise_desc),
 *                                   .pass = "tonemap", .file = "tonemap_point.glsl",
 *                                   .function = "tonemap_point", .defines = my_defines, .bind = my_bind,
 *                                   .user = me});
 *
 * When: add_pointwise and accept_pointwise in create() (after add_pass of the pass they name);
 * load_program where sl_host.load_program may be called; bind_outputs_with inside execute().
 * NULL from get_extension: a host without it (the passes then simply run one after the other).
 */
#ifndef SHADELAB_EXT_POST_H
#define SHADELAB_EXT_POST_H
#include "../shadelab.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SL_EXT_POST "shadelab.post/1"

/* Fields are only ever appended; set struct_size to sizeof(sl_pointwise_desc). */
typedef struct sl_pointwise_desc {
    uint32_t struct_size;
    const char *pass;        /* the caller's own pass (its add_pass name): inputs and outputs "color" only */
    const char *file;        /* GLSL file of the plugin (its resource dir) defining `function` and the
                                uniforms it reads; it may #include "sl:..." and its own files */
    const char *function;    /* vec3 FUNCTION(vec3 color, ivec2 pixel): the pass's value at `pixel` */
    /* Optional: this frame's #defines for `file` ("NAME VALUE" lines, as sl_program_desc.defines),
     * the permutation the pass would draw with; NULL or "" for none. Main thread, each frame. */
    const char *(*defines)(void *user, const sl_frame *frame);
    /* Sets the uniforms `file` reads in `program` (bound, GL context current), on the texture
     * units the plugin reserved. Called before every draw of a program the pass is fused into. */
    void (*bind)(void *user, unsigned program, const sl_frame *frame);
    void *user;
} sl_pointwise_desc;

typedef struct sl_ext_post {
    uint32_t struct_size;    /* sizeof(sl_ext_post) of the host */
    /* Registers the caller's pass `desc->pass` as pointwise. SL_ERR_INVALID when the pass is not
     * the caller's, does not read and write exactly "color", or a field is missing. */
    sl_status (*add_pointwise)(const sl_host *host, const sl_pointwise_desc *desc);
    /* The caller's pass `pass` writes "color" last with programs from load_program() below. */
    sl_status (*accept_pointwise)(const sl_host *host, const char *pass);
    /* sl_host.load_program for the accepting pass's output programs: the fragment shader may call
     * sl_pointwise_epilogue (above). host->program_id gives, inside the pass, the variant with the
     * functions fused this frame (compiled at its first use and kept), and the core calls each
     * fused pass's bind before host->draw_fullscreen draws. */
    sl_program *(*load_program)(const sl_host *host, const sl_program_desc *desc);
    /* host->bind_outputs, then `count` (<= 4) textures of the plugin's own as the next colour
     * attachments (fragment outputs output_count, output_count + 1, ...): a pass that writes its
     * own history and its "color" output in one draw. The textures have the size of the pass's
     * outputs; the display encoding on write (pass.h) does not apply to them. */
    sl_status (*bind_outputs_with)(const sl_host *host, sl_pass_ctx *ctx, int layer, const unsigned *textures,
                                   int count);
} sl_ext_post;

#ifdef __cplusplus
}
#endif
#endif
