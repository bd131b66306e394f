/* aa: antialiasing as post passes. FXAA (Lottes 2009) on the display-referred colour at the end of
 * the post chain; TAA (Karis 2014) on linear HDR colour right after the opaque passes, fed by the
 * core's projection jitter and motion vectors. The reference is the core's 8x8 supersampling.
 * See README.md. */
#include <shadelab/shadelab.h>
#include <shadelab/ext/post.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/matrix.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const methods[] = {"none", "taa", "fxaa", NULL}; /* the key X goes none → taa → fxaa */
enum { AA_NONE, AA_TAA, AA_FXAA };

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "method", .type = SL_PARAM_ENUM, .enum_values = methods, .default_value = {.i = AA_TAA},
      .flags = SL_PARAM_QUALITY_KNOB, .group = "method",
      .description = "none; taa (Karis 2014: "
                     "jittered frames accumulated with motion-vector reprojection, neighbourhood clamping and "
                     "disocclusion rejection; a still is the mean of taa_frames frames); fxaa (Lottes 2009: "
                     "edge-directed blend of the final image, one pass)."),
    P(.id = "fxaa_threshold", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.125f}}, .min = 0.03f, .max = 0.5f,
      .step = 0.005f, .group = "fxaa",
      .description = "FXAA: contrast of the 4-neighbourhood's display luma, relative to its brightest, below which a "
                     "pixel is left untouched (Lottes: 1/8 high quality, 1/4 fast)."),
    P(.id = "fxaa_threshold_min", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.0625f}}, .min = 0, .max = 0.25f,
      .step = 0.005f, .group = "fxaa",
      .description = "FXAA: absolute contrast below which a pixel is left untouched (dark areas; Lottes 1/16..1/12)."),
    P(.id = "fxaa_subpix", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.75f}}, .min = 0, .max = 1, .step = 0.05f,
      .group = "fxaa", .description = "FXAA: strength of the sub-pixel blend (single-pixel features; 0 off, 1 soft)."),
    P(.id = "taa_frames", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 1, .max = 64, .step = 1,
      .group = "taa",
      .description = "TAA: length of the jitter sequence (Halton 2,3) and of the history: a still is the exact mean "
                     "of this many jittered frames, after that each frame has weight 1/taa_frames. A headless still "
                     "renders this many frames (see README)."),
    P(.id = "taa_clamp", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "taa",
      .description = "TAA: clip the history to the current 3x3 neighbourhood's colour box in YCoCg (Karis 2014); off "
                     "shows the ghosts it prevents."),
    P(.id = "taa_reject", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "taa",
      .description = "TAA: drop the history where the reprojected surface is not this one (disocclusion: the depth "
                     "there does not match) or falls outside the last frame."),
    P(.id = "taa_lod_bias", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "taa",
      .description = "TAA: in a still's jittered frames, sample the materials' textures one mip level sharper per "
                     "factor 4 of frames (LOD bias -0.5 log2 taa_frames), so the still is the pixel's box filter of "
                     "the texture, as a path tracer's, not of its mip-blurred copy (see README). Off: every frame "
                     "at the pixel's own mip level."),
    P(.id = "taa_upscale", .type = SL_PARAM_BOOL, .default_value = {.b = false}, .group = "taa",
      .description = "TAA: with core.render_scale below 1, keep the history at the output (window) size and "
                     "reconstruct it from the jittered frames (TAAU, see README: a sharper still, but on a CPU "
                     "rasteriser a motion frame costs 2.6x, so off by default); off: TAA at the render size, "
                     "scaled up bilinearly."),
};

typedef struct aa {
    const sl_host *host;
    const sl_ext_post *post; /* the core's shadelab.post/1: history and output in one draw, tone
                                mapping (a pointwise pass after TAA) fused into it */
    sl_program *fxaa;
    sl_program *taa_copy;  /* a frame without a history, and a converged still's history, as it is */
    sl_program *taa_still; /* a still: the running mean (taa.frag's AA_STILL) */
    bool fbfetch;          /* GL_EXT_shader_framebuffer_fetch: a still updates its history in place
                              (AA_FBFETCH), which is then RGBA32F */
    sl_program *taa[2][2]; /* in motion: the resolve per [clamp][reject] (taa.frag's AA_CLAMP, AA_REJECT) */
    /* the render size below the output size (taau.frag): a frame without a history, a still, motion */
    sl_program *taau_first, *taau_still, *taau[2][2];
    bool upscales;         /* the pass's "color" output is at the output size (taa_io) */
    int unit[5];
    unsigned sampler_linear, sampler_nearest;
    /* TAA: the history (rgb + frames in alpha) as a ping-pong pair, the last frame's depth */
    unsigned history[2], prev_depth, depth_fbo[2];
    int current, hw, hh, dw, dh, hformat;
    uint64_t frames_begun, taa_ran_at; /* begin_frame count; its value when TAA last ran */
    bool history_valid;
    /* stills: frames since the view last changed (versions and size of sl_frame) */
    uint64_t signature, cut;
    int still, restart;       /* frames of the current still; 1 = restart the history this frame */
    bool converged;           /* the still has its taa_frames frames: show the history as it is */
} aa;

static sl_value param(aa *a, const char *id) {
    char full[64];
    snprintf(full, sizeof full, "aa.%s", id);
    return a->host->get_param(a->host, full);
}

/* ------------------------------------------------------------------ FXAA ------------ */

static bool fxaa_active(void *user, const sl_frame *f) {
    (void)f;
    return param(user, "method").i == AA_FXAA;
}

static void fxaa_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    (void)f;
    aa *a = user;
    const sl_host *h = a->host;
    unsigned src = h->pass_texture(h, ctx, "color");
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    unsigned p = h->program_id(h, a->fxaa);
    if (!p) return;
    glUseProgram(p);
    glBindTextureUnit(a->unit[0], src);
    glBindSampler(a->unit[0], a->sampler_linear);
    glUniform1i(glGetUniformLocation(p, "aa_src"), a->unit[0]);
    glUniform1f(glGetUniformLocation(p, "aa_edge_threshold"), param(a, "fxaa_threshold").f[0]);
    glUniform1f(glGetUniformLocation(p, "aa_edge_threshold_min"), param(a, "fxaa_threshold_min").f[0]);
    glUniform1f(glGetUniformLocation(p, "aa_subpix"), param(a, "fxaa_subpix").f[0]);
    h->draw_fullscreen(h, ctx);
    glBindSampler(a->unit[0], 0);
}

/* ------------------------------------------------------------------ TAA ------------- */

/* Radical inverse in base b (the Halton sequence, Halton 1960). */
static float halton(unsigned i, unsigned b) {
    float f = 1, r = 0;
    for (; i > 0; i /= b) f /= (float)b, r += f * (float)(i % b);
    return r;
}
/* Jitters frame k (1..n-1) of an n-frame sequence: Halton (2, 3) point k less the mean of points
 * 1..n-1, so that with frame 0 at the pixel's centre the n offsets average to it, as a path
 * tracer's box filter does. Halton's first points are not centred: their mean was (0, -0.097) of
 * a pixel over 4 frames, (0, -0.043) over 16, which moved a still's image that far off its
 * pixels. */
static void set_frame_jitter(aa *a, unsigned k, unsigned n) {
    float mean[2] = {0, 0};
    for (unsigned i = 1; i < n; i++) mean[0] += halton(i, 2) - 0.5f, mean[1] += halton(i, 3) - 0.5f;
    a->host->set_jitter(a->host, halton(k, 2) - 0.5f - mean[0] / (float)(n - 1),
                        halton(k, 3) - 0.5f - mean[1] / (float)(n - 1));
}

/* What moves the image (camera, animated geometry and lights): while it stays, the view is
 * still. A change of settings or size is a cut instead: the history of another setting is no
 * history of this one, so the accumulation restarts (a live change equals a fresh start). */
static uint64_t motion_signature(const sl_frame *f, bool upscales) {
    /* upscaling, a new render scale moves the samples: the history goes on (at the output size),
     * a still restarts at the new scale */
    uint64_t size = upscales ? (uint64_t)f->width << 32 | (uint32_t)f->height : 0;
    uint64_t v[] = {f->camera_version, f->geometry_version, f->lights_version, size};
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < sizeof v / sizeof *v; i++) h = (h ^ v[i]) * 1099511628211ull;
    return h;
}
static uint64_t cut_signature(const sl_frame *f, bool upscales) {
    uint64_t size = upscales ? (uint64_t)f->output_width << 32 | (uint32_t)f->output_height
                             : (uint64_t)f->width << 32 | (uint32_t)f->height;
    uint64_t v[] = {f->edits_version, size};
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < sizeof v / sizeof *v; i++) h = (h ^ v[i]) * 1099511628211ull;
    return h;
}

/* The length of the jitter sequence and of a still: taa_frames, times the output pixels per
 * render pixel while upscaling (a frame brings each output pixel s^2 samples at render scale s,
 * taau.frag), at most 64 (or taa_frames). */
static int sequence_frames(aa *a, const sl_frame *f) {
    int n = param(a, "taa_frames").i;
    if (!a->upscales || f->width >= f->output_width || f->height >= f->output_height) return n;
    double per_sample = (double)f->output_width * f->output_height / ((double)f->width * f->height);
    int m = (int)ceil(n * per_sample);
    return m < 64 ? m : n > 64 ? n : 64;
}

/* The jittered frames of an n-frame still (not its first, the pixel centre: one frame stays the
 * image without antialiasing) sample the materials' textures with a mip LOD bias of
 * -0.5·log2(n): n samples spread over a pixel each cover 1/n of its area, a footprint sqrt(n)
 * times narrower than the pixel's, so their mean is the box filter of the texture over the pixel
 * (what Cycles and the 8x8 supersampled reference compute) instead of the box filter of the mip
 * level the whole pixel selects, which blurs texture detail a second time. In motion every frame
 * keeps the pixel's own level: a sharper frame would alias where the history is clipped. */
static void still_lod_bias(aa *a, int n) {
    if (!param(a, "taa_lod_bias").b || a->host->abi_minor < 21 || n < 2) return;
    a->host->set_texture_lod_bias(a->host, -0.5f * log2f((float)n));
}

static void begin_frame(void *user, const sl_frame *f) {
    aa *a = user;
    a->frames_begun++;
    if (param(a, "method").i != AA_TAA) return;
    int n = sequence_frames(a, f);
    a->host->set_still_frames(a->host, n);
    /* A still view (nothing changed since the last frame, which TAA rendered) accumulates
     * exactly: the first frame of the still restarts the history at the pixel centre, the next
     * n-1 frames add Halton points 1..n-1 (centred: set_frame_jitter) with equal weights, and
     * from then on the history is shown as it is (no jitter): the window shows what a headless
     * still (n frames) gives. */
    uint64_t sig = motion_signature(f, a->upscales), cut = cut_signature(f, a->upscales);
    bool consecutive = a->history_valid && a->taa_ran_at + 1 == a->frames_begun;
    if (!consecutive || cut != a->cut) a->still = 0, a->restart = 1; /* a first frame starts a still */
    else if (sig != a->signature) a->still = -1, a->restart = 0; /* moving: ordinary TAA */
    else if (a->still < 0) a->still = 0, a->restart = 1;        /* it just stopped: restart */
    else a->still++, a->restart = 0;
    a->signature = sig;
    a->cut = cut;
    a->converged = a->still >= n;
    if (a->still >= 0) {
        if (!a->converged && a->still > 0) {
            set_frame_jitter(a, (unsigned)a->still, (unsigned)n);
            still_lod_bias(a, n);
        }
        return;
    }
    /* Frame k of each run of n samples the pixel centre (k = 0), then Halton points 1..n-1
     * (Halton 0 is a corner). A first frame is therefore the image without antialiasing, so a
     * single-frame render is the same with TAA on (a TAA still is the mean of n frames). */
    unsigned k = (unsigned)(f->index % (uint64_t)(n > 0 ? n : 1));
    if (k) set_frame_jitter(a, k, (unsigned)n);
}

static bool taa_active(void *user, const sl_frame *f) {
    (void)f;
    return param(user, "method").i == AA_TAA;
}

/* The history at the size of the pass's output (the output size while it upscales): RGBA32F where
 * a still updates it in place (framebuffer fetch: on llvmpipe a read of an RGBA32F target costs
 * less than of an RGBA16F one, and less than a texel fetch of either), else in the colour target's
 * own format (RGBA16F, RGBA32F with --float). A new size or format restarts it. */
static void history_textures(aa *a, int w, int h, int format) {
    if (w == a->hw && h == a->hh && format == a->hformat) return;
    if (a->history[0]) glDeleteTextures(2, a->history);
    glCreateTextures(GL_TEXTURE_2D, 2, a->history);
    for (int i = 0; i < 2; i++) glTextureStorage2D(a->history[i], 1, (GLenum)format, w, h);
    a->hw = w, a->hh = h, a->hformat = format;
    a->history_valid = false;
}

/* This frame's depth becomes the next frame's previous depth (disocclusion, in motion). Made at
 * the depth's size after the draw: the draw read the last frame's, whatever its size (a new
 * render scale keeps an upscaling history). Without an upscaling history a new size restarts. */
static void keep_depth(aa *a, unsigned depth, int dw, int dh) {
    if (dw != a->dw || dh != a->dh) {
        if (a->prev_depth) glDeleteTextures(1, &a->prev_depth);
        glCreateTextures(GL_TEXTURE_2D, 1, &a->prev_depth);
        glTextureStorage2D(a->prev_depth, 1, GL_DEPTH_COMPONENT32F, dw, dh);
        a->dw = dw, a->dh = dh;
    }
    glNamedFramebufferTexture(a->depth_fbo[0], GL_DEPTH_ATTACHMENT, depth, 0);
    glNamedFramebufferTexture(a->depth_fbo[1], GL_DEPTH_ATTACHMENT, a->prev_depth, 0);
    glBlitNamedFramebuffer(a->depth_fbo[0], a->depth_fbo[1], 0, 0, dw, dh, 0, 0, dw, dh, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
}

static void bind_tex(aa *a, unsigned prog, int slot, const char *name, unsigned tex, unsigned sampler) {
    glBindTextureUnit(a->unit[slot], tex);
    glBindSampler(a->unit[slot], sampler);
    glUniform1i(glGetUniformLocation(prog, name), a->unit[slot]);
}

/* The inputs of a resolve in motion (taa.frag, taau.frag): reprojection and disocclusion. */
static bool bind_motion_inputs(aa *a, unsigned p, const sl_frame *f, unsigned color, unsigned depth, unsigned motion) {
    float inv[16], prev_inv[16];
    if (!sl_mat4_invert(f->view_proj, inv) || !sl_mat4_invert(f->prev_view_proj, prev_inv)) return false;
    glUseProgram(p);
    bind_tex(a, p, 0, "aa_color", color, a->sampler_nearest);
    bind_tex(a, p, 1, "aa_depth", depth, a->sampler_nearest);
    bind_tex(a, p, 2, "aa_motion", motion, a->sampler_nearest);
    bind_tex(a, p, 3, "aa_history", a->history[a->current], a->sampler_linear);
    bind_tex(a, p, 4, "aa_prev_depth", a->prev_depth, a->sampler_nearest);
    glUniformMatrix4fv(glGetUniformLocation(p, "aa_inv_view_proj"), 1, GL_FALSE, inv);
    glUniformMatrix4fv(glGetUniformLocation(p, "aa_prev_inv_view_proj"), 1, GL_FALSE, prev_inv);
    glUniform3fv(glGetUniformLocation(p, "aa_camera_pos"), 1, f->camera_pos);
    glUniform1i(glGetUniformLocation(p, "aa_frames"), param(a, "taa_frames").i);
    return true;
}

/* The program of a TAAU draw (the render size below the output size, taau.frag): a frame
 * without a history starts from the samples and the bilinear scale-up, a still accumulates the
 * samples' weighted mean, motion reprojects, clips and rejects. */
static unsigned taau_program(aa *a, const sl_frame *f, bool valid, unsigned color, unsigned depth, unsigned motion) {
    const sl_host *h = a->host;
    bool moving = valid && a->still < 0;
    sl_program *prog = !valid ? a->taau_first : !moving ? a->taau_still : a->taau[param(a, "taa_clamp").b][param(a, "taa_reject").b];
    unsigned p = h->program_id(h, prog);
    if (!p) return 0;
    if (moving && !bind_motion_inputs(a, p, f, color, depth, motion)) return taau_program(a, f, false, color, depth, motion);
    glUseProgram(p);
    bind_tex(a, p, 0, "aa_color", color, a->sampler_nearest);
    bind_tex(a, p, 3, "aa_history", a->history[a->current], moving ? a->sampler_linear : a->sampler_nearest);
    /* in motion, the history keeps taa_frames frames' worth of samples (taau.frag): a frame adds
     * 1.372 s^2 of weight on average at render scale s, so the new samples' share is on average
     * 1 / taa_frames, as in TAA */
    double scale2 = (double)f->width * f->height / ((double)f->output_width * f->output_height);
    glUniform1f(glGetUniformLocation(p, "aa_cap"), (float)(param(a, "taa_frames").i * 1.372 * scale2));
    glUniform2f(glGetUniformLocation(p, "aa_jitter"), f->jitter[0], f->jitter[1]);
    return p;
}

/* The program of this frame's TAA draw and its inputs: a frame without a history copies "color";
 * a still averages (no neighbourhood: nothing moved, so the history is this pixel's own frames);
 * in motion the resolve reprojects, clips and rejects. */
static unsigned taa_program(aa *a, const sl_frame *f, bool valid, unsigned color, unsigned depth, unsigned motion) {
    const sl_host *h = a->host;
    if (a->upscales && (f->width != a->hw || f->height != a->hh)) return taau_program(a, f, valid, color, depth, motion);
    if (!valid) {
        unsigned p = h->program_id(h, a->taa_copy);
        if (p) glUseProgram(p), bind_tex(a, p, 0, "aa_src", color, a->sampler_nearest);
        return p;
    }
    if (a->still >= 0) {
        unsigned p = h->program_id(h, a->taa_still);
        if (!p) return 0;
        glUseProgram(p);
        bind_tex(a, p, 0, "aa_color", color, a->sampler_nearest);
        /* in place (AA_FBFETCH): the history is the target, not a texture of this draw */
        if (a->fbfetch) glBindTextureUnit(a->unit[3], 0);
        else bind_tex(a, p, 3, "aa_history", a->history[a->current], a->sampler_nearest);
        glUniform1i(glGetUniformLocation(p, "aa_frames"), param(a, "taa_frames").i);
        return p;
    }
    unsigned p = h->program_id(h, a->taa[param(a, "taa_clamp").b][param(a, "taa_reject").b]);
    if (!p) return 0;
    return bind_motion_inputs(a, p, f, color, depth, motion) ? p : taa_program(a, f, false, color, depth, motion);
}

/* One full-screen draw per frame: the new history (our target) and "color" (the output, through
 * the functions of the pointwise passes fused into this pass: tone mapping) together. */
static void taa_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    aa *a = user;
    const sl_host *h = a->host;
    unsigned color = h->pass_texture(h, ctx, "color"), depth = h->pass_texture(h, ctx, "depth"),
             motion = h->pass_texture(h, ctx, "motion");
    if (!color || !depth || !motion) return;
    int dw, dh, format;
    glGetTextureLevelParameteriv(color, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    glGetTextureLevelParameteriv(depth, 0, GL_TEXTURE_WIDTH, &dw);
    glGetTextureLevelParameteriv(depth, 0, GL_TEXTURE_HEIGHT, &dh);
    history_textures(a, a->upscales ? f->output_width : f->width, a->upscales ? f->output_height : f->height,
                     a->fbfetch ? GL_RGBA32F : format);
    /* without an upscaling history a new render size restarts (the depth of another size too) */
    if (!a->upscales && (dw != a->dw || dh != a->dh)) a->history_valid = false;
    /* the history continues only from the frame just before (not after the method was off, a
     * pause or a resize) */
    bool valid = a->history_valid && a->taa_ran_at + 1 == a->frames_begun && !a->restart;
    a->taa_ran_at = a->frames_begun;
    if (a->converged && valid) { /* a converged still: the history as it is, kept */
        unsigned p = h->program_id(h, a->taa_copy);
        if (!p || h->bind_outputs(h, ctx, 0) != SL_OK) return;
        glUseProgram(p);
        bind_tex(a, p, 0, "aa_src", a->history[a->current], a->sampler_nearest);
        h->draw_fullscreen(h, ctx);
        glBindSampler(a->unit[0], 0);
        return;
    }
    unsigned p = taa_program(a, f, valid, color, depth, motion);
    /* a still with framebuffer fetch writes the history it reads (taa.frag's AA_FBFETCH) */
    bool in_place = a->fbfetch && valid && a->still >= 0 && !(a->upscales && (f->width != a->hw || f->height != a->hh));
    int next = in_place ? a->current : 1 - a->current;
    if (!p) return; /* a program failed to compile (the host reported it): the frame stays as it is */
    if (a->post->bind_outputs_with(h, ctx, 0, &a->history[next], 1) != SL_OK) return;
    h->draw_fullscreen(h, ctx);
    for (int i = 0; i < 5; i++) glBindSampler(a->unit[i], 0);
    /* this frame's depth is the next frame's previous depth (disocclusion, in motion). A still's
     * frames after its first differ only by the jitter: the first one's depth serves */
    if (a->still <= 0 || dw != a->dw || dh != a->dh) keep_depth(a, depth, dw, dh);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    a->current = next;
    a->history_valid = true;
}

/* ------------------------------------------------------------------ plugin ---------- */

static const char *const fxaa_inputs[] = {"color", NULL};
static const char *const taa_inputs[] = {"color", "depth", "motion", NULL};
static const sl_target_desc color_out[] = {{.name = "color", .format = SL_FORMAT_RGBA16F}};
/* TAA with taa_upscale: the pass is the frame's upscaler (pass.h, SL_SIZE_OUTPUT, ABI 1.18) */
static const sl_target_desc color_out_upscaled[] = {{.name = "color", .format = SL_FORMAT_RGBA16F, .width = SL_SIZE_OUTPUT}};

/* TAA's output: at the output size while it upscales (taa and taa_upscale), else at the render
 * size, where a method other than taa leaves the scaling up to the window (bilinear). */
static void taa_io(void *user, const char *const **inputs, const sl_target_desc **outputs, int *count) {
    aa *a = user;
    a->upscales = param(a, "method").i == AA_TAA && param(a, "taa_upscale").b;
    *inputs = taa_inputs;
    *outputs = a->upscales ? color_out_upscaled : color_out;
    *count = 1;
}

/* FXAA runs last before the display encoding: after tone mapping and display-referred effects,
 * on the image as it will be seen (Lottes: after everything but the UI). */
#define AA_STAGE_FXAA (SL_STAGE_DISPLAY_REFERRED + 10)
/* TAA runs on linear HDR radiance right after the opaque passes (the forward pass, envmap's
 * background) and the blended materials (the core's forward-blend pass, SL_STAGE_BLEND), and
 * before every post effect, which then sees a stable image. */
#define AA_STAGE_TAA (SL_STAGE_BLEND + 10)

static sl_status create(const sl_host *host, void **user) {
    aa *a = calloc(1, sizeof *a);
    a->host = host;
    *user = a;
    if (!(a->post = host->get_extension(host, SL_EXT_POST))) {
        host->log(host, SL_LOG_ERROR, "the host does not provide %s (history and output in one draw)", SL_EXT_POST);
        return SL_ERR_FAILED;
    }
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc fxaa = {.struct_size = sizeof fxaa, .name = "aa-fxaa", .stage = AA_STAGE_FXAA,
                               .inputs = fxaa_inputs, .outputs = color_out, .output_count = 1,
                               .execute = fxaa_execute, .is_active = fxaa_active, .user = a,
                               .depends = SL_DEPENDS_INPUTS | SL_DEPENDS_OWN_PARAMS, .display_on_write = true};
    if (host->add_pass(host, &fxaa) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc taa = {.struct_size = sizeof taa, .name = "aa-taa", .stage = AA_STAGE_TAA,
                              .inputs = taa_inputs, .outputs = color_out, .output_count = 1,
                              .execute = taa_execute, .is_active = taa_active, .user = a, .io = taa_io,
                              .depends = SL_DEPENDS_EVERY_FRAME, /* its history moves every frame */
                              .display_on_write = true};
    if (host->add_pass(host, &taa) != SL_OK) return SL_ERR_FAILED;
    if (a->post->accept_pointwise(host, "aa-taa") != SL_OK) return SL_ERR_FAILED; /* tone mapping in our draw */
    static const sl_key_desc key = {.struct_size = sizeof(sl_key_desc), .key = "X", .param = "method",
                                    .description = "next antialiasing method (none, taa, fxaa)"};
    if (host->add_key(host, &key) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {.struct_size = sizeof ref, .settings = "aa.method=none core.ssaa=8",
                                   .accumulate_frames = 1,
                                   .description = "8x8 supersampling box-filtered in linear HDR (core.ssaa=8), no post AA"};
    if (host->set_reference(host, &ref) != SL_OK) return SL_ERR_FAILED;
    for (int i = 0; i < 5; i++)
        if ((a->unit[i] = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    return SL_OK;
}

static sl_status activate(void *user) {
    aa *a = user;
    if (!sl_gl_load(a->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    a->fxaa = a->host->load_program(a->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                  .vertex = "sl:fullscreen.vert", .fragment = "fxaa.frag"});
    /* TAA's programs write "color" through the fused pointwise passes (ext/post.h) */
    bool resolves = true;
    for (int c = 0; c < 2; c++)
        for (int r = 0; r < 2; r++) {
            char defines[64];
            snprintf(defines, sizeof defines, "AA_CLAMP %d\nAA_REJECT %d", c, r);
            a->taa[c][r] = a->post->load_program(a->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                             .vertex = "sl:fullscreen.vert",
                                                                             .fragment = "taa.frag", .defines = defines});
            resolves = resolves && a->taa[c][r];
        }
    for (int c = 0; c < 2; c++)
        for (int r = 0; r < 2; r++) {
            char defines[64];
            snprintf(defines, sizeof defines, "AA_CLAMP %d\nAA_REJECT %d", c, r);
            a->taau[c][r] = a->post->load_program(a->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                              .vertex = "sl:fullscreen.vert",
                                                                              .fragment = "taau.frag", .defines = defines});
            resolves = resolves && a->taau[c][r];
        }
    a->taau_first = a->post->load_program(a->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                        .vertex = "sl:fullscreen.vert", .fragment = "taau.frag",
                                                                        .defines = "AA_FIRST 1"});
    a->taau_still = a->post->load_program(a->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                        .vertex = "sl:fullscreen.vert", .fragment = "taau.frag",
                                                                        .defines = "AA_STILL 1"});
    resolves = resolves && a->taau_first && a->taau_still;
    /* a still reads its history in place where the GL can read the framebuffer (AA_FBFETCH) */
    a->fbfetch = false;
    int nx = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &nx);
    for (int i = 0; i < nx && !a->fbfetch; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (unsigned)i);
        a->fbfetch = e && !strcmp(e, "GL_EXT_shader_framebuffer_fetch");
    }
    a->taa_still = a->post->load_program(a->host, &(sl_program_desc){
                                                      .struct_size = sizeof(sl_program_desc), .vertex = "sl:fullscreen.vert",
                                                      .fragment = "taa.frag",
                                                      .defines = a->fbfetch ? "#extension GL_EXT_shader_framebuffer_fetch : require\n"
                                                                              "AA_STILL 1\nAA_FBFETCH 1"
                                                                            : "AA_STILL 1"});
    a->taa_copy = a->post->load_program(a->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                      .vertex = "sl:fullscreen.vert", .fragment = "taa_copy.frag"});
    glCreateFramebuffers(2, a->depth_fbo);
    for (int i = 0; i < 2; i++) glNamedFramebufferDrawBuffer(a->depth_fbo[i], GL_NONE), glNamedFramebufferReadBuffer(a->depth_fbo[i], GL_NONE);
    glCreateSamplers(1, &a->sampler_nearest);
    glSamplerParameteri(a->sampler_nearest, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(a->sampler_nearest, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(a->sampler_nearest, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(a->sampler_nearest, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glCreateSamplers(1, &a->sampler_linear);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    /* Not compiled here: the host compiles each program at its first program_id() (in the pass
     * that uses it), so the mode not in use (fxaa while TAA runs) costs no compile. A missing
     * file is already an error (load_program returns a program that never gets an id). */
    return a->fxaa && resolves && a->taa_still && a->taa_copy ? SL_OK : SL_ERR_GL;
}

static void deactivate(void *user) {
    aa *a = user;
    glDeleteSamplers(1, &a->sampler_linear);
    glDeleteSamplers(1, &a->sampler_nearest);
    glDeleteFramebuffers(2, a->depth_fbo);
    if (a->history[0]) glDeleteTextures(2, a->history);
    if (a->prev_depth) glDeleteTextures(1, &a->prev_depth);
    a->sampler_linear = a->sampler_nearest = a->history[0] = a->history[1] = a->prev_depth = 0;
    a->hw = a->hh = a->dw = a->dh = a->hformat = 0;
}

static void destroy(void *user) { free(user); }

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "aa",
    .version = "1.0",
    .description = "Antialiasing: FXAA (Lottes 2009) and TAA (Karis 2014: jitter, motion-vector reprojection, "
                   "neighbourhood clamping, disocclusion rejection); reference: core.ssaa=8.",
    .create = create,
    .activate = activate,
    .begin_frame = begin_frame,
    .deactivate = deactivate,
    .destroy = destroy,
    .default_for = SL_PLUGIN_DEFAULT_EVERY_SCENE, /* antialiasing is on by default (README) */
};

SL_DEFINE_PLUGIN(desc)
