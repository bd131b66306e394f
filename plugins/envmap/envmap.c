/* envmap: environment lighting end to end. The scene's "environment" (a lat-long, a cube map as
 * a cross, strip or six faces, RGBE8 PNG, a shadelab-cube prefiltered chain, a constant colour,
 * or the procedural sky when nothing is given) is drawn as the background and lights every
 * material: "mirror" and "environment" look it up, ggx materials get split-sum image-based
 * lighting, everything else diffuse irradiance. envmap.mode = reference swaps the split sum for
 * Monte Carlo integration with the exact BRDF. See README.md; the shared implementation (also
 * used by tools/cube) is the library envmap_prefilter, include/envmap/prefilter.h and io.h. */
#include <shadelab/shadelab.h>
#include <shadelab/cache.h>
#include <shadelab/input.h>
#include <shadelab/matrix.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/ext/budget.h>
#include "envmap/io.h"
#include "envmap/prefilter.h"
#include "reflections.h"
#include "lobe_fit.h"
#include "lobe_fit_table.h"
#include <errno.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define LUT_SAMPLES 1024
#define SKY_WIDTH 1024
#define CONSTANT_CUBE 8 /* a constant environment prefilters to itself: no need for a big cube */

static const char *const modes[] = {"split-sum", "reference", NULL};
static const char *const speculars[] = {"mirror", "dominant", "fis", "hybrid", "filtered", "fitted", NULL};
static const char *const irradiance_methods[] = {"sh", "convolved", NULL};
static const char *const level_maps[] = {"sqrt", "log", NULL}; /* em_level_map's order */
static const char *const reflection_methods[] = {"sky", "screen", NULL};

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "yaw", .type = SL_PARAM_FLOAT, .min = -360, .max = 360, .step = 1, .unit = "deg", .group = "environment",
      .description = "Turns the environment about +Y (+Z towards +X), added to the scene environment's yaw."),
    P(.id = "background", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "environment",
      .description = "Draw the environment behind the geometry (off: the core's constant clear colour)."),
    P(.id = "mode", .type = SL_PARAM_ENUM, .enum_values = modes, .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "lighting",
      .description = "split-sum: prefiltered image-based lighting (envmap.specular says how); reference: Monte Carlo "
                     "integration of the source with the exact BRDF (accumulate frames)."),
    P(.id = "specular", .type = SL_PARAM_ENUM, .enum_values = speculars, .default_value = {.i = 5},
      .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = "lighting",
      .description = "ggx's environment specular in split-sum mode: mirror: the prefiltered chain along the mirror "
                     "direction (Karis 2013); dominant: along GGX's dominant, off-specular direction (Lagarde & de "
                     "Rousiers 2014), one lookup; fis: filtered importance sampling, fis_samples GGX visible-normal "
                     "samples per pixel from the base cube's mips (Krivanek & Colbert 2007), Monte Carlo, times the "
                     "environment BRDF; hybrid: fis below hybrid_alpha, dominant above, its sequence continuing over "
                     "a TAA still's frames (a still converges, its frames are noisy); filtered: deterministic fis "
                     "with one sample set for every pixel reading the prefiltered chain, turned from frame to frame "
                     "of a still; fitted (default: deterministic, no noise, the first-frame chart's choice): three "
                     "lookups of the chain fitted to GGX's real lobe per (n.v, alpha), along the plane of incidence."),
    P(.id = "fis_samples", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 1, .max = 32, .group = "lighting",
      .flags = SL_PARAM_QUALITY_KNOB,
      .description = "Samples per pixel of specular=fis and hybrid (1, 2, 4, 8, 16, 32: error falls with cost; the "
                     "frames of a TAA still and of an accumulated render continue the sequence)."),
    P(.id = "hybrid_alpha", .type = SL_PARAM_FLOAT, .default_value = {.f = {1.1f}}, .min = 0, .max = 2, .step = 0.05f,
      .group = "lighting",
      .description = "specular=hybrid: GGX alpha from which the dominant lookup alone is used; fis's samples below "
                     "hybrid_alpha - 0.25, fading between."),
    P(.id = "fis_lod_bias", .type = SL_PARAM_FLOAT, .default_value = {.f = {0}}, .min = -3, .max = 3, .step = 0.25f,
      .group = "lighting",
      .description = "Bias added to specular=fis's per-sample mip level (1/2 log2 of the sample's solid angle over the base "
                     "texel's); Krivanek & Colbert use +1, chosen here from the measured error."),
    P(.id = "filtered_samples", .type = SL_PARAM_INT, .default_value = {.i = 48}, .min = 1, .max = 64, .group = "lighting",
      .flags = SL_PARAM_QUALITY_KNOB,
      .description = "Samples per pixel of specular=filtered: one set shared by every pixel (deterministic; "
                     "turned from frame to frame of a still); error falls with cost (bench/cycles.sh)."),
    P(.id = "filtered_lod_bias", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = -3, .max = 3, .step = 0.25f,
      .group = "lighting",
      .description = "specular=filtered: each sample reads the prefiltered chain at the roughness whose lobe covers its "
                     "share of the real lobe, times 2^bias (0: the sub-lobes just tile it; more: smoother, blurrier)."),
    P(.id = "filtered_alpha", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = 0, .max = 2, .step = 0.05f,
      .group = "lighting",
      .description = "specular=filtered: GGX alpha from which the dominant lookup alone is used (1 lookup); the "
                     "filtered samples below filtered_alpha - 0.25, fading between (2: filtered at every alpha)."),
    P(.id = "filtered_deconvolve", .type = SL_PARAM_FLOAT, .default_value = {.f = {3}}, .min = 0, .max = 8,
      .step = 0.5f, .group = "lighting",
      .description = "specular=filtered: samples the lobe narrowed to alpha/sqrt(1 + k 4^filtered_lod_bias/N), so that "
                     "with the sub-lobes' blur it comes out at alpha (k = this; 0: off)."),
    P(.id = "irradiance", .type = SL_PARAM_ENUM, .enum_values = irradiance_methods,
      .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = "lighting",
      .description = "Diffuse irradiance: order-2 spherical harmonics (9 coefficients) or a convolved cube."),
    P(.id = "cube_size", .type = SL_PARAM_INT, .default_value = {.i = 256}, .min = 8, .max = 2048, .step = 8, .unit = "px",
      .group = "prefilter", .flags = SL_PARAM_QUALITY_KNOB,
      .description = "Face size of the base and prefiltered specular cubes."),
    P(.id = "samples", .type = SL_PARAM_INT, .default_value = {.i = 512}, .min = 1, .max = 65536, .group = "prefilter",
      .flags = SL_PARAM_QUALITY_KNOB, .description = "GGX importance samples per texel of the specular prefilter."),
    P(.id = "mip_count", .type = SL_PARAM_INT, .default_value = {.i = 7}, .min = 2, .max = 12, .group = "prefilter",
      .flags = SL_PARAM_QUALITY_KNOB,
      .description = "Roughness levels of the specular chain (level_map=sqrt: level m for roughness m/(count-1)); "
                     "at most log2(cube_size), "
                     "so that the roughest level keeps 2x2 texels a face (bench/levels.sh)."),
    P(.id = "level_map", .type = SL_PARAM_ENUM, .enum_values = level_maps, .group = "prefilter",
      .flags = SL_PARAM_QUALITY_KNOB,
      .description = "Roughness of the chain's levels: sqrt: level m for perceptual roughness m/(count-1) (lod = "
                     "sqrt(alpha)(count-1)); log: alpha halves from level to level (measured worse: bench/level_map.sh)."),
    P(.id = "lut_size", .type = SL_PARAM_INT, .default_value = {.i = 64}, .min = 8, .max = 512, .group = "prefilter",
      .flags = SL_PARAM_QUALITY_KNOB, .unit = "px", .description = "Size of the RGBA16F environment-BRDF table."),
    P(.id = "lod_bias", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = -2, .max = 4, .step = 0.25f,
      .group = "prefilter", .description = "Bias added to the PDF-chosen source mip level of each prefilter sample."),
    P(.id = "multiscatter", .type = SL_PARAM_BOOL, .group = "lighting",
      .description = "Multiple-scattering compensation of the split-sum specular (Fdez-Aguera 2019)."),
    P(.id = "reference_samples", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 1, .max = 4096,
      .group = "reference", .description = "Samples per pixel and frame of the Monte Carlo reference."),
    P(.id = "reference_env_sampling", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "reference",
      .description = "The reference samples a lat-long environment by its luminance too, combined with BRDF sampling by "
                     "multiple importance sampling (off: BRDF sampling alone, to compare)."),
    P(.id = "reference_seed", .type = SL_PARAM_INT, .min = 0, .max = 1 << 20, .group = "reference",
      .description = "Starts the reference's sample sequence elsewhere: renders with different seeds are independent "
                     "estimates (their spread is the reference's noise)."),
    P(.id = "cache", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "prefilter",
      .description = "Keep prefiltered cubes on disk ($SHADELAB_CACHE, else ~/.cache/shadelab), keyed by input and parameters."),
    P(.id = "seamless", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "prefilter",
      .description = "GL_TEXTURE_CUBE_MAP_SEAMLESS: filter across cube face edges (off shows the seams)."),
    P(.id = "reflections", .type = SL_PARAM_ENUM, .enum_values = reflection_methods,
      .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB,
      .group = "reflections",
      .description = "What smooth surfaces reflect: sky: the environment alone; screen: the scene itself where a "
                     "reflected ray meets it on screen (one more draw of the opaque scene, at reflections_scale, "
                     "when the view or the scene changes; the environment elsewhere)."),
    P(.id = "reflections_alpha", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.2f}}, .min = 0.01f, .max = 1,
      .step = 0.01f, .group = "reflections",
      .description = "reflections=screen: GGX alpha from which a lobe reflects the environment alone (one ray cannot "
                     "stand for a wide lobe); fading in from half of it."),
    P(.id = "reflections_scale", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.5f}}, .min = 0.25f, .max = 1,
      .step = 0.25f, .group = "reflections",
      .description = "reflections=screen: the size of the scene's image the rays read, relative to the frame."),
    P(.id = "reflections_steps", .type = SL_PARAM_INT, .default_value = {.i = 32}, .min = 4, .max = 128,
      .group = "reflections",
      .description = "reflections=screen: steps along each ray before bisecting to the surface it crossed."),
    P(.id = "sun_elevation", .type = SL_PARAM_FLOAT, .default_value = {.f = {35}}, .min = -EM_SKY_ELEVATION_MAX, .max = EM_SKY_ELEVATION_MAX, .unit = "deg",
      .group = "sky", .description = "Procedural sky (used when the scene gives no environment): sun elevation."),
    P(.id = "sun_azimuth", .type = SL_PARAM_FLOAT, .default_value = {.f = {60}}, .min = -EM_SKY_AZIMUTH_MAX, .max = EM_SKY_AZIMUTH_MAX, .unit = "deg",
      .group = "sky", .description = "Procedural sky: sun azimuth, 0 towards +Z, 90 towards +X."),
    P(.id = "sun_irradiance", .type = SL_PARAM_FLOAT, .default_value = {.f = {3}}, .min = 0, .max = EM_SKY_IRRADIANCE_MAX, .unit = "W/m2",
      .zero_label = "no sun", .group = "sky", .description = "Procedural sky: irradiance of the sun disk (1.5 deg radius) at normal incidence; 0 = no sun."),
    P(.id = "ground_color", .type = SL_PARAM_COLOR, .default_value = {.f = {0.10f, 0.09f, 0.08f}}, .group = "sky",
      .description = "Procedural sky: radiance below the horizon, the ground beyond the scene (a scene whose floor ends "
                     "sets it to the floor's lit radiance, so no band shows between floor and sky)."),
    P(.id = "sun_light", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "sky",
      .description = "Procedural sky: its sun lights the scene as a directional light of its own (light envmap.sun: "
                     "shadowed where a shadow plugin is on, exact for every BRDF) and the sky's image-based "
                     "lighting leaves the disk out; the background still shows it. Off: the disk lights through "
                     "the environment, unshadowed."),
};

#define C(...) {.struct_size = sizeof(sl_shader_chunk_desc), __VA_ARGS__}
static const sl_shader_chunk_desc chunks[] = {
    C(.hook = SL_HOOK_SHADING_MODEL, .file = "envmap_shading.glsl", .function = "envmap_model_none", .name = "mirror"),
    C(.hook = SL_HOOK_SHADING_MODEL, .file = "envmap_shading.glsl", .function = "envmap_model_none", .name = "environment"),
    C(.hook = SL_HOOK_MODEL_LOBES, .file = "envmap_shading.glsl", .function = "envmap_mirror_lobes", .name = "mirror"),
    C(.hook = SL_HOOK_MODEL_LOBES, .file = "envmap_shading.glsl", .function = "envmap_environment_lobes", .name = "environment"),
    C(.hook = SL_HOOK_AMBIENT, .file = "envmap_shading.glsl", .function = "envmap_ambient"),
};

typedef struct envmap {
    const sl_host *host;
    int unit_2d, unit_cube, unit_spec, unit_irr, unit_lut, unit_base; /* unit_cube = unit_2d + 1 (em_gpu) */
    int unit_dist, unit_marginal; /* the reference's environment distribution */
    int unit_spec_blinn;          /* the Blinn-Phong lobes' chain */
    int unit_lobes;               /* specular=fitted's table */
    em_gpu gpu;
    sl_program *progs[6];
    /* [source kind]: 0 a lat-long, 1 a cube (ENVMAP_SOURCE_CUBE), 2 the procedural sky evaluated
     * per pixel (ENVMAP_SOURCE_SKY) */
    sl_program *bg_prog[4], *bg_in_place_prog[4]; /* lat-long, cube, sky, sky with its sun disk */
    bool is_sky;   /* the source is the procedural sky (sky: its parameters) */
    em_sky sky;
    /* the sky's sun as a light (sun_light): its handle (host add_light; -1: none) and whether the
     * sky's lighting leaves the disk to it */
    int sun_handle;
    bool sun_is_light;
    /* the environment as other plugins see it (shadelab.environment/1) while the sun is a light:
     * the base cube with the disk put back (ensure_ext_base), its key */
    unsigned ext_base;
    uint64_t ext_base_key;
    unsigned empty_vao; /* the in-place background's full-screen triangle */
    char glsl_dir[2048];
    uint64_t glsl_hash;
    /* the source */
    char *src_key;
    bool have_src, constant;
    bool bg_is_clear; /* the environment is the scene's constant colour: the core's clear shows it */
    em_env_kind kind;
    unsigned src_tex, dummy_2d, dummy_cube;
    int src_w, src_h;
    uint64_t src_hash;
    float clear[3], scale, scene_yaw;
    /* derived, each with the key it was built for */
    unsigned base, spec, irr, lut;
    unsigned lobe_table; /* specular=fitted's lobes (lobe_fit_table.h), made where a program reads them */
    int base_size, spec_levels, lut_size;
    uint64_t base_key, spec_key, irr_key, sh_key;
    bool spec_from_chain;
    /* the chain of Blinn-Phong lobes (the lobe contract, ABI 1.19), made only when a material's
     * program reads it (envmap_spec_blinn): the GGX chain's settings, its own key and cache file */
    unsigned spec_blinn;
    uint64_t spec_blinn_key;
    bool blinn_store_pending;
    /* the reference's environment importance sampling (a lat-long source): RG32F (conditional
     * CDF, pdf) and R32F marginal CDF, em_env_distribution's arrays; dist_total 0 = none */
    unsigned dist, marginal;
    int dist_w, dist_h;
    double dist_total;
    uint64_t dist_key;
    float sh[9][3];
    bool sh_valid;
    /* a lat-long source's SH projection, made on the CPU from the pixels as loaded (src_sh_valid):
     * ensure_sh then reads nothing back from the GPU */
    float src_sh[9][3];
    bool src_sh_valid;
    double progress_start, progress_last;
    /* a prefiltered chain issued without waiting, written to the disk cache later (store_pending) */
    bool store_pending;
    uint64_t store_key;
    int store_size, store_levels;
    em_reflections refl; /* reflections=screen */
} envmap;

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static sl_value param(envmap *e, const char *id) {
    char full[64];
    snprintf(full, sizeof full, "envmap.%s", id);
    return e->host->get_param(e->host, full);
}

/* ---------------------------------------------------------------- GL state */

typedef struct gl_state {
    int draw_fbo, read_fbo, program, vao, viewport[4];
    bool depth, cull, blend, scissor;
} gl_state;

static void save_state(gl_state *s) {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    s->depth = glIsEnabled(GL_DEPTH_TEST);
    s->cull = glIsEnabled(GL_CULL_FACE);
    s->blend = glIsEnabled(GL_BLEND);
    s->scissor = glIsEnabled(GL_SCISSOR_TEST);
}

static void restore_state(const gl_state *s) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s->draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s->read_fbo);
    glUseProgram(s->program);
    glBindVertexArray(s->vao);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    (s->depth ? glEnable : glDisable)(GL_DEPTH_TEST);
    (s->cull ? glEnable : glDisable)(GL_CULL_FACE);
    (s->blend ? glEnable : glDisable)(GL_BLEND);
    (s->scissor ? glEnable : glDisable)(GL_SCISSOR_TEST);
}

/* Envmap's own GPU work (prefiltering, conversions) in the middle of another's frame: the GL state
 * saved and cube seams filtered (the prefilter always filters across face edges); gpu_work_end puts
 * both back, seamless filtering as the "seamless" parameter says. */
static void gpu_work_begin(gl_state *st) {
    save_state(st);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
}

static void gpu_work_end(envmap *e, const gl_state *st) {
    (param(e, "seamless").b ? glEnable : glDisable)(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    restore_state(st);
}

static void delete_tex(unsigned *t) {
    if (*t) glDeleteTextures(1, t);
    *t = 0;
}

/* em_gpu_init's programs, in its order (e->progs, refresh_programs' mask bits) */
enum { PROG_TO_CUBE = 1, PROG_GGX = 2, PROG_IRRADIANCE = 4, PROG_LUT = 8, PROG_DOWNSAMPLE = 16, PROG_CUBE_TO_CUBE = 32 };
/* em_gpu's ids until refresh_programs sets them: em_gpu_init only needs them non-zero */
#define LAZY_PROGRAM_ID (~0u)

/* The host may rebuild programs (hot reload): refresh the ids before every use, those of the
 * programs the step uses only. Each compiles at its first program_id() (lazy, as every plugin
 * program: the procedural sky's set-up needs no conversion, downsampling or irradiance program,
 * issue 19); one that fails to compile disables the plugin as a failing activate() did. */
static void refresh_programs(envmap *e, unsigned which) {
    unsigned *ids[6] = {&e->gpu.prog_to_cube, &e->gpu.prog_ggx,        &e->gpu.prog_irradiance,
                        &e->gpu.prog_lut,     &e->gpu.prog_downsample, &e->gpu.prog_cube_to_cube};
    for (int i = 0; i < 6; i++)
        if (which & (1u << i)) *ids[i] = e->host->program_id(e->host, e->progs[i]);
}

static void progress(void *user, double fraction, const char *what) {
    envmap *e = user;
    double t = now_s();
    if (t - e->progress_start < 1.0 || t - e->progress_last < 0.5) return;
    e->progress_last = t;
    e->host->log(e->host, SL_LOG_INFO, "%s: %3.0f%% (%.1f s)", what, 100 * fraction, t - e->progress_start);
}

/* ---------------------------------------------------------------- disk cache */

static bool cache_dir(envmap *e, char *out, size_t n) {
    return param(e, "cache").b && sl_cache_dir("envmap", out, n, true);
}

typedef struct cache_header { char magic[8]; uint64_t key; int32_t size, levels; } cache_header;

static unsigned cache_load(envmap *e, uint64_t key, int size, int levels, char *path, size_t n) {
    char dir[2048];
    if (!cache_dir(e, dir, sizeof dir)) return 0;
    snprintf(path, n, "%s/spec-%016llx.bin", dir, (unsigned long long)key);
    int fd = sl_open_input_file(path, NULL, 0); /* a regular file only: never blocks on a FIFO */
    FILE *f = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        if (fd >= 0) close(fd);
        return 0;
    }
    cache_header h;
    unsigned tex = 0;
    if (fread(&h, sizeof h, 1, f) == 1 && !memcmp(h.magic, "SLENVC1", 8) && h.key == key && h.size == size &&
        h.levels == levels) {
        tex = em_new_cube(size, levels);
        bool ok = true;
        for (int l = 0; l < levels && ok; l++) {
            int s = size >> l > 0 ? size >> l : 1;
            size_t bytes = (size_t)6 * s * s * 4 * 2;
            uint16_t *buf = malloc(bytes);
            ok = fread(buf, 1, bytes, f) == bytes;
            if (ok) glTextureSubImage3D(tex, l, 0, 0, 0, s, s, 6, GL_RGBA, GL_HALF_FLOAT, buf);
            free(buf);
        }
        if (!ok) delete_tex(&tex);
    }
    fclose(f);
    return tex;
}

static void cache_store(envmap *e, uint64_t key, unsigned tex, int size, int levels) {
    char dir[2048], path[2300], tmp[2400];
    if (!cache_dir(e, dir, sizeof dir)) return;
    snprintf(path, sizeof path, "%s/spec-%016llx.bin", dir, (unsigned long long)key);
    snprintf(tmp, sizeof tmp, "%s.%d.tmp", path, (int)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) return;
    cache_header h = {"SLENVC1", key, size, levels};
    bool ok = fwrite(&h, sizeof h, 1, f) == 1;
    for (int l = 0; l < levels && ok; l++) {
        int s = size >> l > 0 ? size >> l : 1;
        size_t bytes = (size_t)6 * s * s * 4 * 2;
        uint16_t *buf = malloc(bytes);
        glGetTextureImage(tex, l, GL_RGBA, GL_HALF_FLOAT, (int)bytes, buf);
        ok = fwrite(buf, 1, bytes, f) == bytes;
        free(buf);
    }
    ok = fclose(f) == 0 && ok;
    if (ok && rename(tmp, path) == 0) return;
    unlink(tmp);
    e->host->log(e->host, SL_LOG_WARN, "could not write the prefilter cache %s", path);
}

/* ---------------------------------------------------------------- the source */

/* The chain issued by ensure_spec without waiting is finished by the next frame (or at
 * deactivate): read it back into the disk cache then. */
static void store_pending(envmap *e) {
    if (!e->store_pending) return;
    e->store_pending = false;
    if (e->spec && e->spec_key == e->store_key) cache_store(e, e->store_key, e->spec, e->store_size, e->store_levels);
}
static void store_pending_blinn(envmap *e) {
    if (!e->blinn_store_pending) return;
    e->blinn_store_pending = false;
    if (e->spec_blinn) cache_store(e, e->spec_blinn_key, e->spec_blinn, e->base_size, e->spec_levels);
}

static void free_derived(envmap *e) {
    e->store_pending = false;
    delete_tex(&e->base);
    delete_tex(&e->ext_base);
    delete_tex(&e->spec); /* ours, also when it came from a precomputed chain */
    delete_tex(&e->spec_blinn);
    e->blinn_store_pending = false;
    e->spec_blinn_key = 0;
    e->spec_from_chain = false;
    delete_tex(&e->irr);
    delete_tex(&e->dist);
    delete_tex(&e->marginal);
    e->dist_total = 0;
    e->base_key = e->spec_key = e->irr_key = e->sh_key = e->dist_key = 0;
    e->sh_valid = false;
}

/* SH irradiance from a lat-long's own pixels (the source, not the base cube resampled from it). */
static void project_source_sh(envmap *e, const em_image *latlong) {
    double sh[9][3];
    em_sh9_project_latlong(latlong, sh);
    em_sh9_diffuse_coefficients(sh, e->src_sh);
    e->src_sh_valid = true;
}

static void upload_source(envmap *e, em_env *env, const char *name) {
    e->kind = env->kind;
    e->src_sh_valid = false;
    if (env->kind == EM_ENV_LATLONG) {
        project_source_sh(e, &env->latlong);
        e->src_tex = em_upload_latlong(&env->latlong);
        e->src_w = env->latlong.w, e->src_h = env->latlong.h;
        e->src_hash = em_hash(env->latlong.px, (size_t)e->src_w * e->src_h * 4 * sizeof(float), 1);
    } else {
        e->src_tex = em_upload_cube(env->faces, env->size, em_max_levels(env->size));
        e->src_w = e->src_h = env->size;
        e->src_hash = 2;
        for (int f = 0; f < 6; f++) e->src_hash = em_hash(env->faces[f], (size_t)env->size * env->size * 16, e->src_hash);
        if (env->chain_levels) {
            e->spec = em_upload_cube_levels(env->chain, env->size, env->chain_levels);
            e->spec_levels = env->chain_levels;
            e->spec_from_chain = true;
            e->host->log(e->host, SL_LOG_INFO, "%s: using its %d precomputed specular levels (the prefilter parameters "
                         "do not apply)", name, env->chain_levels);
        }
    }
}

/* The procedural sky, set up without a GPU program (start-up, issue 19): on llvmpipe each program
 * costs tens of ms of compile at its first draw, and the sky is at hand on the CPU. The lat-long
 * (for the background) gets its box mips from here instead of glGenerateMipmap, and the base cube
 * (what the prefilter reads) is em_make_base_cube's conversion done on the CPU at the current
 * cube size up to SKY_CPU_CUBE_MAX; a larger or later cube_size converts on the GPU from the
 * uploaded lat-long when something first reads the cube (ensure_base). The CPU's cost grows with
 * the faces' texels (16 sub-samples each: about 35 ms at 64², 0.55 s at 256² on one core), the
 * GPU's compile does not: ggx_layers.json (256²) started in 1.46 s, 0.89 s on the GPU. */
#define SKY_CPU_CUBE_MAX 64
static int eff_cube_size(envmap *e);
static void upload_sky(envmap *e, em_env *env) {
    em_image mips[16];
    int n = 0;
    em_latlong_mips(&env->latlong, mips, 16, &n);
    e->kind = EM_ENV_LATLONG;
    project_source_sh(e, &env->latlong);
    glCreateTextures(GL_TEXTURE_2D, 1, &e->src_tex);
    glTextureStorage2D(e->src_tex, n, GL_RGBA16F, mips[0].w, mips[0].h);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (int l = 0; l < n; l++) glTextureSubImage2D(e->src_tex, l, 0, 0, mips[l].w, mips[l].h, GL_RGBA, GL_FLOAT, mips[l].px);
    glTextureParameteri(e->src_tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(e->src_tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(e->src_tex, GL_TEXTURE_WRAP_S, GL_REPEAT); /* u wraps around the sphere */
    glTextureParameteri(e->src_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(e->src_tex, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    e->src_w = mips[0].w, e->src_h = mips[0].h;
    e->src_hash = em_hash(mips[0].px, (size_t)e->src_w * e->src_h * 4 * sizeof(float), 1); /* as upload_source */
    int size = eff_cube_size(e), levels = em_max_levels(size);
    if (size <= SKY_CPU_CUBE_MAX) {
        float *faces[16] = {0};
        em_latlong_to_cube_levels(mips, n, size, levels, faces);
        e->base = em_upload_cube_levels(faces, size, levels);
        e->base_size = size;
        e->base_key = em_hash(&size, sizeof size, e->src_hash); /* ensure_base's key: it keeps this cube */
        for (int l = 0; l < levels; l++) free(faces[l]);
    }
    for (int l = 1; l < n; l++) free(mips[l].px);
}

/* The core's procedural textures (host ABI 1.7): envmap parses no texture spec of its own. */
static float *core_pattern(void *user, const char *spec, int size, char *err, size_t n) {
    const sl_host *h = user;
    if (h->struct_size < offsetof(sl_host, procedural_image) + sizeof h->procedural_image || !h->procedural_image) {
        snprintf(err, n, "procedural environment '%s': this host has no procedural textures (needs the SDK ABI 1.7)", spec);
        return NULL;
    }
    return h->procedural_image(h, spec, size, err, n);
}

/* Image files through the core's loader (host ABI 1.10): the plugin links no image library. */
static bool host_read(void *ctx, const char *path, em_image *out, em_io_info *info, char *err, size_t n) {
    const sl_host *h = ctx;
    memset(out, 0, sizeof *out);
    memset(info, 0, sizeof *info);
    if (h->struct_size < offsetof(sl_host, read_image) + sizeof h->read_image || !h->read_image) {
        snprintf(err, n, "%s: this host cannot read image files for plugins (needs the SDK ABI 1.10)", path);
        return false;
    }
    sl_image_file f = {.struct_size = sizeof f};
    if (!h->read_image(h, path, &f, err, n)) return false;
    out->w = f.width, out->h = f.height, out->px = f.pixels;
    info->bits = f.bits, info->channels = f.channels, info->is_float = f.is_float;
    snprintf(info->description, sizeof info->description, "%s", f.description);
    info->srgb = f.srgb;
    snprintf(info->format, sizeof info->format, "%s", f.format);
    return true;
}

/* Whether the sky's sun should be a light of its own: asked for, and the host can add one. */
static bool sun_light_wanted(envmap *e) { return e->sun_handle >= 0 && param(e, "sun_light").b; }

/* The procedural sky of the current parameters. */
static em_sky sky_params(envmap *e) {
    em_sky sky;
    em_sky_default(&sky);
    sky.sun_elevation_deg = param(e, "sun_elevation").f[0];
    sky.sun_azimuth_deg = param(e, "sun_azimuth").f[0];
    sky.sun_irradiance = param(e, "sun_irradiance").f[0];
    memcpy(sky.ground, param(e, "ground_color").f, sizeof sky.ground);
    return sky;
}

static void load_source(envmap *e, const char *map, const float env[5]) {
    free_derived(e);
    em_reflections_free(&e->refl);
    delete_tex(&e->src_tex);
    e->have_src = false;
    e->sun_is_light = false;
    e->constant = e->bg_is_clear = false;
    e->scale = env[3];
    e->scene_yaw = env[4];
    for (int c = 0; c < 3; c++) e->clear[c] = env[c] * env[3];
    char err[4096] = "";
    em_env loaded = {0};
    bool ok = false, is_sky = false;
    const char *name = map ? map : "procedural sky";
    if (map && em_is_procedural(map)) {
        loaded.kind = EM_ENV_LATLONG;
        ok = em_procedural(map, core_pattern, (void *)e->host, &loaded.latlong, &e->constant, err, sizeof err);
        if (ok) em_sanitize(loaded.latlong.px, (size_t)loaded.latlong.w * loaded.latlong.h, &loaded.stats);
    } else if (map) {
        em_reader reader = {host_read, (void *)e->host};
        ok = em_env_load(map, &reader, &loaded, err, sizeof err);
        if (ok) e->host->log(e->host, SL_LOG_INFO, "%s: %s", map, loaded.how);
    }
    if (map && !ok) e->host->log(e->host, SL_LOG_ERROR, "%s; using the procedural sky instead", err);
    if (!ok && !map && (env[0] > 0 || env[1] > 0 || env[2] > 0)) {
        /* no map, a constant colour: that is the environment (intensity applies as scale) */
        char spec[128];
        snprintf(spec, sizeof spec, "constant:%g,%g,%g", env[0], env[1], env[2]);
        loaded.kind = EM_ENV_LATLONG;
        ok = em_procedural(spec, core_pattern, (void *)e->host, &loaded.latlong, &e->constant, err, sizeof err);
        e->bg_is_clear = ok;
        name = "constant environment";
    }
    if (!ok) {
        em_env_free(&loaded);
        e->sky = sky_params(e);
        /* the sun as a light of its own: the sky's lighting leaves the disk out (the background,
         * drawn from e->sky, keeps it) */
        e->sun_is_light = sun_light_wanted(e) && e->sky.sun_irradiance > 0;
        em_sky lit = e->sky;
        if (e->sun_is_light) lit.sun_irradiance = 0;
        loaded.kind = EM_ENV_LATLONG;
        em_sky_latlong(&lit, SKY_WIDTH, SKY_WIDTH / 2, &loaded.latlong);
        name = "procedural sky";
        is_sky = true;
    }
    const em_sanitize_stats *s = &loaded.stats;
    if (s->nan + s->inf + s->negative)
        e->host->log(e->host, SL_LOG_WARN,
                     "%s: replaced %ld invalid values (%ld NaN, %ld infinite, %ld negative): NaN, -Inf and negatives "
                     "became 0, +Inf became 65504", name, s->nan + s->inf + s->negative, s->nan, s->inf, s->negative);
    if (s->clamped)
        e->host->log(e->host, SL_LOG_INFO, "%s: %ld values above 65504 (largest %g) clamped to the half-float limit",
                     name, s->clamped, s->max_value);
    e->is_sky = is_sky;
    if (is_sky) upload_sky(e, &loaded);
    else upload_source(e, &loaded, name);
    em_env_free(&loaded);
    e->have_src = true;
}

/* ---------------------------------------------------------------- derived products */

static int eff_cube_size(envmap *e) {
    if (e->constant) return CONSTANT_CUBE;
    int n = param(e, "cube_size").i, p = 8;
    while (p * 2 <= n) p *= 2; /* power of two: the mip chain halves exactly */
    return p;
}

static void ensure_base(envmap *e) {
    int size = eff_cube_size(e);
    uint64_t key = em_hash(&size, sizeof size, e->src_hash);
    if (e->base && e->base_key == key) return;
    delete_tex(&e->base);
    refresh_programs(e, (e->kind == EM_ENV_CUBE ? PROG_CUBE_TO_CUBE : PROG_TO_CUBE) | PROG_DOWNSAMPLE);
    e->base = em_make_base_cube(&e->gpu, e->src_tex, e->kind == EM_ENV_CUBE, e->src_w, e->src_h, size);
    e->base_size = size;
    e->base_key = key;
}

/* The extension's cube while the sun is a light: the base cube leaves the disk to the light, but
 * a plugin looking radiance up along a direction (refraction's glass ignores lights) must see the
 * sky as it is. The full sky converted on the CPU as upload_sky does, at the base cube's size. */
static uint64_t ext_base_key(envmap *e) { return e->base_key ^ 0x5355u; /* "SU": with the sun */ }
static bool ext_base_current(envmap *e) { return e->ext_base && e->ext_base_key == ext_base_key(e); }
static void ensure_ext_base(envmap *e) {
    uint64_t key = ext_base_key(e);
    if (ext_base_current(e)) return;
    delete_tex(&e->ext_base);
    em_image full = {0}, mips[16];
    int n = 0, size = e->base_size, levels = em_max_levels(size);
    em_sky_latlong(&e->sky, SKY_WIDTH, SKY_WIDTH / 2, &full);
    em_latlong_mips(&full, mips, 16, &n);
    float *faces[16] = {0};
    em_latlong_to_cube_levels(mips, n, size, levels, faces);
    e->ext_base = em_upload_cube_levels(faces, size, levels);
    e->ext_base_key = key;
    for (int l = 0; l < levels; l++) free(faces[l]);
    for (int l = 1; l < n; l++) free(mips[l].px);
    em_image_free(&full);
}

/* The GGX chain's settings and the key of everything it is made from (source, GLSL, settings). */
typedef struct spec_settings {
    int size, samples, levels, map;
    float bias;
} spec_settings;

static uint64_t spec_key(envmap *e, spec_settings *o) {
    spec_settings t;
    t.size = eff_cube_size(e);
    t.samples = e->constant ? 64 : param(e, "samples").i;
    t.levels = param(e, "mip_count").i;
    /* Level m is a (size/2^m)² mip: a chain down to 1² stores the roughest lobe in one texel a
     * face, and α = 1 measured 3-4x worse vs the reference than with a last level of 2² or more
     * (bench/levels.sh: sky 0.093 vs ≤ 0.023, courtyard 0.30 vs ≤ 0.115, any cube size). */
    if (t.levels > em_max_levels(t.size) - 1) t.levels = em_max_levels(t.size) - 1;
    if (t.levels < 2) t.levels = 2;
    t.bias = param(e, "lod_bias").f[0];
    t.map = param(e, "level_map").i;
    uint64_t key = e->src_hash ^ e->glsl_hash;
    int ints[4] = {t.size, t.samples, t.levels, t.map};
    key = em_hash(ints, sizeof ints, key);
    key = em_hash(&t.bias, sizeof t.bias, key);
    if (o) *o = t;
    return key;
}

static void ensure_spec(envmap *e) {
    if (e->spec_from_chain) return;
    spec_settings t;
    uint64_t key = spec_key(e, &t);
    if (e->spec && e->spec_key == key) return;
    int size = t.size, samples = t.samples, levels = t.levels;
    e->store_pending = false;
    delete_tex(&e->spec);
    char path[2400] = "";
    e->spec = cache_load(e, key, size, levels, path, sizeof path);
    if (e->spec) {
        e->host->log(e->host, SL_LOG_DEBUG, "prefilter cache hit: %s", path);
    } else {
        e->host->log(e->host, SL_LOG_DEBUG, "prefiltering the specular chain: %d² cube, %d levels, %d samples", size,
                     levels, samples);
        ensure_base(e);
        refresh_programs(e, PROG_GGX); /* level 0 is a copy of the base (same size: no program) */
        /* Issued without waiting (issue 18 item 5: start-up): on llvmpipe the rasteriser threads
         * prefilter while this thread goes on composing, compiling and drawing the frame (draws
         * that sample the chain come after it in the GL command stream, so they see it done).
         * No per-face progress here, which would wait for each face; the disk cache is written
         * at the next frame or at deactivate, when the work is finished (store_pending). */
        if ((double)size * size * samples >= 256.0 * 256 * 64)
            e->host->log(e->host, SL_LOG_INFO, "prefiltering the GGX chain (%d² cube, %d levels, %d samples) "
                         "alongside the first frame", size, levels, samples);
        em_progress_fn report = e->gpu.progress;
        e->gpu.progress = NULL;
        e->spec = em_prefilter_ggx_map(&e->gpu, e->base, size, levels, samples, t.bias, (em_level_map)t.map);
        e->gpu.progress = report;
        e->store_pending = true;
        e->store_key = key;
        e->store_size = size, e->store_levels = levels;
    }
    e->spec_levels = levels;
    e->spec_key = key;
}

/* The Blinn-Phong chain: the GGX chain's size and levels (a precomputed GGX chain's count), always
 * the log level map (envmap_specular_blinn), prefiltered from the base cube by em_prefilter_chain,
 * issued without waiting as ensure_spec's. */
static void ensure_spec_blinn(envmap *e) {
    spec_settings t;
    uint64_t key = em_hash("blinn-phong, log map", 20, spec_key(e, &t));
    if (e->spec_from_chain) t.levels = e->spec_levels, key = em_hash(&t.levels, sizeof t.levels, key);
    t.map = EM_LEVEL_MAP_LOG;
    if (e->spec_blinn && e->spec_blinn_key == key) return;
    e->blinn_store_pending = false;
    delete_tex(&e->spec_blinn);
    char path[2400] = "";
    e->spec_blinn = cache_load(e, key, t.size, t.levels, path, sizeof path);
    if (!e->spec_blinn) {
        e->host->log(e->host, SL_LOG_DEBUG, "prefiltering the Blinn-Phong chain: %d² cube, %d levels, %d samples", t.size,
                     t.levels, t.samples);
        ensure_base(e);
        refresh_programs(e, PROG_GGX);
        em_progress_fn report = e->gpu.progress;
        e->gpu.progress = NULL;
        e->spec_blinn = em_prefilter_chain(&e->gpu, e->base, t.size, t.levels, t.samples, t.bias, (em_level_map)t.map,
                                           EM_LOBE_BLINN_PHONG);
        e->gpu.progress = report;
        e->blinn_store_pending = true;
    }
    e->spec_levels = t.levels;
    e->spec_blinn_key = key;
}

/* The irradiance a program reads, each made the first time one reads it: the order-2 SH
 * (irradiance=sh, and the dominant light of models lit at it, SL_LOBES_MODEL_AT_DOMINANT_LIGHT,
 * whatever `irradiance` says) and the convolved cube (irradiance=convolved). */
static void ensure_sh(envmap *e) {
    ensure_base(e);
    if (e->sh_valid && e->sh_key == e->base_key) return;
    if (e->src_sh_valid) {
        /* a lat-long source: projected from its pixels when it was loaded. Reading the base cube
         * back waited ≈ 0.1 s in begin_frame for the rasteriser to convert it (head scene). */
        memcpy(e->sh, e->src_sh, sizeof e->sh);
    } else {
        /* a cube source: project a small mip of the base cube (≤ 32²): the box-filtered mips keep
         * the low frequencies SH keeps */
        int level = 0;
        while ((e->base_size >> level) > 32) level++;
        int s = e->base_size >> level;
        float *faces = em_read_cube(e->base, level, s);
        double sh[9][3];
        em_sh9_project(faces, s, sh);
        em_sh9_diffuse_coefficients(sh, e->sh);
        free(faces);
    }
    e->sh_valid = true;
    e->sh_key = e->base_key;
}

static void ensure_convolved(envmap *e) {
    ensure_base(e);
    if (e->irr && e->irr_key == e->base_key) return;
    delete_tex(&e->irr);
    refresh_programs(e, PROG_IRRADIANCE);
    int out = e->base_size < 32 ? e->base_size : 32;
    e->irr = em_convolve_irradiance(&e->gpu, e->base, e->base_size, 16, out);
    e->irr_key = e->base_key;
}

/* The reference's environment distribution, the first time a reference program reads it: the
 * lat-long read back at the mip level ≤ DIST_WIDTH wide (reference mode only, where a read-back
 * is nothing beside the integration), em_env_distribution_build, two float textures. A cube
 * source gets none (the reference then samples the BRDF alone). */
#define DIST_WIDTH 1024
static void ensure_distribution(envmap *e) {
    if (e->dist_key == e->src_hash && (e->dist || e->kind != EM_ENV_LATLONG)) return;
    delete_tex(&e->dist);
    delete_tex(&e->marginal);
    e->dist_total = 0;
    e->dist_key = e->src_hash;
    if (e->kind != EM_ENV_LATLONG || !e->src_tex) return;
    int level = 0, w = e->src_w, h = e->src_h;
    while (w > DIST_WIDTH) w /= 2, h /= 2, level++;
    em_image img = {w, h, malloc((size_t)w * h * 4 * sizeof(float))};
    if (!img.px) return;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(e->src_tex, level, GL_RGBA, GL_FLOAT, (int)((size_t)w * h * 4 * sizeof(float)), img.px);
    em_env_distribution d;
    bool ok = em_env_distribution_build(&img, DIST_WIDTH, &d);
    em_image_free(&img);
    if (!ok) return;
    float *rg = malloc((size_t)d.w * d.h * 2 * sizeof(float));
    if (rg) {
        for (size_t i = 0; i < (size_t)d.w * d.h; i++) rg[2 * i] = d.conditional[i], rg[2 * i + 1] = d.pdf[i];
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glCreateTextures(GL_TEXTURE_2D, 1, &e->dist);
        glTextureStorage2D(e->dist, 1, GL_RG32F, d.w, d.h);
        glTextureSubImage2D(e->dist, 0, 0, 0, d.w, d.h, GL_RG, GL_FLOAT, rg);
        glCreateTextures(GL_TEXTURE_2D, 1, &e->marginal);
        glTextureStorage2D(e->marginal, 1, GL_R32F, d.h, 1);
        glTextureSubImage2D(e->marginal, 0, 0, 0, d.h, 1, GL_RED, GL_FLOAT, d.marginal);
        for (int i = 0; i < 2; i++) {
            unsigned t = i ? e->marginal : e->dist;
            glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        e->dist_w = d.w, e->dist_h = d.h, e->dist_total = d.total;
        free(rg);
    }
    em_env_distribution_free(&d);
}

static void ensure_lut(envmap *e) {
    int size = param(e, "lut_size").i;
    if (e->lut && e->lut_size == size) return;
    delete_tex(&e->lut);
    refresh_programs(e, PROG_LUT);
    e->lut = em_brdf_lut(&e->gpu, size, LUT_SAMPLES);
    e->lut_size = size;
}

/* specular=fitted's table as a 2D array texture, (θ_v, α) with two layers: (t0, a0, w0, t1) and
 * (a1, w1, t2, a2), read bilinearly (envmap_fitted_specular) */
static void ensure_lobe_table(envmap *e) {
    if (e->lobe_table) return;
    enum { T = EM_LOBE_THETAS, A = EM_LOBE_ALPHAS };
    static float texels[2][A][T][4];
    for (int a = 0; a < A; a++)
        for (int t = 0; t < T; t++)
            for (int k = 0; k < 8; k++) texels[k / 4][a][t][k % 4] = em_lobe_table[a][t][k];
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &e->lobe_table);
    glTextureStorage3D(e->lobe_table, 1, GL_RGBA32F, T, A, 2);
    glTextureSubImage3D(e->lobe_table, 0, 0, 0, 0, T, A, 2, GL_RGBA, GL_FLOAT, texels);
    glTextureParameteri(e->lobe_table, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(e->lobe_table, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(e->lobe_table, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(e->lobe_table, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

/* ---------------------------------------------------------------- per frame */

static bool host_scene_uses(envmap *e, const char *uniform) {
    const sl_host *h = e->host;
    return h->struct_size >= offsetof(sl_host, scene_uses_uniform) + sizeof h->scene_uses_uniform &&
           h->scene_uses_uniform && h->scene_uses_uniform(h, uniform);
}

/* What this frame's materials will read, made now rather than at their first bind in the middle of a
 * pass (host ABI 1.11; envmap_bind still makes anything missed, e.g. for override programs): the
 * irradiance (a lat-long's SH was projected on the CPU at load; a cube source's is read back from
 * the base cube, which waits only for the base cube while nothing else is queued), the BRDF LUT
 * and the base cube. The GGX chain is queued by the
 * envmap-prefilter pass (below), after the shadow maps. */
static void prepare(envmap *e) {
    if (!e->have_src) return;
    bool sh = host_scene_uses(e, "envmap_sh"), conv = host_scene_uses(e, "envmap_irr");
    bool lut = host_scene_uses(e, "envmap_lut"), base = host_scene_uses(e, "envmap_base");
    if (!sh && !conv && !lut && !base) return;
    gl_state st;
    gpu_work_begin(&st);
    if (sh) ensure_sh(e);
    if (conv) ensure_convolved(e);
    if (lut) ensure_lut(e);
    if (base) ensure_base(e);
    gpu_work_end(e, &st);
}

/* The GGX chain, in a pass of its own after the shadow maps (stage SL_STAGE_SHADOW + 50), not in
 * begin_frame. On llvmpipe a draw that samples a texture rendered by a draw still queued
 * waits for the rasteriser to reach that draw, and the queue is in order: with the chain issued
 * in begin_frame, ahead of the shadow maps, sss's stretch and irradiance draws (which sample the
 * rim light's shadow map) waited for the whole prefilter, ≈ 0.7 s of a cold head start's main
 * thread (measured with -v: irradiance 732 → 309 ms, stretch 391 → 118 ms with the prefilter
 * emptied to one sample). Issued after the shadow maps, the rasteriser prefilters while this
 * thread composes and compiles the prepasses, and the first pass that waits for it is the first
 * read-back (sss's blurs), which waits for the rasteriser anyway. */
static bool prefilter_active(void *user, const sl_frame *f) {
    envmap *e = user;
    return e->have_src && ((!e->spec_from_chain && host_scene_uses(e, "envmap_spec")) ||
                           host_scene_uses(e, "envmap_spec_blinn"));
}

/* Skipped while the chain it made is current (its key: source, GLSL, settings). */
static uint64_t prefilter_signature(void *user, const sl_frame *f) {
    envmap *e = user;
    (void)f;
    return spec_key(e, NULL) ^ (host_scene_uses(e, "envmap_spec_blinn") ? 0x5b1177 : 0);
}

static void prefilter_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    envmap *e = user;
    gl_state st;
    gpu_work_begin(&st);
    if (!e->spec_from_chain && host_scene_uses(e, "envmap_spec")) ensure_spec(e);
    if (host_scene_uses(e, "envmap_spec_blinn")) ensure_spec_blinn(e);
    gpu_work_end(e, &st);
}

static void update_sun_light(envmap *e);
static void envmap_begin_frame(void *user, const sl_frame *f) {
    envmap *e = user;
    store_pending(e);
    store_pending_blinn(e);
    float env[5];
    const char *map = e->host->environment(e->host, env);
    char key[4400];
    bool sky = !map && !(env[0] > 0 || env[1] > 0 || env[2] > 0);
    const float *ground = param(e, "ground_color").f;
    snprintf(key, sizeof key, "%s|%g %g %g|%g %g %g|%g %g %g|%d", map ? map : "", env[0], env[1], env[2],
             sky ? param(e, "sun_elevation").f[0] : 0.0f, sky ? param(e, "sun_azimuth").f[0] : 0.0f,
             sky ? param(e, "sun_irradiance").f[0] : 0.0f, sky ? ground[0] : 0.0f, sky ? ground[1] : 0.0f,
             sky ? ground[2] : 0.0f, sky && sun_light_wanted(e));
    if (!e->src_key || strcmp(key, e->src_key)) {
        free(e->src_key);
        e->src_key = strdup(key);
        gl_state st;
        save_state(&st);
        load_source(e, map, env);
        restore_state(&st);
    }
    e->scale = env[3];
    e->scene_yaw = env[4];
    for (int c = 0; c < 3; c++) e->clear[c] = env[c] * env[3];
    (param(e, "seamless").b ? glEnable : glDisable)(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    update_sun_light(e);
    prepare(e);
}

static void rotation(envmap *e, float m[9]) { /* world → map: R_y(−yaw), column-major */
    double a = -(e->scene_yaw + param(e, "yaw").f[0]) * M_PI / 180, c = cos(a), s = sin(a);
    float r[9] = {(float)c, 0, (float)-s, 0, 1, 0, (float)s, 0, (float)c};
    memcpy(m, r, sizeof r);
}

/* Light envmap.sun (sun_light): the disk's direction in the world (the map's turned by the yaw),
 * its colour, and the irradiance the disk gives at normal incidence, ∫ L cos over the disk =
 * (E/Ω)·π sin²r = E (1 + cos r)/2, times the environment's intensity. */
static void update_sun_light(envmap *e) {
    if (e->sun_handle < 0) return;
    sl_plugin_light_state st = {.struct_size = sizeof st, .enabled = e->have_src && e->sun_is_light};
    if (st.enabled) {
        double dir[3], r, radiance[3];
        em_sky_sun(&e->sky, dir, &r, radiance);
        float m[9];
        rotation(e, m); /* world → map; its transpose turns the map's direction into the world's */
        for (int i = 0; i < 3; i++)
            st.direction[i] = -(float)(m[i * 3 + 0] * dir[0] + m[i * 3 + 1] * dir[1] + m[i * 3 + 2] * dir[2]);
        double e_disk = radiance[0] * M_PI * sin(r) * sin(r); /* radiance[0]: E/Ω, the colour's red is 1 */
        for (int c = 0; c < 3; c++) st.color[c] = (float)(radiance[c] / radiance[0]);
        st.intensity = (float)(e_disk * e->scale);
    }
    e->host->set_light(e->host, e->sun_handle, &st);
}

static void bind_source(envmap *e, unsigned prog) {
    glBindTextureUnit(e->unit_2d, e->kind == EM_ENV_LATLONG ? e->src_tex : e->dummy_2d);
    glBindTextureUnit(e->unit_cube, e->kind == EM_ENV_CUBE ? e->src_tex : e->dummy_cube);
    glUniform1i(glGetUniformLocation(prog, "envmap_src2d"), e->unit_2d);
    glUniform1i(glGetUniformLocation(prog, "envmap_srccube"), e->unit_cube);
    glUniform1i(glGetUniformLocation(prog, "envmap_is_cube"), e->kind == EM_ENV_CUBE);
    glUniform2f(glGetUniformLocation(prog, "envmap_src_size"), (float)e->src_w, (float)e->src_h);
    float m[9];
    rotation(e, m);
    glUniformMatrix3fv(glGetUniformLocation(prog, "envmap_rot"), 1, GL_FALSE, m);
    glUniform1f(glGetUniformLocation(prog, "envmap_scale"), e->scale);
}

/* envmap_sun_disk's uniforms (mirror and environment programs): the disk the texels leave out. */
static void bind_sun_disk(envmap *e, unsigned prog, const sl_frame *f) {
    int l = glGetUniformLocation(prog, "envmap_sun_radiance");
    if (l < 0) return;
    double dir[3], r, radiance[3];
    em_sky_sun(&e->sky, dir, &r, radiance);
    float k = e->sun_is_light ? e->scale : 0.0f;
    glUniform3f(l, (float)radiance[0] * k, (float)radiance[1] * k, (float)radiance[2] * k);
    glUniform3f(glGetUniformLocation(prog, "envmap_sun_dir"), (float)dir[0], (float)dir[1], (float)dir[2]);
    glUniform1f(glGetUniformLocation(prog, "envmap_sun_radius"), (float)r);
    /* a still's jittered frames: two samples' spacing of the footprint (envmap_sun_disk) */
    bool jittered = f && f->sample_count > 1 && f->sample_index % f->sample_count > 0;
    float footprint = jittered ? fminf(1.0f, 2.0f / sqrtf((float)f->sample_count)) : 1.0f;
    glUniform1f(glGetUniformLocation(prog, "envmap_sun_footprint"), footprint);
}

static void envmap_bind(void *user, unsigned prog, int material, const sl_frame *f) {
    envmap *e = user;
    if (!e->have_src) return;
    int l_spec = glGetUniformLocation(prog, "envmap_spec"), l_irr = glGetUniformLocation(prog, "envmap_irr");
    int l_sh = glGetUniformLocation(prog, "envmap_sh"), l_lut = glGetUniformLocation(prog, "envmap_lut");
    int l_base = glGetUniformLocation(prog, "envmap_base"); /* specular=fis reads the base cube's mips */
    int l_dist = glGetUniformLocation(prog, "envmap_dist"); /* the reference's environment sampling */
    int l_blinn = glGetUniformLocation(prog, "envmap_spec_blinn"); /* a material with Blinn-Phong lobes */
    int l_lobes = glGetUniformLocation(prog, "envmap_lobe_table"); /* specular=fitted */
    /* compute what this program reads, the first time it is needed (a mirror-only scene never
     * prefilters); the forward pass is mid-flight, so GL state is saved and restored */
    bool need_spec = l_spec >= 0 && !e->spec_from_chain, need_lut = l_lut >= 0;
    bool need_base = l_base >= 0, need_dist = l_dist >= 0;
    if (need_spec || l_blinn >= 0 || l_irr >= 0 || l_sh >= 0 || need_lut || need_base || need_dist) {
        gl_state st;
        gpu_work_begin(&st);
        if (need_spec) ensure_spec(e);
        if (l_blinn >= 0) ensure_spec_blinn(e);
        if (l_sh >= 0) ensure_sh(e);
        if (l_irr >= 0) ensure_convolved(e);
        if (need_lut) ensure_lut(e);
        if (need_base) ensure_base(e);
        if (need_dist) ensure_distribution(e);
        gpu_work_end(e, &st);
    }
    bind_source(e, prog);
    if (need_dist) {
        glBindTextureUnit(e->unit_dist, e->dist ? e->dist : e->dummy_2d);
        glBindTextureUnit(e->unit_marginal, e->marginal ? e->marginal : e->dummy_2d);
        glUniform1i(l_dist, e->unit_dist);
        glUniform1i(glGetUniformLocation(prog, "envmap_marginal"), e->unit_marginal);
        glUniform1i(glGetUniformLocation(prog, "envmap_has_dist"), e->dist_total > 0 && param(e, "reference_env_sampling").b);
        glUniform2i(glGetUniformLocation(prog, "envmap_dist_size"), e->dist_w, e->dist_h);
    }
    glBindTextureUnit(e->unit_spec, e->spec ? e->spec : e->dummy_cube);
    glBindTextureUnit(e->unit_irr, e->irr ? e->irr : e->dummy_cube);
    glBindTextureUnit(e->unit_lut, e->lut ? e->lut : e->dummy_2d);
    if (l_spec >= 0) glUniform1i(l_spec, e->unit_spec);
    if (l_blinn >= 0) {
        glBindTextureUnit(e->unit_spec_blinn, e->spec_blinn ? e->spec_blinn : e->dummy_cube);
        glUniform1i(l_blinn, e->unit_spec_blinn);
    }
    if (l_irr >= 0) glUniform1i(l_irr, e->unit_irr);
    if (l_lut >= 0) glUniform1i(l_lut, e->unit_lut);
    if (l_base >= 0) {
        glBindTextureUnit(e->unit_base, e->base ? e->base : e->dummy_cube);
        glUniform1i(l_base, e->unit_base);
        glUniform1f(glGetUniformLocation(prog, "envmap_base_size"), (float)(e->base ? e->base_size : 1));
    }
    if (l_sh >= 0) glUniform3fv(l_sh, 9, &e->sh[0][0]);
    if (l_lobes >= 0) {
        ensure_lobe_table(e);
        glBindTextureUnit(e->unit_lobes, e->lobe_table);
        glUniform1i(l_lobes, e->unit_lobes);
        /* the table's grid (lobe_fit.h): α of its first row, rows per unit α, columns per radian */
        glUniform3f(glGetUniformLocation(prog, "envmap_lobe_grid"), (float)EM_LOBE_ALPHA_MIN, (float)(1 / EM_LOBE_ALPHA_STEP),
                    (float)(180 / (EM_LOBE_THETA_STEP * M_PI)));
    }
    bind_sun_disk(e, prog, f);
    em_reflections_bind(&e->refl, prog);
    glUniform1f(glGetUniformLocation(prog, "envmap_spec_lod_max"), (float)(e->spec_levels > 0 ? e->spec_levels - 1 : 0));
    /* a precomputed chain (shadelab-cube --ggx) is always the sqrt mapping */
    glUniform1i(glGetUniformLocation(prog, "envmap_spec_map"), e->spec_from_chain ? 0 : param(e, "level_map").i);
    /* fis: the footprint of a sample is the share of every averaged frame's samples (ABI 1.9:
     * a TAA still's frames too) */
    int averaged = f ? f->accumulate_count : 1;
    if (f && f->struct_size >= offsetof(sl_frame, sample_count) + sizeof f->sample_count) {
        averaged = f->sample_count;
        /* a still's first frame is also what a frame in motion shows (sample 0): its own footprint */
        if (f->sample_index == 0 && f->accumulate_count <= 1) averaged = 1;
    }
    glUniform1f(glGetUniformLocation(prog, "envmap_accumulated"), (float)(averaged > 1 ? averaged : 1));
    /* specular=hybrid: no sample in sample 0 of an average (a frame in motion costs one lookup),
     * the others weigh count/(count - 1) (envmap_shading.glsl) */
    float fis_weight = 1;
    if (f && f->struct_size >= offsetof(sl_frame, sample_count) + sizeof f->sample_count && f->sample_count > 1)
        fis_weight = f->sample_index == 0 ? 0.0f : (float)f->sample_count / (float)(f->sample_count - 1);
    glUniform1f(glGetUniformLocation(prog, "envmap_fis_weight"), fis_weight);
}

/* ---------------------------------------------------------------- background pass */

static bool background_shown(envmap *e) { return e->have_src && !e->bg_is_clear && param(e, "background").b; }
static bool core_supersampled(envmap *e) { return e->host->get_param(e->host, "core.ssaa").i > 1; }

/* Without supersampling the background is drawn inside the opaque pass's targets, where depth is
 * still the cleared 1.0 (glDepthRange(1, 1) puts the triangle there, GL_EQUAL keeps only those
 * pixels, so covered ones are rejected before shading): no full-screen copy of "color". */
static bool background_active(void *user, const sl_frame *f) {
    (void)f;
    return background_shown(user) && !core_supersampled(user);
}
/* With core.ssaa > 1 "depth" is k× larger than "color": the full-screen pass that composites the
 * sky in proportion to each pixel's background samples (envmap_background.frag). */
static bool background_ssaa_active(void *user, const sl_frame *f) {
    (void)f;
    return background_shown(user) && core_supersampled(user);
}

/* The procedural sky's terms (em_sky_radiance) for envmap_background.frag's ENVMAP_SOURCE_SKY:
 * the disk is box-filtered over each pixel in closed form, sharp at any resolution (the lat-long's
 * texels blurred it over about two pixels). */
static void bind_sky(envmap *e, unsigned prog) {
    double dir[3], r, sun[3];
    em_sky_sun(&e->sky, dir, &r, sun);
    glUniform3f(glGetUniformLocation(prog, "envmap_sky_sun"), (float)dir[0], (float)dir[1], (float)dir[2]);
    glUniform1f(glGetUniformLocation(prog, "envmap_sky_sun_radius"), (float)r);
    glUniform3f(glGetUniformLocation(prog, "envmap_sky_sun_radiance"), (float)sun[0], (float)sun[1], (float)sun[2]);
    glUniform3fv(glGetUniformLocation(prog, "envmap_sky_ground"), 1, e->sky.ground);
}

static void background_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    envmap *e = user;
    const sl_host *h = e->host;
    bool in_place = !core_supersampled(e);
    unsigned color = in_place ? 0 : h->pass_texture(h, ctx, "color"), depth = in_place ? 0 : h->pass_texture(h, ctx, "depth");
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    int kind = e->is_sky ? 2 + (e->sky.sun_irradiance > 0) : e->kind == EM_ENV_CUBE;
    unsigned prog = h->program_id(h, in_place ? e->bg_in_place_prog[kind] : e->bg_prog[kind]);
    if (!prog) return;
    glUseProgram(prog);
    if (e->is_sky) bind_sky(e, prog);
    glUniform2f(glGetUniformLocation(prog, "envmap_jitter"), f->jitter[0], f->jitter[1]);
    /* the lighting units are free during this pass (bind() sets them again per material) */
    glBindTextureUnit(e->unit_spec, color);
    glBindTextureUnit(e->unit_lut, depth);
    glUniform1i(glGetUniformLocation(prog, "envmap_color"), e->unit_spec);
    glUniform1i(glGetUniformLocation(prog, "envmap_depth"), e->unit_lut);
    bind_source(e, prog);
    float inv[16];
    if (!sl_mat4_invert(f->view_proj, inv)) return;
    glUniformMatrix4fv(glGetUniformLocation(prog, "envmap_inv_view_proj"), 1, GL_FALSE, inv);
    glUniform2f(glGetUniformLocation(prog, "envmap_viewport"), (float)f->width, (float)f->height);
    glUniform1f(glGetUniformLocation(prog, "envmap_pixel_angle"), 2.0f / (f->proj[5] * (float)f->height));
    glUniform3fv(glGetUniformLocation(prog, "envmap_clear"), 1, e->clear);
    if (!in_place) {
        h->draw_fullscreen(h, ctx);
        return;
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glDepthRange(1.0, 1.0);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glBindVertexArray(e->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDepthRange(0.0, 1.0);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
}

/* ---------------------------------------------------------------- lifecycle */

static const char *const bg_inputs[] = {"color", "depth", NULL};
static const sl_target_desc bg_outputs[] = {{.name = "color", .format = SL_FORMAT_RGBA16F}};
/* in place: draws on "color" tested against "depth" (attached, not written), reads neither */
static const sl_target_desc bg_in_place_outputs[] = {{.name = "color", .format = SL_FORMAT_RGBA16F},
                                                     {.name = "depth", .format = SL_FORMAT_DEPTH32F}};

/* Light envmap.sun: a directional light as wide as the disk (the core's angular_radius: its
 * highlights and its shadow's softness). Hosts before ABI 1.22 have no add_light: the disk lights
 * as part of the sky (-1). */
static int add_sun_light(const sl_host *host) {
    if (host->struct_size < offsetof(sl_host, set_light) + sizeof host->set_light || !host->add_light) return -1;
    em_sky sky;
    em_sky_default(&sky);
    char radius[32];
    snprintf(radius, sizeof radius, "%g", sky.sun_radius_deg);
    const char *keys[] = {"angular_radius", radius, NULL};
    sl_plugin_light_desc d = {.struct_size = sizeof d, .name = "sun", .type = "directional", .cast_shadows = true,
                              .keys = keys};
    return host->add_light(host, &d);
}

static bool envmap_lit(void *user) { return ((envmap *)user)->have_src; }

static sl_status envmap_create(const sl_host *host, void **user) {
    if (host->struct_size < offsetof(sl_host, environment) + sizeof host->environment || !host->environment) {
        host->log(host, SL_LOG_ERROR, "this host has no environment query (needs the SDK ABI 1.1)");
        return SL_ERR_UNSUPPORTED;
    }
    envmap *e = calloc(1, sizeof *e);
    e->host = host;
    *user = e;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    e->sun_handle = add_sun_light(host);
    /* specular for the window's frame-time budget (ext/budget.h, docs/budget.md): dominant (one
     * lookup) while the view moves when the frame does not fit, the configured setting when it is
     * still. bench/budget.sh: the built-in scene's whole frame at 1280x720 relative to filtered's,
     * RMSE of one frame against the reference at 320x180 (bench/budget.csv) */
    static const char *const budget_speculars[] = {"dominant", "fitted", "filtered"};
    static const float budget_cost[] = {0.158f, 0.218f, 1}, budget_error[] = {0.0066f, 0.0045f, 0.0039f};
    const sl_ext_budget *budget = host->get_extension(host, SL_EXT_BUDGET);
    const sl_quality_model spec = {.struct_size = sizeof spec, .param = "specular", .count = 3,
                                   .values = budget_speculars, .cost = budget_cost, .error = budget_error,
                                   .measured_with = "envmap bench/budget.sh, bench/budget.csv (built-in scene)"};
    if (budget && budget->add_quality_model(host, &spec) != SL_OK) return SL_ERR_FAILED;
    /* reflections: the sky alone while the view moves when screen's two passes do not fit. The
     * default scene orbited at 1280x720 with reflections_scale 0.5 (README, "Reflections of the
     * scene"): frame p50 145 and 217 ms, motion frames' RMSE against its 4x4-supersampled still
     * with reflections */
    static const char *const budget_reflections[] = {"sky", "screen"};
    static const float refl_cost[] = {0.67f, 1}, refl_error[] = {0.0327f, 0.0192f};
    const sl_quality_model refl = {.struct_size = sizeof refl, .param = "reflections", .count = 2,
                                   .values = budget_reflections, .cost = refl_cost, .error = refl_error,
                                   .measured_with = "envmap README, Reflections of the scene (shadelab-bench --orbit)"};
    if (budget && budget->add_quality_model(host, &refl) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc bg = {.struct_size = sizeof bg, .name = "envmap-background", .stage = SL_STAGE_OPAQUE,
                             .outputs = bg_in_place_outputs, .output_count = 2, .execute = background_execute,
                             .is_active = background_active, .user = e,
                             .depends = SL_DEPENDS_INPUTS | SL_DEPENDS_CAMERA | SL_DEPENDS_OWN_PARAMS,
                             .display_on_write = true, .draws_only = true /* ABI 1.12: host->compile_ahead */};
    if (host->add_pass(host, &bg) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc bg_ssaa = {.struct_size = sizeof bg_ssaa, .name = "envmap-background-ssaa", .stage = SL_STAGE_OPAQUE,
                                  .inputs = bg_inputs, .outputs = bg_outputs, .output_count = 1,
                                  .execute = background_execute, .is_active = background_ssaa_active, .user = e,
                                  .depends = SL_DEPENDS_INPUTS | SL_DEPENDS_CAMERA | SL_DEPENDS_OWN_PARAMS,
                                  .display_on_write = true, .draws_only = true};
    if (host->add_pass(host, &bg_ssaa) != SL_OK) return SL_ERR_FAILED;
    /* no outputs: the chain is envmap's own texture; runs when its signature (the chain's key)
     * moves, or on any edit (a signature without depends) */
    const sl_pass_desc prefilter = {.struct_size = sizeof prefilter, .name = "envmap-prefilter",
                                    .stage = SL_STAGE_SHADOW + 50, .execute = prefilter_execute,
                                    .is_active = prefilter_active, .signature = prefilter_signature, .user = e};
    if (host->add_pass(host, &prefilter) != SL_OK) return SL_ERR_FAILED;
    if (em_reflections_create(&e->refl, host, envmap_lit, e) != SL_OK) return SL_ERR_FAILED;
    static const sl_reference_desc ref = {
        .struct_size = sizeof ref, .settings = "envmap.mode=reference envmap.reference_samples=64",
        .accumulate_frames = 64,
        .description = "Monte Carlo integration of the source environment at full resolution with the exact BRDF "
                       "(GGX visible-normal sampling for the specular lobe, cosine sampling for the diffuse, each "
                       "combined with environment importance sampling by MIS), 64 frames x 64 samples per pixel."};
    host->set_reference(host, &ref);
    host->set_bind_callback(host, envmap_bind, e);
    int units[10];
    for (int i = 0; i < 10; i++)
        if ((units[i] = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    e->unit_2d = units[0], e->unit_cube = units[1], e->unit_spec = units[2], e->unit_irr = units[3], e->unit_lut = units[4];
    e->unit_base = units[5], e->unit_dist = units[6], e->unit_marginal = units[7], e->unit_spec_blinn = units[8];
    e->unit_lobes = units[9];
    if (e->unit_cube != e->unit_2d + 1) return SL_ERR_FAILED;
    snprintf(e->glsl_dir, sizeof e->glsl_dir, "%s", host->resource_dir(host));
    return SL_OK;
}

static unsigned load_for_gpu(void *user, const char *fragment, const char *defines) {
    envmap *e = user;
    sl_program *p = e->host->load_program(
        e->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc), .vertex = "sl:fullscreen.vert",
                                    .fragment = fragment, .defines = defines});
    for (int i = 0; i < 6; i++)
        if (!e->progs[i]) { e->progs[i] = p; break; }
    return p ? LAZY_PROGRAM_ID : 0; /* compiled when a step first needs it (refresh_programs) */
}

static sl_status envmap_activate(void *user) {
    envmap *e = user;
    const char *missing = NULL;
    if (!sl_gl_load(e->host->gl_get_proc_address, &missing)) {
        e->host->log(e->host, SL_LOG_ERROR, "OpenGL entry point %s is missing", missing);
        return SL_ERR_GL;
    }
    e->gpu = (em_gpu){.load = load_for_gpu, .load_user = e, .progress = progress, .progress_user = e, .unit = e->unit_2d,
                      .identity_blend = !e->host->is_gpu(e->host)};
    char err[512];
    if (!em_gpu_init(&e->gpu, err, sizeof err)) {
        e->host->log(e->host, SL_LOG_ERROR, "%s", err);
        return SL_ERR_GL;
    }
    /* the background per source kind, drawn in place or (supersampled) as a pass of its own; each
     * compiled at its first program_id() (lazy): a scene compiles the one it draws */
    static const char *const bg_defines[2][4] = {
        {NULL, "ENVMAP_SOURCE_CUBE 1", "ENVMAP_SOURCE_SKY 1", "ENVMAP_SOURCE_SKY 1\nENVMAP_SKY_SUN 1"},
        {"ENVMAP_IN_PLACE 1", "ENVMAP_IN_PLACE 1\nENVMAP_SOURCE_CUBE 1", "ENVMAP_IN_PLACE 1\nENVMAP_SOURCE_SKY 1",
         "ENVMAP_IN_PLACE 1\nENVMAP_SOURCE_SKY 1\nENVMAP_SKY_SUN 1"}};
    for (int kind = 0; kind < 4; kind++) {
        sl_program **slot[2] = {&e->bg_prog[kind], &e->bg_in_place_prog[kind]};
        for (int in_place = 0; in_place < 2; in_place++) {
            *slot[in_place] = e->host->load_program(e->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                                 .vertex = "sl:fullscreen.vert",
                                                                                 .fragment = "envmap_background.frag",
                                                                                 .defines = bg_defines[in_place][kind]});
            if (!*slot[in_place]) return SL_ERR_GL;
        }
    }
    if (em_reflections_activate(&e->refl) != SL_OK) return SL_ERR_GL;
    glCreateVertexArrays(1, &e->empty_vao);
    e->glsl_hash = em_glsl_hash(e->glsl_dir, e->host->shader_dir(e->host));
    /* 1×1 stand-ins so every sampler always has a texture of its own type on its own unit */
    static const float black[4] = {0, 0, 0, 1};
    glCreateTextures(GL_TEXTURE_2D, 1, &e->dummy_2d);
    glTextureStorage2D(e->dummy_2d, 1, GL_RGBA16F, 1, 1);
    glTextureSubImage2D(e->dummy_2d, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, black);
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &e->dummy_cube);
    glTextureStorage2D(e->dummy_cube, 1, GL_RGBA16F, 1, 1);
    for (int f = 0; f < 6; f++) glTextureSubImage3D(e->dummy_cube, 0, 0, 0, f, 1, 1, 1, GL_RGBA, GL_FLOAT, black);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return SL_OK;
}

static void envmap_deactivate(void *user) {
    envmap *e = user;
    store_pending(e);
    store_pending_blinn(e);
    free_derived(e);
    em_reflections_free(&e->refl);
    delete_tex(&e->src_tex);
    delete_tex(&e->lut);
    delete_tex(&e->lobe_table);
    delete_tex(&e->dummy_2d);
    delete_tex(&e->dummy_cube);
    if (e->empty_vao) glDeleteVertexArrays(1, &e->empty_vao);
    e->empty_vao = 0;
    em_gpu_free(&e->gpu);
    free(e->src_key);
    e->src_key = NULL;
    e->have_src = false;
}

static void envmap_destroy(void *user) {
    envmap *e = user;
    if (e) free(e->src_key);
    free(e);
}

/* Extension "shadelab.environment/1" (sdk/include/shadelab/ext/environment.h): the base cube
 * (level 0 = the source resampled, solid-angle-weighted mips), its rotation and intensity, for
 * other plugins (extras/refraction). One envmap per process, so one static record. */
#include <shadelab/ext/environment.h>
static bool envmap_ext_environment_get(void *ctx, sl_environment_cube *out) {
    envmap *e = ctx;
    if (!e || !out || out->struct_size < sizeof *out || !e->have_src) return false;
    if (!e->base || (e->sun_is_light && !ext_base_current(e))) {
        gl_state st;
        gpu_work_begin(&st);
        ensure_base(e);
        if (e->sun_is_light && e->base) ensure_ext_base(e);
        gpu_work_end(e, &st);
    }
    if (!e->base) return false;
    out->texture = e->sun_is_light && e->ext_base ? e->ext_base : e->base;
    out->size = e->base_size;
    out->levels = em_max_levels(e->base_size);
    rotation(e, out->world_to_map);
    out->scale = e->scale;
    out->version = e->sun_is_light ? e->ext_base_key : e->base_key;
    return true;
}
static sl_ext_environment envmap_ext_environment = {.struct_size = sizeof(sl_ext_environment),
                                                   .get = envmap_ext_environment_get};
static const void *envmap_get_extension(void *user, const char *id) {
    if (!user || strcmp(id, SL_EXT_ENVIRONMENT)) return NULL;
    envmap_ext_environment.ctx = user;
    return &envmap_ext_environment;
}

static const char *const requires_[] = {"ggx", NULL};

static const char *const envmap_models[] = {"mirror", "environment", NULL};
static const sl_plugin_desc envmap_desc = {
    SL_PLUGIN_HEADER,
    .id = "envmap",
    .version = "1.0",
    .description = "Environment maps: background, mirror/environment materials, split-sum IBL for ggx "
                   "(prefiltered GGX cube, SH or convolved irradiance, BRDF LUT) and a Monte Carlo reference.",
    .dependencies = requires_,
    .create = envmap_create,
    .activate = envmap_activate,
    .begin_frame = envmap_begin_frame,
    .deactivate = envmap_deactivate,
    .destroy = envmap_destroy,
    .get_extension = envmap_get_extension,
    .default_for = SL_PLUGIN_DEFAULT_MODEL_FILE | SL_PLUGIN_DEFAULT_MODEL_ENVIRONMENT, /* a model's sky */
    .shading_models = envmap_models,
};

SL_DEFINE_PLUGIN(envmap_desc)
