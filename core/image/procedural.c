/* Procedural textures: the texture specs a scene may use instead of a file (scenes/README.md,
 * "Procedural textures"). Colour patterns (checker, grid, gradient, uv, constant) and
 * tangent-space normal maps from analytic height fields (flat, tilt, bumps, waves), generated
 * at load time with no file. One parser for every reader: the renderer's material textures, the
 * tools (through the toolkit) and the tests. */
#include "image/image.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void set_err(char *err, size_t err_size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void set_err(char *err, size_t err_size, const char *fmt, ...) {
    if (!err || !err_size) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
}

/* Strict integer: digits only (optional surrounding spaces), within [lo, hi]. */
static bool parse_int(const char *s, size_t len, long lo, long hi, long *out) {
    char buf[32];
    if (len == 0 || len >= sizeof buf) return false;
    memcpy(buf, s, len);
    buf[len] = 0;
    char *end;
    errno = 0;
    long v = strtol(buf, &end, 10);
    while (*end == ' ') end++;
    if (end == buf || *end || errno || v < lo || v > hi) return false;
    *out = v;
    return true;
}

/* Strict float: a whole field, finite, within [lo, hi]. */
static bool parse_float(const char *s, size_t len, double lo, double hi, double *out) {
    char buf[64];
    if (len == 0 || len >= sizeof buf) return false;
    memcpy(buf, s, len);
    buf[len] = 0;
    char *end;
    errno = 0;
    double v = strtod(buf, &end);
    while (*end == ' ') end++;
    if (end == buf || *end || errno || !isfinite(v) || v < lo || v > hi) return false;
    *out = v;
    return true;
}

/* ---- tangent-space normal maps from height fields ------------------------------------------
 * Image coordinates X = u (right) and Y = image up = 1 − v, both 0..1 over the texture (row 0 is
 * the top, as every sl_image). The map stores n·0.5 + 0.5 with n = (−∂h/∂X, −∂h/∂Y, 1)/|…|:
 * the +Y ("OpenGL", glTF) convention, green = slope toward image up. Linear data. */
typedef struct wave { double fx, fy, phase, amp; } wave;

static unsigned lcg(unsigned *s) { *s = *s * 1664525u + 1013904223u; return *s >> 8; }

/* "waves:N:A:SEED": six plane waves with integer frequencies (tileable) of length in [N/2, N],
 * random directions and phases from SEED; each h_k = a/(2π|f|)·sin(2π f·X + φ), a = A/√6. */
static void make_waves(wave w[6], int n, double a, long seed) {
    unsigned s = (unsigned)seed * 2654435761u + 12345u;
    for (int k = 0; k < 6; k++) {
        int fx, fy;
        do {
            fx = (int)(lcg(&s) % (unsigned)(2 * n + 1)) - n;
            fy = (int)(lcg(&s) % (unsigned)(2 * n + 1)) - n;
        } while (fx * fx + fy * fy < n * n / 4 || fx * fx + fy * fy > n * n);
        w[k] = (wave){fx, fy, 2 * M_PI * (lcg(&s) % 1000) / 1000.0, a / sqrt(6.0)};
    }
}

/* "r,g,b" or "r,g,b,a": finite, ≥ 0. On failure writes why. */
static bool parse_colour(const char *s, size_t len, float rgba[4], char *why, size_t why_size) {
    char buf[256];
    if (len == 0) {
        snprintf(why, why_size, "a colour is empty");
        return false;
    }
    if (len >= sizeof buf) {
        snprintf(why, why_size, "a colour is too long");
        return false;
    }
    memcpy(buf, s, len);
    buf[len] = 0;
    int n = 0;
    const char *p = buf;
    for (;;) {
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        while (*end == ' ') end++;
        if (end == p || (*end && *end != ',')) {
            snprintf(why, why_size, "colour '%.100s' is not a list of numbers r,g,b", buf);
            return false;
        }
        if (n == 4) {
            snprintf(why, why_size, "colour '%.100s' has more than 4 components", buf);
            return false;
        }
        if (!isfinite(v) || v < 0.0 || v > FLT_MAX) {
            snprintf(why, why_size, "colour '%.100s' has a component that is negative or not finite", buf);
            return false;
        }
        rgba[n++] = (float)v;
        if (!*end) break;
        p = end + 1;
    }
    if (n < 3) {
        snprintf(why, why_size, "colour '%.100s' has %d component%s, needs 3 (r,g,b) or 4 (r,g,b,a)",
                 buf, n, n == 1 ? "" : "s");
        return false;
    }
    if (n == 3) rgba[3] = 1.0f;
    return true;
}

bool sl_image_procedural(sl_image *img, const char *spec, int size, char *err, size_t err_size) {
    if (!img) return false;
    memset(img, 0, sizeof *img);
    if (!spec || !*spec) {
        set_err(err, err_size, "procedural texture: empty spec (known: " SL_PROCEDURAL_KINDS ")");
        return false;
    }
    if (size < 1 || size > SL_IMAGE_MAX_DIM) {
        set_err(err, err_size, "procedural texture '%s': size %d out of range 1..%d", spec, size,
                SL_IMAGE_MAX_DIM);
        return false;
    }

    /* Split on ':' into at most 5 fields (one more than any form takes, to detect extras). */
    const char *field[5];
    size_t flen[5];
    int nf = 0;
    for (const char *p = spec;;) {
        const char *colon = strchr(p, ':');
        size_t len = colon ? (size_t)(colon - p) : strlen(p);
        if (nf < 5) field[nf] = p, flen[nf] = len;
        nf++;
        if (!colon) break;
        p = colon + 1;
    }
    const char *name = field[0];
    size_t nlen = flen[0];
#define NAME_IS(s) (nlen == strlen(s) && !strncmp(name, s, nlen))

    enum { CHECKER, GRID, GRADIENT, UV, CONSTANT, FLAT, TILT, BUMPS, WAVES } kind;
    const char *form;
    int want_fields;
    if (NAME_IS("checker")) kind = CHECKER, form = "checker:N:r,g,b:r,g,b", want_fields = 4;
    else if (NAME_IS("grid")) kind = GRID, form = "grid:N:r,g,b:r,g,b", want_fields = 4;
    else if (NAME_IS("gradient")) kind = GRADIENT, form = "gradient", want_fields = 1;
    else if (NAME_IS("uv")) kind = UV, form = "uv", want_fields = 1;
    else if (NAME_IS("constant")) kind = CONSTANT, form = "constant:r,g,b", want_fields = 2;
    else if (NAME_IS("flat")) kind = FLAT, form = "flat", want_fields = 1;
    else if (NAME_IS("tilt")) kind = TILT, form = "tilt:X,Y", want_fields = 2;
    else if (NAME_IS("bumps")) kind = BUMPS, form = "bumps:N:A", want_fields = 3;
    else if (NAME_IS("waves")) kind = WAVES, form = "waves:N:A:SEED", want_fields = 4;
    else {
        set_err(err, err_size, "procedural texture '%s': unknown kind '%.*s' (known: " SL_PROCEDURAL_KINDS ")",
                spec, (int)nlen, name);
        return false;
    }
#undef NAME_IS
    if (nf != want_fields) {
        set_err(err, err_size, "procedural texture '%s': %s: expected '%s'", spec,
                nf < want_fields ? "missing fields" : "too many fields", form);
        return false;
    }

    long n = 1;
    float ca[4] = {0, 0, 0, 1}, cb[4] = {0, 0, 0, 1};
    char why[300];
    if (kind == CHECKER || kind == GRID) {
        if (!parse_int(field[1], flen[1], 1, size, &n)) {
            set_err(err, err_size,
                    "procedural texture '%s': N '%.*s' must be a whole number from 1 to the size "
                    "%d: expected '%s'",
                    spec, (int)flen[1], field[1], size, form);
            return false;
        }
        if (!parse_colour(field[2], flen[2], ca, why, sizeof why) ||
            !parse_colour(field[3], flen[3], cb, why, sizeof why)) {
            set_err(err, err_size, "procedural texture '%s': %s: expected '%s'", spec, why, form);
            return false;
        }
    } else if (kind == CONSTANT) {
        if (!parse_colour(field[1], flen[1], ca, why, sizeof why)) {
            set_err(err, err_size, "procedural texture '%s': %s: expected '%s'", spec, why, form);
            return false;
        }
    }

    double tilt[2] = {0, 0}, amp = 0;
    wave waves[6];
    if (kind == TILT) {
        const char *comma = memchr(field[1], ',', flen[1]);
        if (!comma || !parse_float(field[1], (size_t)(comma - field[1]), -1, 1, &tilt[0]) ||
            !parse_float(comma + 1, flen[1] - (size_t)(comma + 1 - field[1]), -1, 1, &tilt[1]) ||
            tilt[0] * tilt[0] + tilt[1] * tilt[1] > 1) {
            set_err(err, err_size, "procedural texture '%s': X,Y must be two numbers with X^2 + Y^2 <= 1: expected '%s'",
                    spec, form);
            return false;
        }
    } else if (kind == BUMPS || kind == WAVES) {
        long seed = 0;
        if (!parse_int(field[1], flen[1], kind == WAVES ? 2 : 1, 4096, &n) ||
            !parse_float(field[2], flen[2], -100, 100, &amp) ||
            (kind == WAVES && !parse_int(field[3], flen[3], 0, 1000000000, &seed))) {
            set_err(err, err_size,
                    "procedural texture '%s': N must be a whole number in %d..4096, A a slope in -100..100%s: "
                    "expected '%s'", spec, kind == WAVES ? 2 : 1, kind == WAVES ? ", SEED a whole number >= 0" : "",
                    form);
            return false;
        }
        if (kind == WAVES) make_waves(waves, (int)n, amp, seed);
    }

    size_t npix = (size_t)size * (size_t)size;
    float *px = malloc(npix * 4 * sizeof(float));
    if (!px) {
        set_err(err, err_size, "procedural texture '%s': out of memory for %dx%d", spec, size, size);
        return false;
    }
    long line_width = size / (16 * n);
    if (line_width < 1) line_width = 1;
    for (long y = 0; y < size; y++) {
        for (long x = 0; x < size; x++) {
            float *d = px + ((size_t)y * size + (size_t)x) * 4;
            const float *c = NULL;
            switch (kind) {
            case CHECKER:
                c = ((x * n / size + y * n / size) & 1) ? cb : ca;
                break;
            case GRID: {
                long cx = x * n / size, cy = y * n / size;
                long sx = (cx * size + n - 1) / n, sy = (cy * size + n - 1) / n; /* cell start */
                c = (x - sx < line_width || y - sy < line_width) ? ca : cb;
                break;
            }
            case CONSTANT:
                c = ca;
                break;
            case GRADIENT:
                d[0] = size > 1 ? (float)x / (float)(size - 1) : 0.0f;
                d[1] = size > 1 ? (float)y / (float)(size - 1) : 0.0f;
                d[2] = 0.0f, d[3] = 1.0f;
                break;
            case UV:
                d[0] = ((float)x + 0.5f) / (float)size;
                d[1] = ((float)y + 0.5f) / (float)size;
                d[2] = 0.0f, d[3] = 1.0f;
                break;
            case FLAT: case TILT: case BUMPS: case WAVES: {
                double X = (x + 0.5) / size, Y = 1.0 - (y + 0.5) / size, hx = 0, hy = 0, nrm[3];
                if (kind == TILT) {
                    nrm[0] = tilt[0], nrm[1] = tilt[1], nrm[2] = sqrt(fmax(0.0, 1 - tilt[0] * tilt[0] - tilt[1] * tilt[1]));
                } else {
                    if (kind == BUMPS) { /* h = A/(2πN)·sin(2πNX)·sin(2πNY): N×N bumps, slope amplitude A */
                        double w = 2 * M_PI * n;
                        hx = amp * cos(w * X) * sin(w * Y);
                        hy = amp * sin(w * X) * cos(w * Y);
                    } else if (kind == WAVES) {
                        for (int k = 0; k < 6; k++) {
                            const wave *q = &waves[k];
                            double c = cos(2 * M_PI * (q->fx * X + q->fy * Y) + q->phase), len = hypot(q->fx, q->fy);
                            hx += q->amp * c * q->fx / len;
                            hy += q->amp * c * q->fy / len;
                        }
                    }
                    double l = sqrt(hx * hx + hy * hy + 1);
                    nrm[0] = -hx / l, nrm[1] = -hy / l, nrm[2] = 1 / l;
                }
                for (int c3 = 0; c3 < 3; c3++) d[c3] = (float)(nrm[c3] * 0.5 + 0.5);
                d[3] = 1.0f;
                break;
            }
            }
            if (c) memcpy(d, c, 4 * sizeof(float));
        }
    }
    img->width = img->height = size;
    img->channels = 4;
    img->pixels = px;
    img->source_bits = 32;
    img->source_float = true;
    img->source_srgb = false;
    return true;
}


bool sl_image_is_procedural(const char *spec) {
    static const char *const kinds[] = {"checker", "grid", "gradient", "uv", "constant", "flat", "tilt", "bumps", "waves", NULL};
    if (!spec) return false;
    size_t len = strcspn(spec, ":");
    for (const char *const *k = kinds; *k; k++)
        if (strlen(*k) == len && !strncmp(spec, *k, len)) return true;
    return false;
}
