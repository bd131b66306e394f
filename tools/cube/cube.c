/* shadelab-cube: prefilters environment maps for image-based lighting on the GPU (or llvmpipe)
 * with exactly the code the envmap plugin runs at load (its tool API, <envmap/prefilter.h>). */
#include "envmap/io.h"
#include "envmap/prefilter.h"
#include "toolkit.h"
#include <shadelab/gl.h>
#include <shadelab/input.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static const char *usage =
    "usage: shadelab-cube IN --ggx OUT [options]         prefiltered specular chain OUT.1 ... OUT.N\n"
    "       shadelab-cube IN --lambertian OUT [options]  diffuse (irradiance/pi) cube\n"
    "       shadelab-cube IN --convert OUT [options]     the environment itself as a cube\n"
    "       shadelab-cube --brdf-lut OUT [options]       environment-BRDF table (A, B) + a PNG picture\n"
    "\n"
    "IN: a lat-long (2:1) HDR/EXR/PNG, a cube cross (4:3, 3:4) or strip (6:1, 1:6), six face files\n"
    "(name_px.exr ... name_nz.exr: give any one), an RGBE8 PNG written by this tool, or a procedural\n"
    "environment: sky[:ELEVATION[:AZIMUTH[:SUN_E]]], constant:R,G,B, uv, checker:N:R,G,B:R,G,B. NaN, Inf and\n"
    "negative values are replaced (a warning gives the count); values above 65504 are clamped.\n"
    "OUT: .exr (half float) or .png (RGBE8, tagged \"" EM_RGBE_TAG "\"), six faces as a horizontal\n"
    "cross (4:3: +Y over +Z; -X +Z +X -Z; -Y under +Z), OpenGL face orientation. The envmap plugin\n"
    "loads any of these as a scene's environment map; given OUT.1 of a --ggx chain it uses the\n"
    "precomputed levels instead of prefiltering. --ggx level k (1..N) is for perceptual roughness\n"
    "(k-1)/(N-1), GGX alpha = roughness^2; level 1 is the unfiltered environment.\n"
    "\n"
    "options:\n"
    "  --size N          face size (default 256; --lambertian 32; --brdf-lut: table size, 64)\n"
    "  --samples N       GGX samples per texel (default 1024; --brdf-lut too)\n"
    "  --levels N        roughness levels of --ggx (default 6, at most log2(size)+1)\n"
    "  --lod-bias B      bias of the PDF-chosen source mip level (default 1)\n"
    "  --irradiance M    --lambertian method: convolved (default: the exact cosine sum on a 32^2\n"
    "                    grid, resampled), sh (9 spherical-harmonic coefficients) or direct\n"
    "                    (the exact sum at every output texel: the slow reference)\n"
    "  --backend B       headless (default: EGL on a GPU, else OSMesa), osmesa or egl\n"
    "  -q, --quiet       no progress bar\n"
    "  -h, --help        this text\n"
    "The --brdf-lut .exr holds A in red, B in green, the diffuse Fresnel weight C(n.v) in blue;\n"
    "texel (i, j) is n.v = i/(N-1) and roughness "
    "j/(N-1), row 0 (top) is roughness 0. The picture beside it (OUT with .png) shows the same.\n";

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static bool quiet;
static double t_start;

static void bar(void *user, double f, const char *what) {
    if (quiet) return;
    int n = (int)(f * 30 + 0.5);
    fprintf(stderr, "\r[%.*s%.*s] %3.0f%% %5.1f s  %-70.70s", n, "##############################", 30 - n,
            "..............................", f * 100, now_s() - t_start, what);
    fflush(stderr);
}

static const char *glsl_dir(void) {
    static char dir[4096];
    const char *env = getenv("SHADELAB_ENVMAP_DIR");
    struct stat st;
    if (env && *env) snprintf(dir, sizeof dir, "%s", env);
    else if (stat(ENVMAP_GLSL_DIR "/envmap_ggx.frag", &st) == 0) snprintf(dir, sizeof dir, "%s", ENVMAP_GLSL_DIR);
    else {
        char exe[4096];
        ssize_t l = readlink("/proc/self/exe", exe, sizeof exe - 1);
        exe[l > 0 ? l : 0] = 0;
        snprintf(dir, sizeof dir, "%s/../%s/shadelab/plugins/envmap", dirname(exe), SL_INSTALL_LIBDIR);
    }
    return dir;
}

static sl_program *programs[8];
static int program_count;

static unsigned load_program(void *user, const char *fragment, const char *defines) {
    char err[16384] = "";
    sl_program *p = sl_tool_program_from_files(glsl_dir(), "sl:fullscreen.vert", fragment, defines, err, sizeof err);
    unsigned id = sl_tool_program_id(p);
    if (!id) fprintf(stderr, "shadelab-cube: %s\n", err);
    if (program_count < 8) programs[program_count++] = p;
    return id;
}

/* The core's procedural textures (the toolkit's sl_image_procedural): the parser scenes use. */
static float *core_pattern(void *user, const char *spec, int size, char *err, size_t n) {
    (void)user;
    sl_image img;
    return sl_image_procedural(&img, spec, size, err, n) ? img.pixels : NULL;
}

/* A whole number option within [lo, hi] (the SDK's strict reader): false after saying why. */
static bool int_arg(const char *opt, const char *v, long lo, long hi, int *out) {
    long x;
    if (!sl_parse_long(v, lo, hi, &x)) {
        fprintf(stderr, "shadelab-cube: %s %s: expected a whole number %ld..%ld\n", opt, v, lo, hi);
        return false;
    }
    *out = (int)x;
    return true;
}

static int fail(const char *fmt, const char *a) {
    fprintf(stderr, "shadelab-cube: ");
    fprintf(stderr, fmt, a);
    fputc('\n', stderr);
    return 1;
}

int main(int argc, char **argv) {
    const char *in = NULL, *out = NULL, *mode = NULL, *backend = "headless";
    int size = -1, samples = 1024, levels = 6;
    float bias = 1;
    em_irradiance_method irr_method = EM_IRRADIANCE_CONVOLVED;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool has = i + 1 < argc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) { fputs(usage, stdout); return 0; }
        else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) quiet = true;
        else if ((!strcmp(a, "--ggx") || !strcmp(a, "--lambertian") || !strcmp(a, "--convert") || !strcmp(a, "--brdf-lut")) && has) {
            if (mode) return fail("%s: only one of --ggx, --lambertian, --convert, --brdf-lut", a);
            mode = a + 2, out = argv[++i];
        } else if (!strcmp(a, "--size") && has) {
            if (!int_arg(a, argv[++i], 1, 8192, &size)) return 2;
        } else if (!strcmp(a, "--samples") && has) {
            if (!int_arg(a, argv[++i], 1, 1 << 20, &samples)) return 2;
        } else if (!strcmp(a, "--levels") && has) {
            if (!int_arg(a, argv[++i], 1, 16, &levels)) return 2;
        } else if (!strcmp(a, "--lod-bias") && has) {
            double b;
            if (!sl_parse_double(argv[++i], -2, 4, &b)) { /* the envmap.lod_bias parameter's range */
                fprintf(stderr, "shadelab-cube: --lod-bias %s: expected a finite number -2..4\n", argv[i]);
                return 2;
            }
            bias = (float)b;
        } else if (!strcmp(a, "--irradiance") && has) {
            const char *m = argv[++i];
            if (!strcmp(m, "convolved")) irr_method = EM_IRRADIANCE_CONVOLVED;
            else if (!strcmp(m, "sh")) irr_method = EM_IRRADIANCE_SH;
            else if (!strcmp(m, "direct")) irr_method = EM_IRRADIANCE_DIRECT;
            else {
                fprintf(stderr, "shadelab-cube: --irradiance %s: expected convolved, sh or direct\n", m);
                return 2;
            }
        } else if (!strcmp(a, "--backend") && has) backend = argv[++i];
        else if (a[0] == '-') { fprintf(stderr, "shadelab-cube: unknown option or missing value: %s\n\n%s", a, usage); return 2; }
        else if (!in) in = a;
        else { fprintf(stderr, "shadelab-cube: more than one input (%s)\n\n%s", a, usage); return 2; }
    }
    bool lut = mode && !strcmp(mode, "brdf-lut");
    if (!mode || (!lut && !in) || (lut && in)) { fprintf(stderr, "%s", usage); return 2; }
    if (size < 0) size = lut ? 64 : !strcmp(mode, "lambertian") ? 32 : 256;
    if (size < (lut ? 2 : 1)) {
        fprintf(stderr, "shadelab-cube: --size %d: the --brdf-lut table needs a whole number 2..8192\n", size);
        return 2;
    }
    const char *ext = strrchr(out, '.');
    if (!ext || (strcasecmp(ext, ".exr") && strcasecmp(ext, ".png"))) return fail("%s: OUT must end in .exr or .png", out);

    sl_backend_kind kind;
    if (!sl_backend_parse(backend, &kind)) return fail("--backend %s: expected headless, osmesa or egl", backend);
    char err[16384] = "";
    em_env env = {0};
    if (in && em_is_procedural(in)) {
        bool constant;
        env.kind = EM_ENV_LATLONG;
        if (!em_procedural(in, core_pattern, NULL, &env.latlong, &constant, err, sizeof err)) return fail("%s", err);
        snprintf(env.how, sizeof env.how, "procedural %dx%d lat-long", env.latlong.w, env.latlong.h);
    } else if (in && !em_env_load(in, &em_io_reader, &env, err, sizeof err)) {
        return fail("%s", err);
    }
    if (in) {
        long bad = env.stats.nan + env.stats.inf + env.stats.negative;
        if (bad)
            fprintf(stderr, "shadelab-cube: warning: %s: replaced %ld invalid values (%ld NaN, %ld infinite, %ld negative)\n",
                    in, bad, env.stats.nan, env.stats.inf, env.stats.negative);
        if (!quiet) fprintf(stderr, "%s: %s\n", in, env.how);
    }
    sl_backend b = {0};
    if (!sl_backend_create(&b, kind, 16, 16, "shadelab-cube", err, sizeof err)) return fail("%s", err);
    const char *missing = NULL;
    if (!sl_gl_load(b.get_proc_address, &missing)) return fail("OpenGL entry point %s is missing", missing);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    em_gpu g = {.load = load_program, .progress = bar, .unit = 0};
    if (!em_gpu_init(&g, err, sizeof err)) return fail("%s", err);
    if (!quiet) fprintf(stderr, "%s (%s)\n", glGetString(GL_RENDERER), b.name);

    t_start = now_s();
    int rc = 0;
    if (lut) {
        unsigned t = em_brdf_lut(&g, size, samples);
        float *px = em_read_2d(t, size, size);
        glFinish();
        double secs = now_s() - t_start;
        unsigned char *pic = malloc((size_t)size * size * 4);
        for (int i = 0; i < size * size; i++) {
            px[i * 4 + 3] = 1;
            for (int c = 0; c < 4; c++) {
                float v = c == 3 ? 1 : px[i * 4 + c];
                pic[i * 4 + c] = (unsigned char)lrintf(255 * (v < 0 ? 0 : v > 1 ? 1 : v));
            }
        }
        char png[4096];
        snprintf(png, sizeof png, "%.*s.png", (int)(ext - out), out);
        bool ok = (strcasecmp(ext, ".exr") ? true : em_io_write_exr(out, px, size, size, "shadelab envmap BRDF LUT: R = A, G = B, B = diffuse weight C(n.v)", err, sizeof err)) &&
                  em_io_write_png8(png, pic, size, size, "shadelab envmap BRDF LUT picture", err, sizeof err);
        if (!ok) rc = fail("%s", err);
        else fprintf(stderr, "wrote %s%s%s (%d², %d samples) in %.2f s\n", strcasecmp(ext, ".exr") ? "" : out,
                     strcasecmp(ext, ".exr") ? "" : " and ", png, size, samples, secs);
        free(px);
        free(pic);
    } else {
        unsigned src = env.kind == EM_ENV_LATLONG ? em_upload_latlong(&env.latlong)
                                                  : em_upload_cube(env.faces, env.size, em_max_levels(env.size));
        int sw = env.kind == EM_ENV_LATLONG ? env.latlong.w : env.size, sh = env.kind == EM_ENV_LATLONG ? env.latlong.h : env.size;
        bool lambert = !strcmp(mode, "lambertian");
        int base_size = lambert ? (size > 64 ? size : 64) : size;
        unsigned base = em_make_base_cube(&g, src, env.kind == EM_ENV_CUBE, sw, sh, base_size);
        if (!strcmp(mode, "convert")) {
            float *f = em_read_cube(base, 0, size);
            float *faces[6];
            for (int k = 0; k < 6; k++) faces[k] = f + (size_t)k * size * size * 4;
            if (!em_write_cube(out, faces, size, err, sizeof err)) rc = fail("%s", err);
            else fprintf(stderr, "wrote %s (%d² faces) in %.2f s\n", out, size, now_s() - t_start);
            free(f);
        } else if (lambert) {
            static const char *how[] = {"direct cosine sum over a 32² mip at every texel",
                                        "cosine sum over a 32² mip on a 32² grid, resampled", "9 SH coefficients"};
            unsigned irr = em_irradiance_cube(&g, base, base_size, 32, size, irr_method);
            float *f = em_read_cube(irr, 0, size);
            float *faces[6];
            for (int k = 0; k < 6; k++) faces[k] = f + (size_t)k * size * size * 4;
            if (!em_write_cube(out, faces, size, err, sizeof err)) rc = fail("%s", err);
            else fprintf(stderr, "wrote %s (%d² faces, %s) in %.2f s\n", out, size, how[irr_method], now_s() - t_start);
            free(f);
        } else {
            if (levels > em_max_levels(size)) levels = em_max_levels(size);
            unsigned chain = em_prefilter_ggx(&g, base, size, levels, samples, bias);
            glFinish();
            double secs = now_s() - t_start;
            if (!quiet) fputc('\n', stderr);
            for (int l = 0; l < levels && !rc; l++) {
                int s = size >> l > 0 ? size >> l : 1;
                float *f = em_read_cube(chain, l, s);
                float *faces[6];
                for (int k = 0; k < 6; k++) faces[k] = f + (size_t)k * s * s * 4;
                char name[4096];
                em_chain_name(out, l + 1, name, sizeof name);
                if (!em_write_cube(name, faces, s, err, sizeof err)) rc = fail("%s", err);
                free(f);
            }
            if (!rc) {
                char first[4096], last[4096];
                em_chain_name(out, 1, first, sizeof first);
                em_chain_name(out, levels, last, sizeof last);
                fprintf(stderr, "prefiltered %d² x %d levels with %d samples in %.2f s (%s); wrote %s ... %s\n", size,
                        levels, samples, secs, b.name, first, last);
            }
        }
    }
    for (int i = 0; i < program_count; i++) sl_tool_program_free(programs[i]);
    em_gpu_free(&g);
    em_env_free(&env);
    sl_backend_destroy(&b);
    return rc;
}
