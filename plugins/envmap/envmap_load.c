/* Environment files: format and layout detection, RGBE8 and sRGB decoding, precomputed chains,
 * sanitising. Shared by the plugin and shadelab-cube (include/envmap/io.h). */
#include "envmap/io.h"
#include <shadelab/input.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

void em_env_free(em_env *e) {
    if (!e) return;
    em_image_free(&e->latlong);
    for (int f = 0; f < 6; f++) free(e->faces[f]);
    for (int l = 0; l < e->chain_levels; l++) free(e->chain[l]);
    free(e->chain);
    memset(e, 0, sizeof *e);
}

/* a readable regular file (the SDK's check; never opens it) */
static bool exists(const char *p) {
    char why[160];
    return !sl_input_file_problem(p, why, sizeof why);
}

static float srgb_decode(float x) {
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return x <= 0.04045f ? x / 12.92f : powf((x + 0.055f) / 1.055f, 2.4f);
}

static void add_stats(em_sanitize_stats *a, const em_sanitize_stats *b) {
    a->nan += b->nan;
    a->inf += b->inf;
    a->negative += b->negative;
    a->clamped += b->clamped;
    if (b->max_value > a->max_value) a->max_value = b->max_value;
}

void em_chain_name(const char *path, int level, char *out, size_t n) {
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(path, '.');
    if (!dot || (slash && dot < slash)) snprintf(out, n, "%s.%d", path, level);
    else snprintf(out, n, "%.*s.%d%s", (int)(dot - path), path, level, dot);
}

/* One image file, decoded to linear float RGBA (RGBE8 and 8/16-bit sRGB handled). */
static bool load_linear(const em_reader *rd, const char *path, em_image *img, char *how, size_t hn, char *err, size_t n) {
    em_io_info info;
    if (!rd->read(rd->ctx, path, img, &info, err, n)) return false;
    size_t len = strlen(path);
    bool rgbe = !strcmp(info.description, EM_RGBE_TAG) || (len > 9 && !strcasecmp(path + len - 9, ".rgbe.png"));
    size_t count = (size_t)img->w * img->h;
    if (rgbe) {
        if (info.bits != 8 || info.channels != 4) {
            snprintf(err, n, "%s: marked RGBE8 but has %d channels of %d bits (expected 4 × 8)", path, info.channels,
                     info.bits);
            em_image_free(img);
            return false;
        }
        for (size_t i = 0; i < count; i++) {
            unsigned char b[4];
            for (int c = 0; c < 4; c++) b[c] = (unsigned char)lrintf(img->px[i * 4 + c] * 255.0f);
            em_rgbe_decode(b, img->px + i * 4);
            img->px[i * 4 + 3] = 1;
        }
        snprintf(how, hn, "RGBE8 %s", info.format);
    } else if (info.srgb) {
        for (size_t i = 0; i < count * 4; i++)
            if (i % 4 != 3) img->px[i] = srgb_decode(img->px[i]);
        snprintf(how, hn, "%d-bit sRGB %s (decoded to linear)", info.bits, info.format);
    } else {
        snprintf(how, hn, "%s %s", info.is_float ? (info.bits == 16 ? "half" : "float") : "linear integer", info.format);
    }
    return true;
}

/* Faces of a cube-layout image (or the image itself as a lat-long). */
static bool image_to_env(const char *path, em_image *img, em_env *e, char *err, size_t n) {
    em_layout l = em_detect_layout(img->w, img->h);
    if (l == EM_LAYOUT_UNKNOWN) {
        snprintf(err, n, "%s: %dx%d is neither a 2:1 lat-long nor a cube layout (4:3 or 3:4 cross, 6:1 or 1:6 strip)", path,
                 img->w, img->h);
        em_image_free(img);
        return false;
    }
    if (l == EM_LAYOUT_LATLONG) {
        e->kind = EM_ENV_LATLONG;
        e->latlong = *img;
        memset(img, 0, sizeof *img);
        return true;
    }
    e->kind = EM_ENV_CUBE;
    em_extract_faces(img, l, e->faces, &e->size);
    em_image_free(img);
    return true;
}

/* "_px" style face token in the file name: its offset, or -1. */
static int face_token(const char *path, const char **tokens) {
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    for (const char *p = base; *p; p++) {
        if (p != base && p[-1] != '_' && p[-1] != '-' && p[-1] != '.') continue;
        size_t t = strlen(tokens[0]);
        if (!strncasecmp(p, tokens[0], t) && !isalnum((unsigned char)p[t])) return (int)(p - path);
    }
    return -1;
}

/* 0: not a face name; 1: loaded; -1: error (in err). */
static int load_six(const em_reader *rd, const char *path, em_env *e, char *err, size_t n) {
    static const char *sets[2][6] = {{"px", "nx", "py", "ny", "pz", "nz"}, {"posx", "negx", "posy", "negy", "posz", "negz"}};
    for (int s = 0; s < 2; s++)
        for (int f = 0; f < 6; f++) {
            int at = face_token(path, &sets[s][f]);
            if (at < 0) continue;
            e->kind = EM_ENV_CUBE;
            char how[256] = "";
            for (int g = 0; g < 6; g++) {
                char p[4096];
                size_t tl = strlen(sets[s][f]);
                snprintf(p, sizeof p, "%.*s%s%s", at, path, sets[s][g], path + at + tl);
                em_image img;
                if (!load_linear(rd, p, &img, how, sizeof how, err, n)) return -1;
                if (img.w != img.h || (g && img.w != e->size)) {
                    snprintf(err, n, "%s: face is %dx%d; the six faces must be equal squares", p, img.w, img.h);
                    em_image_free(&img);
                    return -1;
                }
                e->size = img.w;
                e->faces[g] = img.px;
            }
            snprintf(e->how, sizeof e->how, "six %s faces %d²", how, e->size);
            return 1;
        }
    return 0;
}

static bool is_chain_head(const char *path) {
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(path, '.');
    if (!dot || (slash && dot < slash) || dot - path < 2) return false;
    return dot[-1] == '1' && dot[-2] == '.';
}

static bool load_chain(const em_reader *rd, const char *path, em_env *e, char *err, size_t n) {
    char stem_ext[4096];
    const char *dot = strrchr(path, '.');
    snprintf(stem_ext, sizeof stem_ext, "%.*s%s", (int)(dot - path - 2), path, dot); /* X.1.exr → X.exr */
    int levels = 0;
    char p[4096];
    for (;; levels++) {
        em_chain_name(stem_ext, levels + 1, p, sizeof p);
        if (!exists(p) || levels == 16) break;
    }
    e->chain = calloc(levels, sizeof *e->chain);
    char how[256] = "";
    for (int l = 0; l < levels; l++) {
        em_chain_name(stem_ext, l + 1, p, sizeof p);
        em_image img;
        if (!load_linear(rd, p, &img, how, sizeof how, err, n)) return false;
        em_env lev = {0};
        if (!image_to_env(p, &img, &lev, err, n)) return false;
        if (lev.kind != EM_ENV_CUBE) {
            snprintf(err, n, "%s: a prefiltered chain level must be a cube layout", p);
            em_env_free(&lev);
            return false;
        }
        int want = l == 0 ? lev.size : (e->size >> l) > 0 ? (e->size >> l) : 1;
        if (lev.size != want) {
            snprintf(err, n, "%s: level %d has faces of %d², expected %d² (each level half the one before)", p, l + 1,
                     lev.size, want);
            em_env_free(&lev);
            return false;
        }
        if (l == 0) e->size = lev.size;
        size_t face = (size_t)lev.size * lev.size * 4;
        e->chain[l] = malloc(face * 6 * sizeof(float));
        for (int f = 0; f < 6; f++) {
            memcpy(e->chain[l] + face * f, lev.faces[f], face * sizeof(float));
            if (l == 0) e->faces[f] = lev.faces[f], lev.faces[f] = NULL;
        }
        e->chain_levels = l + 1;
        em_env_free(&lev);
    }
    e->kind = EM_ENV_CUBE;
    snprintf(e->how, sizeof e->how, "precomputed GGX chain of %d levels, %s, %d² (%s)", levels, how, e->size,
             em_layout_name(EM_LAYOUT_HCROSS));
    return levels > 0;
}

bool em_env_load(const char *path, const em_reader *rd, em_env *e, char *err, size_t n) {
    memset(e, 0, sizeof *e);
    if (n) err[0] = 0;
    bool ok;
    int six = 0;
    if (is_chain_head(path) && exists(path)) {
        ok = load_chain(rd, path, e, err, n);
    } else if ((six = load_six(rd, path, e, err, n)) != 0) {
        ok = six > 0;
    } else {
        em_image img;
        char how[256] = "";
        ok = load_linear(rd, path, &img, how, sizeof how, err, n);
        em_layout l = ok ? em_detect_layout(img.w, img.h) : EM_LAYOUT_UNKNOWN;
        int w = ok ? img.w : 0, h = ok ? img.h : 0;
        ok = ok && image_to_env(path, &img, e, err, n);
        if (ok) snprintf(e->how, sizeof e->how, "%s, %s %dx%d", how, em_layout_name(l), w, h);
    }
    if (!ok) {
        em_env_free(e);
        return false;
    }
    em_sanitize_stats s;
    if (e->kind == EM_ENV_LATLONG) {
        em_sanitize(e->latlong.px, (size_t)e->latlong.w * e->latlong.h, &s);
        add_stats(&e->stats, &s);
    } else {
        for (int f = 0; f < 6; f++) {
            em_sanitize(e->faces[f], (size_t)e->size * e->size, &s);
            add_stats(&e->stats, &s);
        }
        for (int l = 0; l < e->chain_levels; l++) {
            int sz = e->size >> l > 0 ? e->size >> l : 1;
            em_sanitize(e->chain[l], (size_t)6 * sz * sz, &s); /* counted once, through level 1 */
        }
    }
    return true;
}

/* ---------------------------------------------------------------- procedural environments */

bool em_is_procedural(const char *s) {
    return !strncmp(s, "constant:", 9) || !strcmp(s, "uv") || !strcmp(s, "gradient") || !strncmp(s, "checker:", 8) ||
           !strncmp(s, "grid:", 5) || !strcmp(s, "sky") || !strncmp(s, "sky:", 4);
}

/* One field of "sky:E:A:I": a finite number within [lo, hi], or the message naming it. */
static bool sky_field(const char *spec, const char *text, size_t len, const char *what, double lo, double hi, float *out,
                      char *err, size_t n) {
    char buf[64];
    double v;
    snprintf(buf, sizeof buf, "%.*s", (int)(len < sizeof buf - 1 ? len : sizeof buf - 1), text);
    if (len >= sizeof buf || !sl_parse_double(buf, lo, hi, &v)) {
        snprintf(err, n, "procedural environment '%s': %s '%.*s' must be a finite number in %g..%g: expected "
                         "sky[:ELEVATION[:AZIMUTH[:SUN_IRRADIANCE]]]", spec, what, (int)(len > 40 ? 40 : len), text, lo, hi);
        return false;
    }
    *out = (float)v;
    return true;
}

bool em_procedural(const char *spec, em_pattern_fn pattern, void *user, em_image *img, bool *constant, char *err,
                   size_t n) {
    memset(img, 0, sizeof *img);
    *constant = false;
    if (!strcmp(spec, "sky") || !strncmp(spec, "sky:", 4)) {
        em_sky sky;
        em_sky_default(&sky);
        static const char *what[3] = {"ELEVATION (degrees)", "AZIMUTH (degrees)", "SUN_IRRADIANCE (W/m²)"};
        const double lo[3] = {-EM_SKY_ELEVATION_MAX, -EM_SKY_AZIMUTH_MAX, 0};
        const double hi[3] = {EM_SKY_ELEVATION_MAX, EM_SKY_AZIMUTH_MAX, EM_SKY_IRRADIANCE_MAX};
        float *field[3] = {&sky.sun_elevation_deg, &sky.sun_azimuth_deg, &sky.sun_irradiance};
        const char *p = spec[3] == ':' ? spec + 4 : NULL;
        for (int k = 0; p; k++) {
            const char *colon = strchr(p, ':');
            size_t len = colon ? (size_t)(colon - p) : strlen(p);
            if (k == 3) {
                snprintf(err, n, "procedural environment '%s': too many fields: expected "
                                 "sky[:ELEVATION[:AZIMUTH[:SUN_IRRADIANCE]]]", spec);
                return false;
            }
            if (!sky_field(spec, p, len, what[k], lo[k], hi[k], field[k], err, n)) return false;
            p = colon ? colon + 1 : NULL;
        }
        em_sky_latlong(&sky, 1024, 512, img);
        return true;
    }
    if (!pattern) {
        snprintf(err, n, "procedural environment '%s': no procedural texture reader given", spec);
        return false;
    }
    /* the core's square pattern at the lat-long's width, rows averaged in pairs to the 2:1 height:
     * exact for the linear ramps (uv, gradient), a box filter across checker and grid edges */
    bool is_constant = !strncmp(spec, "constant:", 9);
    int w = is_constant ? 8 : 512, h = w / 2;
    float *sq = pattern(user, spec, w, err, n);
    if (!sq) return false;
    img->px = malloc((size_t)w * h * 4 * sizeof(float));
    if (!img->px) {
        free(sq);
        snprintf(err, n, "procedural environment '%s': out of memory", spec);
        return false;
    }
    img->w = w, img->h = h;
    for (int y = 0; y < h; y++)
        for (int i = 0; i < w * 4; i++)
            img->px[(size_t)y * w * 4 + i] = 0.5f * (sq[(size_t)(2 * y) * w * 4 + i] + sq[(size_t)(2 * y + 1) * w * 4 + i]);
    free(sq);
    *constant = is_constant;
    return true;
}
