/* Fused full-screen passes: the core's side of the extension "shadelab.post/1"
 * (sdk/include/shadelab/ext/post.h). Pointwise passes registered by plugins run inside the output
 * draw of the accepting pass before them, as a program variant composed with their functions,
 * instead of as passes of their own. The host (core/host) forwards the extension's calls here;
 * the renderer routes each frame (sl_post_route) and skips the fused passes. */
#ifndef SL_RENDER_POST_H
#define SL_RENDER_POST_H
#include <shadelab/shadelab.h>
#include <shadelab/ext/post.h>

struct sl_app;

/* Registrations (create(), no GL needed). owner: the calling plugin's index. */
sl_status sl_post_add_pointwise(struct sl_app *app, int owner, const sl_pointwise_desc *desc);
sl_status sl_post_accept(struct sl_app *app, int owner, const char *pass);
/* host->load_program with the epilogue (identity until something is fused). */
sl_program *sl_post_load_program(struct sl_app *app, int owner, const sl_program_desc *desc);
/* host->program_id: inside a pass with fused passes, an epilogue program's variant for them. */
unsigned sl_post_program_id(struct sl_app *app, sl_program *p);
/* Before host->draw_fullscreen: the fused passes' bind callbacks on the bound program. */
void sl_post_bind_fused(struct sl_app *app);
sl_status sl_post_bind_outputs_with(struct sl_app *app, sl_pass_ctx *ctx, int layer, const unsigned *textures, int count);
/* After a pass ran (graph_run.c): detaches what bind_outputs_with attached to its framebuffer. */
void sl_post_end_pass(struct sl_app *app, unsigned fbo);

/* Per frame, after the display routing (renderer.c): which passes are fused into which, among
 * the passes from index `first` on (accumulated frames: the post passes only). */
void sl_post_route(struct sl_app *app, int first);
/* The graph index of the pass that pass `index` is fused into this frame, or -1. */
int sl_post_fused_into(struct sl_app *app, int index);
/* Frees the registrations and the variant programs (GL context current). */
void sl_post_free(struct sl_app *app);
#endif
