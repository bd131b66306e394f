/* The toon example's claims, each against its closed form, with the SDK's harness only.
 *
 *  directional  a unit sphere under one directional light (no other light): every pixel equals
 *               E/π ⊙ (base·q(n·l) + rim·[n·v < rim] + highlight·[n·h ≥ highlight]), q(t) =
 *               ceil(t·N)/N, with n the analytic sphere normal (pixels within 0.01 of an edge are
 *               skipped: the mesh's interpolated normals differ from it by ~1e-4); every band,
 *               the unlit side, the rim and the highlight cover pixels.
 *  environment  the same sphere under envmap's procedural sky (sun included), no light:
 *               (a) toon with 1024 bands and no rim or highlight equals a Lambert sphere — the
 *               contract's evaluation at the dominant light plus the rest on the diffuse is exact
 *               for a Lambert f (common.glsl); (b) 3 bands minus 1024 bands is base·E_d/π·(q(t) − t)
 *               ≥ 0: non-negative, and large somewhere (the bands are there); (c) the rim: the
 *               image with the rim minus without is zero where n·v > rim and positive where below.
 *  area light   (a)–(c) under one rectangle area light (extras/area-light; required in tree,
 *               skipped out of tree where it is not installed). */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
#define PI 3.14159265358979323846
static int failures;
#define CHECK(c, ...) do { if (!(c)) { printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); failures++; } } while (0)

static const double base[3] = {0.8, 0.5, 0.3}, rim_color[3] = {0.2, 0.3, 0.4}, hl_color[3] = {0.5, 0.5, 0.5};
static const double rim = 0.3, hl = 0.95;

/* The camera of every scene below: at (0, 0, 4) looking at the origin, vertical field 40°. The
 * ray through pixel (x, y) (top row first) hits the unit sphere at normal n, seen along v; false
 * when it misses (closest distance to the centre in *miss). */
static bool sphere_at(int x, int y, double n[3], double v[3], double *miss) {
    double t = tan(20.0 * PI / 180.0);
    double d[3] = {(2.0 * (x + 0.5) / W - 1.0) * t * W / H, (1.0 - 2.0 * (y + 0.5) / H) * t, -1.0};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; i++) d[i] /= len;
    double o[3] = {0, 0, 4}, b = o[2] * d[2], c = 16.0 - 1.0, disc = b * b - c;
    *miss = sqrt(fmax(16.0 - b * b, 0.0));
    if (disc <= 0) return false;
    double s = -b - sqrt(disc);
    for (int i = 0; i < 3; i++) n[i] = o[i] + s * d[i], v[i] = -d[i];
    return true;
}
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The sphere's material: hl_on false gives the highlight no colour. */
static const char *material(char *buf, size_t n, const char *model, int bands, double rim_value, bool hl_on) {
    double k = hl_on ? 1 : 0;
    snprintf(buf, n,
             "{\"name\": \"m\", \"model\": \"%s\", \"base_color\": [%g, %g, %g], \"toon_bands\": %d, \"toon_rim\": %g,"
             " \"toon_rim_color\": [%g, %g, %g], \"toon_highlight\": %g, \"toon_highlight_color\": [%g, %g, %g]}",
             model, base[0], base[1], base[2], bands, rim_value, rim_color[0], rim_color[1], rim_color[2], hl,
             k * hl_color[0], k * hl_color[1], k * hl_color[2]);
    return buf;
}

/* Renders the sphere with material `mat` and the scene's `plugins` and `lights` into img. */
static bool render(const char *plugins, const char *mat, const char *lights, const char *environment, float *img) {
    static char json[8192];
    snprintf(json, sizeof json,
             "{\"plugins\": [%s],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40}],\n"
             " \"materials\": [%s],\n"
             " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 256,"
             " \"rings\": 128}, \"material\": \"m\"}],\n"
             " \"lights\": [%s], \"environment\": %s}",
             plugins, mat, lights, environment);
    const char *toon[] = {TOON_PLUGIN_PATH, NULL};
    const char *plain[] = {"aa.enabled=false", NULL};
    const char *env[] = {"aa.enabled=false", "envmap.background=false", "envmap.cube_size=32",
                         "envmap.sun_elevation=30", "envmap.sun_azimuth=150", NULL};
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W,
                                                          .height = H, .scene_json = json, .plugins = toon,
                                                          .settings = strstr(plugins, "envmap") ? env : plain,
                                                          .float32 = true, .strict = true},
                                      err, sizeof err);
    if (!h) {
        CHECK(0, "harness: %s", err);
        return false;
    }
    bool ok = sl_harness_render(h, img);
    CHECK(ok && sl_harness_count_nonfinite(img, W, H) == 0, "render: finite pixels");
    sl_harness_destroy(h);
    return ok;
}

/* A directional light of irradiance E from l: each pixel against the closed form. */
static void test_directional(void) {
    const double E = 2.0, l[3] = {0.72, 0.48, 0.5};
    const int bands = 4;
    double ln = sqrt(dot3(l, l)), L[3] = {l[0] / ln, l[1] / ln, l[2] / ln};
    char mat[1024], lights[512];
    snprintf(lights, sizeof lights, "{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [%g, %g, %g],"
             " \"intensity\": %g, \"color\": [1, 1, 1]}", -L[0], -L[1], -L[2], E);
    static float img[W * H * 4];
    if (!render("", material(mat, sizeof mat, "toon", bands, rim, true), lights, "{\"color\": [0, 0, 0]}", img)) return;
    int count[8] = {0}, rims = 0, highlights = 0, checked = 0, wrong = 0;
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double n[3], v[3], miss;
            const float *p = img + ((size_t)y * W + x) * 4;
            if (!sphere_at(x, y, n, v, &miss)) {
                if (miss > 1.02) CHECK(p[0] == 0 && p[1] == 0 && p[2] == 0, "background (%d, %d) is black", x, y);
                continue;
            }
            double h[3] = {L[0] + v[0], L[1] + v[1], L[2] + v[2]}, hn = sqrt(dot3(h, h));
            double nl = dot3(n, L), nv = dot3(n, v), nh = dot3(n, h) / hn;
            bool edge = nv < 0.03 || fabs(nv - rim) < 0.01 || fabs(nh - hl) < 0.003;
            for (int k = 0; k <= bands; k++) edge |= fabs(nl - (double)k / bands) < 0.01;
            if (edge) continue;
            int band = nl > 0 ? (int)ceil(nl * bands) : 0;
            bool in_rim = nl > 0 && nv < rim, in_hl = nl > 0 && nh >= hl;
            count[band]++, rims += in_rim, highlights += in_hl, checked++;
            for (int c = 0; c < 3; c++) {
                double want = nl > 0 ? E / PI * (base[c] * band / bands + (in_rim ? rim_color[c] : 0) + (in_hl ? hl_color[c] : 0)) : 0;
                double err = fabs(p[c] - want);
                if (err > 1e-3 * want + 1e-5) wrong++;
                if (err > worst) worst = err;
            }
        }
    printf("directional: %d pixels checked (unlit %d, bands %d %d %d %d, rim %d, highlight %d), %d channels off, "
           "worst |error| %.2e\n", checked, count[0], count[1], count[2], count[3], count[4], rims, highlights, wrong, worst);
    CHECK(wrong == 0, "every checked pixel equals the closed form");
    for (int k = 0; k <= bands; k++) CHECK(count[k] >= 20, "band %d covers pixels (%d)", k, count[k]);
    CHECK(rims >= 20 && highlights >= 10, "the rim (%d) and the highlight (%d) cover pixels", rims, highlights);
}

static double lum(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

/* (a)–(c) of the header under a light that is not a point (the scene's plugins, lights and
 * environment). */
static void test_extended(const char *name, const char *plugins, const char *lights, const char *environment) {
    static float lambert[W * H * 4], smooth[W * H * 4], banded[W * H * 4], no_rim[W * H * 4], shiny[W * H * 4];
    char mat[1024];
    if (!render(plugins, material(mat, sizeof mat, "lambert", 3, 0, false), lights, environment, lambert) ||
        !render(plugins, material(mat, sizeof mat, "toon", 1024, 0, false), lights, environment, smooth) ||
        !render(plugins, material(mat, sizeof mat, "toon", 3, 0, false), lights, environment, no_rim) ||
        !render(plugins, material(mat, sizeof mat, "toon", 3, rim, false), lights, environment, banded) ||
        !render(plugins, material(mat, sizeof mat, "toon", 3, rim, true), lights, environment, shiny))
        return;
    double peak = 0;
    for (int i = 0; i < W * H; i++) peak = fmax(peak, lum(lambert + 4 * i));
    double lambert_err = 0, band_min = 0, band_max = 0, rim_inside = 0, rim_max = 0;
    int sphere = 0, rim_lit = 0, highlight = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double n[3], v[3], miss;
            if (!sphere_at(x, y, n, v, &miss) || dot3(n, v) < 0.03) continue;
            int i = 4 * (y * W + x);
            double nv = dot3(n, v);
            sphere++;
            if (fabs(nv - rim) < 0.01) continue;
            for (int c = 0; c < 3; c++) lambert_err = fmax(lambert_err, fabs(smooth[i + c] - lambert[i + c]) / peak);
            highlight += lum(shiny + i) - lum(banded + i) > 0.01 * peak;
            double step = (lum(no_rim + i) - lum(smooth + i)) / peak, with_rim = (lum(banded + i) - lum(no_rim + i)) / peak;
            band_min = fmin(band_min, step), band_max = fmax(band_max, step);
            if (nv > rim) rim_inside = fmax(rim_inside, fabs(with_rim));
            else rim_max = fmax(rim_max, with_rim), rim_lit += with_rim > 0.01;
        }
    printf("%s: peak %.3f; 1024 bands vs Lambert: max |diff| %.2e of peak; 3 bands - 1024: [%.3f, %.3f] of peak; "
           "rim: up to %.3f of peak on %d pixels, %.1e inside; highlight on %d pixels\n",
           name, peak, lambert_err, band_min, band_max, rim_max, rim_lit, rim_inside, highlight);
    CHECK(sphere > 1000 && peak > 0, "%s: the sphere is lit", name);
    CHECK(lambert_err < 5e-3, "%s: toon with 1024 bands equals Lambert (%.2e of peak)", name, lambert_err);
    CHECK(band_min > -5e-3 && band_max > 0.1, "%s: 3 bands lie at or above the smooth term, well above in places", name);
    CHECK(highlight >= 5, "%s: the highlight shows", name);
    CHECK(rim_inside < 1e-4 && rim_max > 0.05 && rim_lit >= 20, "%s: the rim only where n.v < rim, and visible", name);
}

int main(void) {
    test_directional();
    test_extended("environment", "\"envmap\"", "", "{\"intensity\": 1}");
#ifdef TOON_AREA_LIGHT
    test_extended("area light", "\"area-light\"",
                  "{\"name\": \"box\", \"type\": \"area\", \"position\": [2.5, 2.0, 2.5], \"direction\": [-0.6, -0.45, -0.6],"
                  " \"color\": [1, 1, 1], \"intensity\": 6, \"width\": 1.5, \"height\": 1.0, \"axis\": [1, 0, -1]}",
                  "{\"color\": [0, 0, 0]}");
#else
    printf("area light: skipped (built out of tree: area-light, an extra, is not installed)\n");
#endif
    if (failures) printf("%d check(s) failed\n", failures);
    else printf("toon: all checks passed\n");
    return failures ? 1 : 0;
}
