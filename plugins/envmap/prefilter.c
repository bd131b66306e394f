/* envmap core, GPU side: cube conversion, the GGX specular prefilter, the irradiance
 * convolution and the BRDF LUT (see <envmap/prefilter.h>). Every pass draws one full-screen triangle
 * per face and level into a framebuffer of its own; callers in the middle of a frame save and
 * restore GL state around these calls (envmap.c does). */
#include "envmap/prefilter.h"
#include <shadelab/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int em_max_levels(int size) {
    int l = 1;
    while (size > 1) size >>= 1, l++;
    return l;
}

bool em_gpu_init(em_gpu *g, char *err, size_t n) {
    static const char *files[6] = {"envmap_to_cube.frag", "envmap_ggx.frag", "envmap_irradiance.frag", "envmap_lut.frag",
                                   "envmap_downsample.frag", "envmap_to_cube.frag"};
    static const char *defines[6] = {NULL, NULL, NULL, NULL, NULL, "ENVMAP_IN_CUBE 1"};
    unsigned *progs[6] = {&g->prog_to_cube,    &g->prog_ggx,          &g->prog_irradiance,
                          &g->prog_lut,        &g->prog_downsample,   &g->prog_cube_to_cube};
    for (int i = 0; i < 6; i++) {
        *progs[i] = g->load(g->load_user, files[i], defines[i]);
        if (!*progs[i]) {
            snprintf(err, n, "envmap: %s failed to compile (see the log)", files[i]);
            return false;
        }
    }
    glCreateVertexArrays(1, &g->vao);
    glCreateFramebuffers(1, &g->fbo);
    return true;
}

void em_gpu_free(em_gpu *g) {
    if (g->vao) glDeleteVertexArrays(1, &g->vao);
    if (g->fbo) glDeleteFramebuffers(1, &g->fbo);
    g->vao = g->fbo = 0;
}

static void set_filtering(unsigned t, bool mips) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, mips ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

unsigned em_new_cube(int size, int levels) {
    unsigned t;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &t);
    glTextureStorage2D(t, levels, GL_RGBA16F, size, size);
    set_filtering(t, levels > 1);
    glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, levels - 1);
    return t;
}

unsigned em_upload_latlong(const em_image *img) {
    unsigned t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    /* the box mips made on the CPU (em_latlong_mips), as the sky's: glGenerateMipmap compiles a
     * blit program at every start on llvmpipe (its variants are not in Mesa's disk cache), ≈ 0.1 s */
    em_image mips[16];
    int levels = 0;
    em_latlong_mips(img, mips, 16, &levels);
    glTextureStorage2D(t, levels, GL_RGBA16F, img->w, img->h);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (int l = 0; l < levels; l++) glTextureSubImage2D(t, l, 0, 0, mips[l].w, mips[l].h, GL_RGBA, GL_FLOAT, mips[l].px);
    for (int l = 1; l < levels; l++) free(mips[l].px);
    set_filtering(t, true);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT); /* u wraps around the sphere */
    return t;
}

unsigned em_upload_cube(float *const faces[6], int size, int levels) {
    unsigned t = em_new_cube(size, levels);
    /* each face's box mips made on the CPU (em_latlong_mips on the face as an image), as
     * em_upload_latlong's: no glGenerateMipmap blit program to compile at start-up */
    for (int f = 0; f < 6; f++) {
        em_image mips[16];
        int n = 0;
        em_latlong_mips(&(em_image){size, size, faces[f]}, mips, levels < 16 ? levels : 16, &n);
        for (int l = 0; l < n; l++) glTextureSubImage3D(t, l, 0, 0, f, mips[l].w, mips[l].h, 1, GL_RGBA, GL_FLOAT, mips[l].px);
        for (int l = 1; l < n; l++) free(mips[l].px);
    }
    return t;
}

unsigned em_upload_cube_levels(float *const *level_faces, int size, int levels) {
    unsigned t = em_new_cube(size, levels);
    for (int l = 0; l < levels; l++) {
        int s = size >> l;
        if (s < 1) s = 1;
        glTextureSubImage3D(t, l, 0, 0, 0, s, s, 6, GL_RGBA, GL_FLOAT, level_faces[l]);
    }
    return t;
}

/* Binds the pass input on g->unit (2D) or g->unit + 1 (cube): a program may declare both sampler
 * types (envmap_ggx.frag: its sample table and the cube), which must never share a unit. */
static void bind_input(em_gpu *g, unsigned prog, unsigned tex, bool is_cube) {
    glBindTextureUnit(g->unit, is_cube ? 0 : tex);
    glBindTextureUnit(g->unit + 1, is_cube ? tex : 0);
    int l2 = glGetUniformLocation(prog, "envmap_in2d"), lc = glGetUniformLocation(prog, "envmap_incube");
    if (l2 >= 0) glProgramUniform1i(prog, l2, g->unit);
    if (lc >= 0) glProgramUniform1i(prog, lc, g->unit + 1);
}

static void draw_into(em_gpu *g, unsigned tex, int level, int layer, int w, int h) {
    if (layer >= 0) glNamedFramebufferTextureLayer(g->fbo, GL_COLOR_ATTACHMENT0, tex, level, layer);
    else glNamedFramebufferTexture(g->fbo, GL_COLOR_ATTACHMENT0, tex, level);
    glNamedFramebufferDrawBuffer(g->fbo, GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    /* on llvmpipe an opaque draw (no depth, no blending) compiles its shader twice, once more for whole
     * tiles (Mesa's lp_state_fs.c); the identity blend writes the same bits and compiles it once:
     * ≈ 0.1 s of a cold start's prefilter programs */
    if (g->identity_blend) {
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ZERO);
    } else {
        glDisable(GL_BLEND);
    }
    glDisable(GL_SCISSOR_TEST);
    glBindVertexArray(g->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

static void report(em_gpu *g, double fraction, const char *what) {
    if (!g->progress) return;
    glFinish();
    g->progress(g->progress_user, fraction, what);
}

#define U1I(p, name, v) glProgramUniform1i(p, glGetUniformLocation(p, name), v)
#define U1F(p, name, v) glProgramUniform1f(p, glGetUniformLocation(p, name), v)

/* Levels 1.. from level 0, each from the one above (sampling restricted to it: no feedback). On
 * llvmpipe a program compiles once per state of the textures it samples, and a sampled range whose
 * last level is 0 is a state of its own: level 1 reads level 0 of t (base = max = 0), so every later
 * level reads a one-level texture too, the level above drawn a second time into it (the smaller
 * levels' texels, ≈ a third of level 1's: a second compile cost 0.08 s of a cold start). */
static void downsample_cube(em_gpu *g, unsigned t, int size, int levels) {
    unsigned p = g->prog_downsample;
    glUseProgram(p);
    glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, 0);
    glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, 0);
    unsigned src = t, copy = 0;
    for (int l = 1; l < levels; l++) {
        int s = size >> l;
        bind_input(g, p, src, true);
        U1F(p, "envmap_src_level", 0.0f);
        U1F(p, "envmap_size", (float)s);
        unsigned next = l + 1 < levels ? em_new_cube(s, 1) : 0;
        if (next) set_filtering(next, true); /* the sampler state t has (a one-level range of a mipped cube) */
        for (int f = 0; f < 6; f++) {
            U1I(p, "envmap_face", f);
            draw_into(g, t, l, f, s, s);
            if (next) draw_into(g, next, 0, f, s, s);
        }
        if (copy) glDeleteTextures(1, &copy);
        src = copy = next;
    }
    if (copy) glDeleteTextures(1, &copy);
    glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, 0);
    glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, levels - 1);
}

unsigned em_make_base_cube(em_gpu *g, unsigned src, bool src_is_cube, int src_w, int src_h, int size) {
    int levels = em_max_levels(size);
    unsigned t = em_new_cube(size, levels);
    unsigned p = src_is_cube ? g->prog_cube_to_cube : g->prog_to_cube;
    glUseProgram(p);
    bind_input(g, p, src, src_is_cube);
    glProgramUniform2f(p, glGetUniformLocation(p, "envmap_in_size"), (float)src_w, (float)src_h);
    U1F(p, "envmap_size", (float)size);
    /* same-size cube copies read texel centres exactly; everything else gets 4×4 sub-samples */
    U1I(p, "envmap_subsamples", src_is_cube && src_w == size ? 1 : 4);
    for (int f = 0; f < 6; f++) {
        U1I(p, "envmap_face", f);
        draw_into(g, t, 0, f, size, size);
    }
    downsample_cube(g, t, size, levels);
    return t;
}

/* The sample table of one level (envmap_ggx.frag): Hammersley points → half-vectors distributed
 * as D(h)(n·h) → l = reflect(−n, h), kept when n·l > 0, with the source mip level from the
 * sample's PDF, D(h)(n·h)/(4 v·h) = D/4 at v = n. D is GGX's of α, or (EM_LOBE_BLINN_PHONG) the
 * normalised Blinn-Phong (p+2)/(2π) cos^p θ of p = em_blinn_power(α), whose cos θ is
 * (1 − y)^(1/(p+2)). The same formulas as envmap_common.glsl's, in double. */
static int lobe_table(float *out, int samples, double alpha, em_lobe_shape shape, int base_size, float bias, int max_lod) {
    double a2 = alpha * alpha, omega_p = 4 * M_PI / (6.0 * base_size * base_size), p = em_blinn_power(alpha);
    int k = 0;
    for (int i = 0; i < samples; i++) {
        uint32_t b = (uint32_t)i;
        b = (b << 16) | (b >> 16);
        b = ((b & 0x55555555u) << 1) | ((b & 0xAAAAAAAAu) >> 1);
        b = ((b & 0x33333333u) << 2) | ((b & 0xCCCCCCCCu) >> 2);
        b = ((b & 0x0F0F0F0Fu) << 4) | ((b & 0xF0F0F0F0u) >> 4);
        b = ((b & 0x00FF00FFu) << 8) | ((b & 0xFF00FF00u) >> 8);
        double x = (i + 0.5) / samples, y = b * 2.3283064365386963e-10, c2, D;
        if (shape == EM_LOBE_BLINN_PHONG) {
            double c = pow(1 - y, 1 / (p + 2));
            c2 = c * c, D = (p + 2) / (2 * M_PI) * pow(c, p);
        } else {
            c2 = (1 - y) / (1 + (a2 - 1) * y);
            double d = c2 * (a2 - 1) + 1;
            D = a2 / (M_PI * d * d);
        }
        double c = sqrt(c2), s = sqrt(fmax(0, 1 - c2)), phi = 2 * M_PI * x;
        double h[3] = {s * cos(phi), s * sin(phi), c};
        double l[3] = {2 * c * h[0], 2 * c * h[1], 2 * c * h[2] - 1};
        if (l[2] <= 0) continue;
        double pdf = D * 0.25;
        double lod = 0.5 * log2(1.0 / (samples * pdf * omega_p)) + bias;
        lod = lod < 0 ? 0 : lod > max_lod ? max_lod : lod;
        out[k * 4 + 0] = (float)l[0], out[k * 4 + 1] = (float)l[1], out[k * 4 + 2] = (float)l[2], out[k * 4 + 3] = (float)lod;
        k++;
    }
    return k;
}

double em_blinn_power(double alpha) {
    double a2 = alpha * alpha;
    return a2 > 0 ? fmax(2 / log2(1 + a2) - 2, 0) : INFINITY;
}

double em_level_alpha(int level, int levels, em_level_map map) {
    if (level <= 0 || levels < 2) return 0;
    if (map == EM_LEVEL_MAP_LOG) return ldexp(1.0, level - (levels - 1));
    double r = (double)level / (levels - 1);
    return r * r;
}

double em_alpha_lod(double alpha, int levels, em_level_map map) {
    double top = levels - 1;
    if (map == EM_LEVEL_MAP_LOG) {
        double a1 = em_level_alpha(1, levels, map);
        return alpha >= a1 ? top + log2(alpha) : alpha / a1;
    }
    return sqrt(alpha) * top;
}

/* One cube drawn into level 0 of dst at out_size (the conversion pass: bilinear, seamless when the
 * caller enabled it; a box of such reads when shrinking). */
static void convert_cube_into(em_gpu *g, unsigned src, int src_size, unsigned dst, int out_size);

unsigned em_prefilter_ggx(em_gpu *g, unsigned base, int size, int levels, int samples, float lod_bias) {
    return em_prefilter_ggx_map(g, base, size, levels, samples, lod_bias, EM_LEVEL_MAP_SQRT);
}

unsigned em_prefilter_ggx_map(em_gpu *g, unsigned base, int size, int levels, int samples, float lod_bias,
                              em_level_map map) {
    return em_prefilter_chain(g, base, size, levels, samples, lod_bias, map, EM_LOBE_GGX);
}

unsigned em_prefilter_chain(em_gpu *g, unsigned base, int size, int levels, int samples, float lod_bias, em_level_map map,
                            em_lobe_shape shape) {
    int max_levels = em_max_levels(size);
    if (levels > max_levels) levels = max_levels;
    if (levels < 1) levels = 1;
    unsigned t = em_new_cube(size, levels);
    /* level 0 (roughness 0): the base cube itself */
    convert_cube_into(g, base, size, t, size);
    /* work per level ∝ texels × samples: progress in those units */
    double total = 0, done = 0;
    for (int l = 1; l < levels; l++) total += 6.0 * (size >> l) * (size >> l);
    unsigned p = g->prog_ggx;
    glUseProgram(p);
    bind_input(g, p, base, true);
    /* every level's table in one texture, uploaded before the first draw: a texture written between
     * draws that read it makes llvmpipe finish those draws first (the write waits for them), which
     * made the main thread wait for each level in turn instead of issuing the chain and going on */
    int rows = (samples + 1023) / 1024, n = levels > 1 ? levels - 1 : 1;
    float *table = calloc((size_t)rows * n * 1024 * 4, sizeof(float));
    int *counts = calloc((size_t)n, sizeof *counts);
    for (int l = 1; l < levels && table && counts; l++) {
        double a = em_level_alpha(l, levels, map);
        counts[l - 1] = lobe_table(table + (size_t)(l - 1) * rows * 1024 * 4, samples, a < 2e-3 ? 2e-3 : a, shape, size,
                                    lod_bias, max_levels - 1);
    }
    unsigned tex;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, 1024, rows * n);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (table) glTextureSubImage2D(tex, 0, 0, 0, 1024, rows * n, GL_RGBA, GL_FLOAT, table);
    glBindTextureUnit(g->unit, tex);
    char what[128];
    for (int l = 1; l < levels && table && counts; l++) {
        int s = size >> l;
        if (s < 1) s = 1;
        U1I(p, "envmap_count", counts[l - 1]);
        U1I(p, "envmap_row", (l - 1) * rows);
        U1F(p, "envmap_size", (float)s);
        for (int f = 0; f < 6; f++) {
            U1I(p, "envmap_face", f);
            glUseProgram(p);
            draw_into(g, t, l, f, s, s);
            done += (double)s * s;
            /* levels counted as the files of a chain are (1..N, level 1 the unfiltered copy above) */
            snprintf(what, sizeof what, "%s prefilter %d² cube, %d samples: level %d/%d face %d/6",
                     shape == EM_LOBE_BLINN_PHONG ? "Blinn-Phong" : "GGX", size, samples, l + 1, levels, f + 1);
            report(g, total > 0 ? done / total : 1, what);
        }
    }
    free(counts);
    glBindTextureUnit(g->unit, 0);
    glDeleteTextures(1, &tex);
    free(table);
    return t;
}

unsigned em_convolve_irradiance(em_gpu *g, unsigned base, int base_size, int src_size, int out_size) {
    if (src_size > base_size) src_size = base_size;
    int level = 0;
    while ((base_size >> level) > src_size) level++;
    src_size = base_size >> level;
    unsigned t = em_new_cube(out_size, 1);
    unsigned p = g->prog_irradiance;
    glUseProgram(p);
    bind_input(g, p, base, true);
    U1F(p, "envmap_src_level", (float)level);
    U1I(p, "envmap_src_size", src_size);
    U1F(p, "envmap_size", (float)out_size);
    for (int f = 0; f < 6; f++) {
        U1I(p, "envmap_face", f);
        draw_into(g, t, 0, f, out_size, out_size);
    }
    return t;
}

static void convert_cube_into(em_gpu *g, unsigned src, int src_size, unsigned dst, int out_size) {
    if (out_size == src_size) { /* the pass would read texel centres exactly: a copy, no program to run */
        glCopyImageSubData(src, GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, dst, GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, out_size, out_size, 6);
        return;
    }
    unsigned p = g->prog_cube_to_cube;
    glUseProgram(p);
    bind_input(g, p, src, true);
    glProgramUniform2f(p, glGetUniformLocation(p, "envmap_in_size"), (float)src_size, (float)src_size);
    U1F(p, "envmap_size", (float)out_size);
    U1I(p, "envmap_subsamples", out_size >= src_size ? 1 : 4);
    for (int f = 0; f < 6; f++) {
        U1I(p, "envmap_face", f);
        draw_into(g, dst, 0, f, out_size, out_size);
    }
}

/* One cube level resampled to another face size (convert_cube_into). */
static unsigned resample_cube(em_gpu *g, unsigned src, int src_size, int out_size) {
    unsigned t = em_new_cube(out_size, 1);
    convert_cube_into(g, src, src_size, t, out_size);
    return t;
}

unsigned em_irradiance_cube(em_gpu *g, unsigned base, int base_size, int src_size, int out_size,
                            em_irradiance_method method) {
    if (method == EM_IRRADIANCE_DIRECT || (method == EM_IRRADIANCE_CONVOLVED && out_size <= EM_IRRADIANCE_GRID))
        return em_convolve_irradiance(g, base, base_size, src_size, out_size);
    if (method == EM_IRRADIANCE_CONVOLVED) {
        unsigned grid = em_convolve_irradiance(g, base, base_size, src_size, EM_IRRADIANCE_GRID);
        unsigned t = resample_cube(g, grid, EM_IRRADIANCE_GRID, out_size);
        glDeleteTextures(1, &grid);
        return t;
    }
    /* SH: project level 0 (exact texel solid angles; O(base_size²)), evaluate per output texel */
    float *faces = em_read_cube(base, 0, base_size);
    double sh[9][3];
    em_sh9_project(faces, base_size, sh);
    free(faces);
    size_t n = (size_t)out_size * out_size;
    float *out = malloc(6 * n * 4 * sizeof(float));
    for (int f = 0; f < 6; f++)
        for (int y = 0; y < out_size; y++)
            for (int x = 0; x < out_size; x++) {
                double d[3], e[3];
                em_cube_dir(f, (x + 0.5) / out_size, (y + 0.5) / out_size, d);
                em_sh9_diffuse(sh, d, e);
                float *px = out + ((size_t)f * n + (size_t)y * out_size + x) * 4;
                for (int c = 0; c < 3; c++) px[c] = e[c] > 0 ? (e[c] < EM_HALF_MAX ? (float)e[c] : EM_HALF_MAX) : 0.0f;
                px[3] = 1;
            }
    float *fp[6];
    for (int f = 0; f < 6; f++) fp[f] = out + (size_t)f * n * 4;
    unsigned t = em_upload_cube(fp, out_size, 1);
    free(out);
    return t;
}

unsigned em_brdf_lut(em_gpu *g, int size, int samples) {
    unsigned t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, GL_RGBA16F, size, size);
    set_filtering(t, false);
    unsigned p = g->prog_lut;
    glUseProgram(p);
    U1F(p, "envmap_size", (float)size);
    U1I(p, "envmap_samples", samples);
    draw_into(g, t, 0, -1, size, size);
    return t;
}

float *em_read_cube(unsigned tex, int level, int size) {
    size_t bytes = (size_t)6 * size * size * 4 * sizeof(float);
    float *out = malloc(bytes);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(tex, level, GL_RGBA, GL_FLOAT, (int)bytes, out);
    return out;
}

float *em_read_2d(unsigned tex, int w, int h) {
    size_t bytes = (size_t)w * h * 4 * sizeof(float);
    float *out = malloc(bytes);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (int)bytes, out);
    return out;
}

uint64_t em_glsl_hash(const char *dir, const char *shader_dir) {
    static const char *files[] = {"envmap_common.glsl", "envmap_to_cube.frag", "envmap_ggx.frag", "envmap_irradiance.frag",
                                  "envmap_lut.frag", "envmap_downsample.frag", "sl:ggx_brdf.glsl"};
    uint64_t h = 0x5eed;
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        char path[4096];
        if (!strncmp(files[i], "sl:", 3)) snprintf(path, sizeof path, "%s/%s", shader_dir ? shader_dir : ".", files[i] + 3);
        else snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        FILE *f = fopen(path, "rb");
        if (!f) { h = em_hash(files[i], strlen(files[i]), h); continue; }
        char buf[8192];
        size_t got;
        while ((got = fread(buf, 1, sizeof buf, f)) > 0) h = em_hash(buf, got, h);
        fclose(f);
    }
    return h;
}
