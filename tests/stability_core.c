/* Stability of the core's shading in its known failure regions (docs/stability.md). Each case
 * drives the method there and asserts no NaN/Inf AND a stated non-trivial value computed in C,
 * so a black (or constant) image cannot pass.
 *
 *   point_light_close        point light 1 mm above a plane: E = I/d² per pixel (d → 1 mm)
 *   point_light_on_surface   point light exactly on the plane (d → 0), rendered
 *   point_light_zero_distance the core's sl_light_point evaluated in GLSL at d = 0 exactly and
 *                            below 0.1 mm, where only the clamp d² ≥ 1e-8 keeps 0·∞ out
 *   singular_transform       a node matrix with a zero column: NaN normal matrix → the
 *                            geometric-normal fallback of shaders/forward.frag
 *   zero_area_triangles      an OBJ with zero-area triangles sharing the lit quad's vertices,
 *                            zero normals and all-equal UVs (degenerate tangent frames)
 *   nonfinite_hdr            inputs that would overflow to +Inf (and Inf·0 = NaN) are refused by
 *                            the schema (albedo 1e38); radiance over what RGBA16F holds is
 *                            clamped to 65504 by the forward pass (finite, displays white);
 *                            huge finite radiance shows white
 *   tiny_and_huge_scenes     a 1 mm and a 10 km sphere with no camera: the default camera
 *                            frames the bounds and the sphere is lit at the Lambert value */
#include <shadelab/harness.h>
#include "check.h"
#include "test_tmp.h"
#include "scene/scene.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const double PI = 3.14159265358979323846;

typedef struct render { float *hdr, *display; int w, h; } render;

static bool render_scene(const char *json, int w, int h, render *out) {
    char err[4096];
    sl_harness *hs = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w, .height = h,
                                                           .scene_json = json, .strict = true},
                                       err, sizeof err);
    CHECK_MSG(hs != NULL, "%s", err);
    if (!hs) return false;
    out->w = w;
    out->h = h;
    out->hdr = malloc(sizeof(float) * 4 * w * h);
    out->display = malloc(sizeof(float) * 4 * w * h);
    bool ok = sl_harness_render(hs, out->hdr) && sl_harness_read_display(hs, out->display);
    CHECK(ok);
    sl_harness_destroy(hs);
    return ok;
}

static void render_free(render *r) {
    free(r->hdr);
    free(r->display);
}

static long nonfinite_rgb(const render *r) {
    long n = 0;
    for (long i = 0; i < (long)r->w * r->h; i++)
        for (int c = 0; c < 3; c++) n += !isfinite(r->hdr[4 * i + c]);
    return n;
}

/* World point on the plane y = 0 seen by pixel (px, py) from a camera at height H looking
 * straight down (up = -Z, so image right = +X and image up = -Z), vertical fov in degrees. */
static void plane_point(int px, int py, int w, int h, double H, double fov, double *x, double *z) {
    double t = tan(fov * PI / 360.0);
    double nx = 2.0 * (px + 0.5) / w - 1.0, ny = 1.0 - 2.0 * (py + 0.5) / h;
    *x = nx * H * t * ((double)w / h);
    *z = -ny * H * t;
}

/* ------------------------------------------------------------------------------------------ */

static void point_light_close(void) {
    /* I = 1e-3 W/sr at h = 1 mm above a white (k_d = 1) plane, seen from 2 cm:
     * L(r) = (1/π) · I · h / (h² + r²)^(3/2), the peak under the light I/(π h²) = 318.3. */
    const double h = 1e-3, I = 1e-3, H = 0.02, fov = 40;
    const int n = 33; /* odd: the centre pixel looks straight down at the light's foot */
    char json[1024];
    snprintf(json, sizeof json,
             "{\"cameras\": [{\"position\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": %g,"
             " \"near\": 0.001, \"far\": 1}],"
             " \"materials\": [{\"name\": \"white\", \"base_color\": [1, 1, 1]}],"
             " \"nodes\": [{\"mesh\": {\"primitive\": \"plane\", \"size\": 1}, \"material\": \"white\"}],"
             " \"lights\": [{\"type\": \"point\", \"position\": [0, %g, 0], \"intensity\": %g}]}",
             H, fov, h, I);
    render r;
    if (!render_scene(json, n, n, &r)) return;
    CHECK(nonfinite_rgb(&r) == 0);
    double peak = I / (PI * h * h), worst = 0, max = 0;
    for (int py = 0; py < n; py++)
        for (int px = 0; px < n; px++) {
            double x, z;
            plane_point(px, py, n, n, H, fov, &x, &z);
            double expect = I * h / (PI * pow(h * h + x * x + z * z, 1.5));
            double got = r.hdr[4 * (py * n + px)];
            worst = fmax(worst, fabs(got - expect) / expect);
            max = fmax(max, got);
        }
    /* half-float colour target: 2^-11 relative, plus interpolation of the position */
    CHECK_MSG(worst < 5e-3, "worst relative error %.3g against I·h/(π d³)", worst);
    CHECK_MSG(max > 0.99 * peak && max <= peak * 1.002, "max %g, bound I/(πh²) = %g", max, peak);
    double corner = r.hdr[0];
    CHECK_MSG(corner > 0.2 && corner < 0.4, "corner %g", corner); /* 1/d³ fall-off, lit */
    render_free(&r);

    /* I = 1: the peak I/(πh²) = 318310 is beyond half float (65504). The default RGBA16F
     * target must stay finite (llvmpipe saturates at 65504; +Inf would display black); the
     * RGBA32F target keeps the exact value. */
    snprintf(json, sizeof json,
             "{\"cameras\": [{\"position\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": %g,"
             " \"near\": 0.001, \"far\": 1}],"
             " \"materials\": [{\"name\": \"white\", \"base_color\": [1, 1, 1]}],"
             " \"nodes\": [{\"mesh\": {\"primitive\": \"plane\", \"size\": 1}, \"material\": \"white\"}],"
             " \"lights\": [{\"type\": \"point\", \"position\": [0, %g, 0], \"intensity\": 1}]}",
             H, fov, h);
    if (render_scene(json, n, n, &r)) {
        CHECK_MSG(nonfinite_rgb(&r) == 0, "RGBA16F: %ld non-finite values", nonfinite_rgb(&r));
        float c = r.hdr[4 * (n / 2 * n + n / 2)];
        CHECK_MSG(c >= 65000 && c <= 65504, "RGBA16F centre %g: expected the half-float maximum", c);
        CHECK(r.display[4 * (n / 2 * n + n / 2)] == 1.0f);
        render_free(&r);
    }
    char err[4096];
    sl_harness *hs = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = n, .height = n,
                                                           .scene_json = json, .float32 = true},
                                       err, sizeof err);
    CHECK_MSG(hs != NULL, "%s", err);
    if (hs) {
        float *px = malloc(sizeof(float) * 4 * n * n);
        CHECK(sl_harness_render(hs, px));
        CHECK(sl_harness_count_nonfinite(px, n, n) == 0);
        CHECK_NEAR(px[4 * (n / 2 * n + n / 2)], 1 / (PI * h * h), 318310 * 5e-3);
        free(px);
        sl_harness_destroy(hs);
    }
}

static void point_light_on_surface(void) {
    /* A point light lying in the plane: l ⟂ n everywhere, so it adds exactly 0; at the centre
     * pixel d → 0 and only the clamp d² ≥ 1e-8 keeps 0·∞ out. A directional light at 60° from
     * the normal gives every pixel L = (k_d/π)·E·cos 60° = 0.5 with E = π. */
    const int n = 33;
    const char *json =
        "{\"cameras\": [{\"position\": [0, 3, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": 40}],"
        " \"materials\": [{\"name\": \"white\", \"base_color\": [1, 1, 1]}],"
        " \"nodes\": [{\"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"white\"}],"
        " \"lights\": [{\"type\": \"point\", \"position\": [0, 0, 0], \"intensity\": 1000},"
        "              {\"type\": \"directional\", \"direction\": [0.8660254, -0.5, 0], \"intensity\": 3.14159265}]}";
    render r;
    if (!render_scene(json, n, n, &r)) return;
    CHECK(nonfinite_rgb(&r) == 0);
    double worst = 0;
    for (long i = 0; i < (long)n * n; i++) worst = fmax(worst, fabs(r.hdr[4 * i] - 0.5));
    CHECK_MSG(worst < 2e-3, "worst |L - 0.5| = %g (centre %g)", worst, r.hdr[4 * (n / 2 * n + n / 2)]);
    render_free(&r);
}

static void point_light_zero_distance(void) {
    /* A rasterised pixel almost never lands exactly on the light, so the clamp is driven
     * directly: sl_light_point (shaders/lights.glsl) for surface points at distances 0 (exact),
     * 1e-5 and 1e-4 m (inside the clamp), 1e-3 and 1 m above, 1e-3 m beside and below the light,
     * against the same formula in C: d² = max(|d|², 1e-8), l = d/√d², E = I/d². */
    char err[4096];
    sl_harness *hs = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8},
                                       err, sizeof err);
    CHECK_MSG(hs != NULL, "%s", err);
    if (!hs) return;
    enum { N = 8 };
    const float offsets[N][3] = {{0, 0, 0}, {0, 1e-5f, 0}, {0, 1e-4f, 0}, {0, 1e-3f, 0},
                                 {0, 1, 0}, {1e-3f, 0, 0}, {0, -1e-3f, 0}, {0, 0, 0}};
    const float intensity[N] = {1, 1, 1, 1, 1, 1, 1, 1e3f};
    float in0[N * 4] = {0}, in1[N * 4] = {0}, out[N * 4];
    for (int i = 0; i < N; i++) {
        for (int c = 0; c < 3; c++) in0[4 * i + c] = 0.25f; /* the surface point */
        for (int c = 0; c < 3; c++) in1[4 * i + c] = 0.25f + offsets[i][c];
        in1[4 * i + 3] = intensity[i];
    }
    const char *files[] = {"lights.glsl", "../tests/stability_core.glsl", NULL};
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .files = files, .width = N, .height = 1, .in0 = in0, .in1 = in1,
                           .expression = "stability_point_light(in0, in1)"};
    bool ok = sl_harness_eval_glsl(hs, &d, out, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    for (int i = 0; ok && i < N; i++) {
        double dx = (double)in1[4 * i] - in0[4 * i], dy = (double)in1[4 * i + 1] - in0[4 * i + 1],
               dz = (double)in1[4 * i + 2] - in0[4 * i + 2];
        double d2 = fmax(dx * dx + dy * dy + dz * dz, 1e-8), E = intensity[i] / d2, ly = dy / sqrt(d2);
        double expect = E * fmax(0, ly);
        CHECK_MSG(out[4 * i + 3] == 0, "case %d: NaN/Inf in l or E", i);
        CHECK_MSG(isfinite(out[4 * i]) && fabs(out[4 * i] - expect) <= 1e-3 * fmax(expect, 1e-3),
                  "case %d: E·max(0,n·l) = %g, expected %g", i, out[4 * i], expect);
        CHECK_MSG(fabs(out[4 * i + 1] - E) <= 1e-3 * E, "case %d: E = %g, expected %g", i, out[4 * i + 1], E);
    }
    /* the stated values: at d = 0 nothing is added and E is I·1e8; 1 mm above gives I·1e6 */
    CHECK(out[0] == 0 && fabs(out[1] - 1e8) < 1e5);
    CHECK(fabs(out[4 * 3] - 1e6) < 1e3);
    sl_harness_destroy(hs);
}

static void singular_transform(void) {
    /* A node matrix with a zero Y column flattens the plane onto itself but makes the normal
     * matrix (inverse transpose) Inf/NaN: the interpolated normal is NaN and forward.frag falls
     * back to the geometric normal from the position derivatives. Expected: L = 0.5 as above. */
    const int n = 24;
    const char *json =
        "{\"cameras\": [{\"position\": [0, 3, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": 40}],"
        " \"materials\": [{\"name\": \"white\", \"base_color\": [1, 1, 1]}],"
        " \"nodes\": [{\"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"white\","
        "             \"matrix\": [1, 0, 0, 0,  0, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}],"
        " \"lights\": [{\"type\": \"directional\", \"direction\": [0.8660254, -0.5, 0], \"intensity\": 3.14159265}]}";
    render r;
    if (!render_scene(json, n, n, &r)) return;
    CHECK(nonfinite_rgb(&r) == 0);
    double worst = 0;
    for (long i = 0; i < (long)n * n; i++) worst = fmax(worst, fabs(r.hdr[4 * i] - 0.5));
    CHECK_MSG(worst < 2e-3, "worst |L - 0.5| = %g", worst);
    render_free(&r);
}

static bool write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fputs(text, f);
    return fclose(f) == 0;
}

static void zero_area_triangles(void) {
    /* quad.obj: a 2 m quad facing +Y (two triangles) plus zero-area triangles that share its
     * vertices (collinear, repeated vertex) and carry zero normals; flat.obj: a quad whose
     * UVs are all equal, so no tangent can be derived from them. */
    char dir[512], quad[600], flat[600];
    snprintf(dir, sizeof dir, "%s/zero-area", sl_test_dir());
    char cmd[700];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
    CHECK(system(cmd) == 0);
    snprintf(quad, sizeof quad, "%s/quad.obj", dir);
    snprintf(flat, sizeof flat, "%s/flat.obj", dir);
    CHECK(write_text(quad,
                     "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0 0\n"
                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                     "vn 0 1 0\nvn 0 0 0\n"
                     "f 1/1/1 3/3/1 2/2/1\nf 1/1/1 4/4/1 3/3/1\n"
                     "f 1/1/2 5/1/2 3/3/2\n"  /* collinear: 5 is the midpoint of 1-3 */
                     "f 2/2/2 2/2/2 4/4/2\n"  /* a repeated vertex */
                     "f 4/4/2 5/1/2 2/2/2\n")); /* collinear along the other diagonal */
    CHECK(write_text(flat, "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0.5 0.5\n"
                           "f 1/1 3/1 2/1\nf 1/1 4/1 3/1\n"));
    char json[2048];
    snprintf(json, sizeof json,
             "{\"cameras\": [{\"position\": [0, 2.5, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": 40}],"
             " \"materials\": [{\"name\": \"white\", \"base_color\": [1, 1, 1]}],"
             " \"nodes\": [{\"name\": \"quad\", \"translate\": [-1, 0, 0], \"scale\": [0.98, 1, 0.98], \"material\": \"white\","
             "              \"mesh\": {\"file\": \"%s\"}},"
             "             {\"name\": \"flat\", \"translate\": [1, 0, 0], \"scale\": [0.98, 1, 0.98], \"material\": \"white\","
             "              \"mesh\": {\"file\": \"%s\"}}],"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0.8660254, -0.5, 0], \"intensity\": 3.14159265}]}",
             quad, flat);
    /* what the loader hands the renderer: unit normals, unit tangents orthogonal to them, w = ±1 */
    sl_scene scene = {0};
    char err[4096];
    bool loaded = sl_scene_load_text(&scene, json, "<stability>", dir, NULL, err, sizeof err);
    CHECK_MSG(loaded, "%s", err);
    int meshes = 0;
    for (int m = 0; loaded && m < scene.mesh_count; m++) {
        const sl_mesh_data *d = &scene.meshes[m].data;
        meshes++;
        for (int v = 0; v < d->vertex_count; v++) {
            const float *nv = d->normals + 3 * v, *t = d->tangents + 4 * v;
            double nl = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
            double tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
            double dot = nv[0] * t[0] + nv[1] * t[1] + nv[2] * t[2];
            CHECK_MSG(fabs(nl - 1) < 1e-4 && fabs(tl - 1) < 1e-4 && fabs(dot) < 1e-4 && fabs(fabs(t[3]) - 1) < 1e-6,
                      "mesh %d vertex %d: |n| %g |t| %g n·t %g w %g", m, v, nl, tl, dot, t[3]);
        }
    }
    CHECK(meshes == 2);
    sl_scene_free(&scene);
    /* rendered: both quads at L = (1/π)·π·cos 60° = 0.5 in their interiors */
    const int w = 48, h = 24;
    render r;
    if (render_scene(json, w, h, &r)) {
        CHECK(nonfinite_rgb(&r) == 0);
        int lit = 0;
        double worst = 0;
        for (int py = 0; py < h; py++)
            for (int px = 0; px < w; px++) {
                double x, z;
                plane_point(px, py, w, h, 2.5, 40, &x, &z);
                /* interiors, a pixel away from every edge (including the seam at x = 0) */
                if (fabs(z) > 0.85 || fabs(x) > 1.85 || fabs(x) < 0.15) continue;
                worst = fmax(worst, fabs(r.hdr[4 * (py * w + px)] - 0.5));
                lit++;
            }
        CHECK_MSG(lit > w * h / 3, "%d interior pixels", lit);
        CHECK_MSG(worst < 2e-3, "worst |L - 0.5| = %g", worst);
        render_free(&r);
    }
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
}

static void nonfinite_hdr(void) {
    const int n = 16;
    const char *fmt =
        "{\"cameras\": [{\"position\": [0, 3, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": 40}],"
        " \"materials\": [{\"name\": \"m\", \"base_color\": [%s]}],"
        " \"nodes\": [{\"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],"
        " \"lights\": [{\"type\": \"directional\", \"direction\": [0, %s, 0], \"intensity\": %s}]}";
    char json[1024], err[2048];
    /* k_d = 1e38 (which lit by E = 1e6 overflowed float to +Inf, and to NaN lit from behind): a
     * colour beyond what a pixel holds is refused, the same from a scene as from --set */
    snprintf(json, sizeof json, fmt, "1e38, 1e38, 1e38", "-1", "1e6");
    sl_harness *hs = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = n, .height = n,
                                                           .scene_json = json},
                                       err, sizeof err);
    CHECK_MSG(hs == NULL, "albedo 1e38 accepted");
    if (hs) sl_harness_destroy(hs);
    CHECK_CONTAINS(err, "must be <= 65504");
    struct { const char *albedo, *dir, *E, *what; double hdr; } cases[] = {
        /* L = k_d/π·E = 1e6/π ≈ 3.2e5: over RGBA16F's 65504, clamped by the forward pass (was +Inf) */
        {"1, 1, 1", "-1", "1e6", "radiance 3.2e5 (over half float)", 65504},
        /* huge but finite (1e4, inside half float): kept, and the display clamps to white */
        {"1, 1, 1", "-1", "31415.9265", "radiance 1e4", 1e4},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        snprintf(json, sizeof json, fmt, cases[k].albedo, cases[k].dir, cases[k].E);
        render r;
        if (!render_scene(json, n, n, &r)) continue;
        long bad = nonfinite_rgb(&r);
        CHECK_MSG(bad == 0, "%s: %ld non-finite", cases[k].what, bad);
        CHECK_MSG(fabs(r.hdr[0] - cases[k].hdr) < cases[k].hdr * 2e-3, "%s: HDR %g, expected %g", cases[k].what, r.hdr[0],
                  cases[k].hdr);
        double worst = 0;
        for (long i = 0; i < (long)n * n; i++)
            for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(r.display[4 * i + c] - 1.0));
        CHECK_MSG(worst == 0, "%s: display should be 1 everywhere, off by %g", cases[k].what, worst);
        render_free(&r);
    }
}

static void tiny_and_huge_scenes(void) {
    /* A sphere alone, no camera: the default camera frames the bounds from direction
     * v = normalize(0, 0.3, 0.95). A directional light travelling along -v with E = π lights
     * the point facing the camera at L = (k_d/π)·E = 0.8 (default k_d 0.8). */
    const double radii[] = {1e-3, 1.0, 1e4};
    const int n = 32;
    int covered0 = 0;
    for (size_t k = 0; k < sizeof radii / sizeof *radii; k++) {
        char json[1024];
        snprintf(json, sizeof json,
                 "{\"nodes\": [{\"mesh\": {\"primitive\": \"sphere\", \"radius\": %g}}],"
                 " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -0.3, -0.95], \"intensity\": 3.14159265}]}",
                 radii[k]);
        render r;
        if (!render_scene(json, n, n, &r)) continue;
        CHECK(nonfinite_rgb(&r) == 0);
        /* the four centre pixels see the sphere within half a pixel of its nearest point */
        double centre = 0;
        for (int dy = 0; dy < 2; dy++)
            for (int dx = 0; dx < 2; dx++) centre += r.hdr[4 * ((n / 2 - 1 + dy) * n + n / 2 - 1 + dx)] / 4;
        CHECK_MSG(fabs(centre - 0.8) < 0.8 * 0.01, "radius %g: centre %g, expected 0.8", radii[k], centre);
        int covered = 0;
        for (long i = 0; i < (long)n * n; i++) covered += r.hdr[4 * i] > 0.05f;
        /* framed the same at every scale: the camera sits at 1.05·R/sin(22.5°) from the centre of
         * the bounds, R = half their diagonal = √3·r, so the disc's angular radius is
         * asin(sin 22.5° / (1.05·√3)) = 12.1° and it covers π/4·(tan 12.1°/tan 22.5°)² = 21%
         * of a square view (a little less where the limb is darker than 0.05) */
        if (k == 0) covered0 = covered;
        double frac = (double)covered / (n * n);
        CHECK_MSG(frac > 0.17 && frac < 0.23, "radius %g: lit fraction %.3f, expected about 0.21", radii[k], frac);
        CHECK_MSG(abs(covered - covered0) <= 4, "radius %g: %d lit pixels, radius %g: %d", radii[k], covered, radii[0], covered0);
        render_free(&r);
    }
}

int main(void) {
    point_light_close();
    point_light_on_surface();
    point_light_zero_distance();
    singular_transform();
    zero_area_triangles();
    nonfinite_hdr();
    tiny_and_huge_scenes();
    return check_result();
}
