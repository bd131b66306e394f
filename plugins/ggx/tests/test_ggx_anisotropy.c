/* ggx's KHR_materials_anisotropy layer (README "Layers") against closed forms.
 *
 * The test writes the extension's lobe again in C: α_t = mix(α, 1, strength²), α_b = α, the
 * direction t = T·cos r + B·sin r (r = anisotropyRotation, counter-clockwise from the tangent T
 * toward the bitangent B), b = n × t, Burley's distribution as the extension states it,
 *   D(h) = 1 / (π α_t α_b ((h·t)²/α_t² + (h·b)²/α_b² + (h·n)²)²),
 * and the Smith masking of that distribution (Heitz 2014, §5.3),
 *   G₁(x) = 2 / (1 + √(1 + (α_t²(x·t)² + α_b²(x·b)²)/(x·n)²)),  G = G₁(v)·G₁(l).
 *  1. the C lobe itself, independent of the renderer: at α_t = α_b it is ggx's isotropic
 *     D·G/(4 n·l n·v) (ggx_layer_test.h); D is normalised, ∫ D (n·h) dω_h = 1, and G₁
 *     is the masking of this D, ∫ G₁(v) max(0, v·h) D dω_h = n·v (Heitz's identity), for several
 *     α_t, α_b and views along and across t (numerical integration over the slopes); its white
 *     furnace (F = 1) stays ≤ 1 (it loses what single scattering loses, more the rougher);
 *  2. the render of a plane (tangent +X, bitangent −Z) under a sun equals, per pixel, glTF's
 *     metallic-roughness BRDF with that lobe, (1 − F)(1 − m)·base/π + F·D·G/(4 n·l n·v), for
 *     strength 0.5 and 1 and rotations 0 and 1 rad; the "ggx-anisotropy" view equals
 *     (0.5 + 0.5 cos r, 0.5 + 0.5 sin r, strength); the spec's sample code (height-correlated V)
 *     is printed beside it for comparison, not asserted (ggx's G is separable);
 *  3. strength 0 renders the isotropic model (float rounding only), the layer switched off renders
 *     bit for bit the material without the key, and a constant anisotropy texture (1, 1, 1) — the
 *     direction (1, 1)/√2, full strength — rotated by r renders as the rotation r + π/4 without it;
 *  4. the highlight stretches along the direction: a plane seen from above, lit by a point light at
 *     the camera, whose image mapped back onto the plane has its principal axis at the rotation
 *     (mod π) for four rotations: by symmetry about t and b, exactly, up to the pixel grid.
 * Mutations tried, each caught: α_t = mix(α, 1, strength) (2), t and b exchanged in the surface
 * hook (2, 4), the rotation's sine negated (2, 3, 4). */
#include "camera_rays.h"
#include "ggx_layer_test.h"
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 96
static float img[W * H * 4], img2[W * H * 4];
static const double kd[3] = {0.7, 0.5, 0.3}, E = 3, metal = 0.3, alpha = 0.4 * 0.4;


/* ---- the lobe, in the frame (t, b, n): vectors given as (x·t, x·b, x·n) ------------------------ */
static double aniso_D(const double h[3], double at, double ab) {
    if (h[2] <= 0) return 0;
    double k = h[0] * h[0] / (at * at) + h[1] * h[1] / (ab * ab) + h[2] * h[2];
    return 1 / (M_PI * at * ab * k * k);
}
static double aniso_G1(const double x[3], const double h[3], double at, double ab) {
    if (x[2] <= 0 || dot3(x, h) <= 0) return 0;
    double a2t2 = (at * at * x[0] * x[0] + ab * ab * x[1] * x[1]) / (x[2] * x[2]);
    return 2 / (1 + sqrt(1 + a2t2));
}
/* The extension's sample visibility (height-correlated), V = G/(4 n·l n·v) */
static double spec_sample_V(const double l[3], const double v[3], double at, double ab) {
    double gv = l[2] * sqrt(at * at * v[0] * v[0] + ab * ab * v[1] * v[1] + v[2] * v[2]);
    double gl = v[2] * sqrt(at * at * l[0] * l[0] + ab * ab * l[1] * l[1] + l[2] * l[2]);
    return fmin(0.5 / (gv + gl), 1);
}

/* ∫ f(h) dω_h over the slopes (x, y) = (−h_t/h_n, −h_b/h_n), x = α_t tan u, y = α_b tan w
 * (dω_h = cos³θ_h dx dy), midpoint rule: g(h) times D(h). */
typedef double (*integrand)(const double h[3], const void *user);
static double integrate_slopes(integrand g, const void *user, double at, double ab) {
    enum { N = 600 };
    double sum = 0, du = M_PI / N;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double u = -M_PI / 2 + (i + 0.5) * du, w = -M_PI / 2 + (j + 0.5) * du;
            double x = at * tan(u), y = ab * tan(w), c = 1 / sqrt(1 + x * x + y * y);
            double h[3] = {-x * c, -y * c, c};
            double jac = at / (cos(u) * cos(u)) * ab / (cos(w) * cos(w)) * c * c * c;
            sum += g(h, user) * aniso_D(h, at, ab) * jac * du * du;
        }
    return sum;
}
static double one_n_dot_h(const double h[3], const void *user) { return (void)user, h[2]; }
typedef struct { double v[3], at, ab; } masking_case;
static double masked_projection(const double h[3], const void *user) {
    const masking_case *m = user;
    return aniso_G1(m->v, h, m->at, m->ab) * fmax(dot3(m->v, h), 0);
}

/* The white furnace of the lobe (F = 1): E(v) = ∫ f (n·l) dl = ∫ D G₁(v) G₁(l) (v·h)/(n·v) dω_h
 * over the mirrored l = 2(v·h)h − v (dl = 4 (v·h) dω_h), 0 where l is below the horizon. */
static double reflected_albedo(const double h[3], const void *user) {
    const masking_case *m = user;
    double vh = dot3(m->v, h), l[3];
    for (int i = 0; i < 3; i++) l[i] = 2 * vh * h[i] - m->v[i];
    if (vh <= 0 || l[2] <= 0) return 0;
    return aniso_G1(m->v, h, m->at, m->ab) * aniso_G1(l, h, m->at, m->ab) * vh / m->v[2];
}

static void test_lobe_on_paper(void) {
    const double alphas[][2] = {{0.16, 0.16}, {0.37, 0.16}, {1.0, 0.16}, {0.5, 0.05}, {1.0, 1.0}};
    double worst_d = 0, worst_g = 0, albedo_lo = 1, albedo_hi = 0;
    for (size_t a = 0; a < sizeof alphas / sizeof *alphas; a++) {
        double at = alphas[a][0], ab = alphas[a][1];
        worst_d = fmax(worst_d, fabs(integrate_slopes(one_n_dot_h, NULL, at, ab) - 1));
        for (int k = 0; k < 6; k++) {
            double theta = (k % 3) * 0.6 + 0.3, phi = k < 3 ? 0 : M_PI / 2; /* along t, then across */
            masking_case m = {{sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)}, at, ab};
            worst_g = fmax(worst_g, fabs(integrate_slopes(masked_projection, &m, at, ab) - m.v[2]) / m.v[2]);
            double e = integrate_slopes(reflected_albedo, &m, at, ab);
            albedo_lo = fmin(albedo_lo, e), albedo_hi = fmax(albedo_hi, e);
        }
    }
    /* at α_t = α_b the lobe is ggx's isotropic one (the shared dg_over_4), for any t */
    double worst_iso = 0;
    const double n[3] = {0, 0, 1};
    for (int k = 0; k < 400; k++) {
        double tv = 0.05 + 1.45 * (k % 20) / 20, tl = 0.05 + 1.45 * (k / 20) / 20, pv = 0.7 * k, pl = 2.9 * k + 1, a = 0.05 + 0.9 * k / 400;
        double v[3] = {sin(tv) * cos(pv), sin(tv) * sin(pv), cos(tv)}, l[3] = {sin(tl) * cos(pl), sin(tl) * sin(pl), cos(tl)};
        double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
        normalize3(h);
        double want = dg_over_4(n, v, l, a), got = aniso_D(h, a, a) * aniso_G1(v, h, a, a) * aniso_G1(l, h, a, a) / (4 * v[2] * l[2]);
        worst_iso = fmax(worst_iso, fabs(got - want) / want);
    }
    printf("C lobe: |int D (n.h) - 1| worst %.2e; masking int G1 (v.h) D / (n.v) - 1 worst %.2e; at alpha_t = alpha_b "
           "against ggx's isotropic D G/(4 n.l n.v) worst %.2e\n", worst_d, worst_g, worst_iso);
    CHECK_MSG(worst_iso < 1e-12, "equal alphas must give the isotropic lobe (%.2e)", worst_iso);
    printf("white furnace (F = 1) of those lobes and views: directional albedo %.4f..%.4f\n", albedo_lo, albedo_hi);
    CHECK_MSG(albedo_hi <= 1 + 1e-3 && albedo_lo > 0, "the lobe's albedo %.4f..%.4f must lie in (0, 1]", albedo_lo, albedo_hi);
    CHECK_MSG(worst_d < 1e-3, "D must be normalised (%.2e)", worst_d);
    CHECK_MSG(worst_g < 2e-3, "G1 must be the masking of D (%.2e)", worst_g);
}

/* ---- the render ---------------------------------------------------------------------------- */
#define BASE_KEYS "\"fresnel\": \"metallic-roughness\", \"base_color\": [0.7, 0.5, 0.3], \"metallic\": 0.3, \"roughness\": 0.4"
#define SUN "{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0.3, -0.6, 0.75], \"intensity\": 3}"
static const test_camera cam = {{0, 3, 4}, {0, 0, 0}, 50, W, H};

static bool render(const test_camera *c, const char *material, const char *light, const char *const *settings,
                   const char *view, float *out) {
    char json[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [%g, %g, %g], \"target\": [%g, %g, %g], \"fov_y\": %g, "
             "\"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", %s}],\n"
             " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],\n"
             " \"lights\": [%s]}",
             c->pos[0], c->pos[1], c->pos[2], c->target[0], c->target[1], c->target[2], c->fov_deg, material, light);
    sl_harness *h = ggx_test_harness(json, W, H, settings, view);
    if (!h) return false;
    bool ok = ggx_test_render(h, W, H, out, material);
    sl_harness_destroy(h);
    return ok;
}

/* World vector → the plane's rotated frame (x·t, x·b, x·n): t = (cos r, 0, −sin r), b = n × t. */
static void to_frame(const double x[3], double r, double out[3]) {
    const double t[3] = {cos(r), 0, -sin(r)}, b[3] = {-sin(r), 0, -cos(r)};
    out[0] = dot3(x, t), out[1] = dot3(x, b), out[2] = x[1];
}

static void test_render_closed_form(void) {
    const double strengths[] = {0.5, 1.0}, rotations[] = {0.0, 1.0};
    double sun[3] = {-0.3, 0.6, -0.75};
    normalize3(sun);
    for (int si = 0; si < 2; si++)
        for (int ri = 0; ri < 2; ri++) {
            double s = strengths[si], r = rotations[ri], at = alpha + (1 - alpha) * s * s, ab = alpha;
            char keys[512];
            snprintf(keys, sizeof keys, BASE_KEYS ", \"anisotropy\": %g, \"anisotropy_rotation\": %g", s, r);
            if (!render(&cam, keys, SUN, NULL, NULL, img) || !render(&cam, keys, SUN, NULL, "ggx-anisotropy", img2)) return;
            double worst = 0, worst_view = 0, spec_sample = 0, lo = 1e30, hi = 0;
            int checked = 0;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    float p[3], o[3], d[3];
                    if (!test_camera_hit_ground(&cam, x, y, 9.5f, p)) continue;
                    test_camera_ray(&cam, x, y, o, d);
                    double vw[3] = {-d[0], -d[1], -d[2]}, hw[3] = {vw[0] + sun[0], vw[1] + sun[1], vw[2] + sun[2]};
                    normalize3(hw);
                    double v[3], l[3], h[3];
                    to_frame(vw, r, v), to_frame(sun, r, l), to_frame(hw, r, h);
                    double G = aniso_G1(v, h, at, ab) * aniso_G1(l, h, at, ab), Dh = aniso_D(h, at, ab);
                    double spec = Dh * G / (4 * l[2] * v[2]);
                    spec_sample = fmax(spec_sample, fabs(Dh * spec_sample_V(l, v, at, ab) - spec) / spec);
                    lo = fmin(lo, spec), hi = fmax(hi, spec);
                    for (int c = 0; c < 3; c++) {
                        int i = (y * W + x) * 4 + c;
                        double f0 = 0.04 * (1 - metal) + kd[c] * metal, F = schlick(dot3(v, h), f0);
                        double want = ((1 - F) * (1 - metal) * kd[c] / M_PI + F * spec) * E * l[2];
                        worst = fmax(worst, fabs(img[i] - want) / want);
                    }
                    const double view[3] = {0.5 + 0.5 * cos(r), 0.5 + 0.5 * sin(r), s};
                    for (int c = 0; c < 3; c++) worst_view = fmax(worst_view, fabs(img2[(y * W + x) * 4 + c] - view[c]));
                    checked++;
                }
            printf("strength %.1f rotation %.1f: %d pixels, D G/(4 n.l n.v) %.3g..%.3g, worst relative error %.2e; "
                   "ggx-anisotropy view worst %.2e; the spec's height-correlated sample V differs by up to %.1f %%\n",
                   s, r, checked, lo, hi, worst, worst_view, 100 * spec_sample);
            CHECK(checked > 2000);
            CHECK_MSG(hi > 0.3 && hi > 10 * lo, "the highlight must be in view (%.3g..%.3g)", lo, hi);
            CHECK_MSG(worst < 1e-3, "strength %g rotation %g: worst relative error %.2e", s, r, worst);
            CHECK_MSG(worst_view < 1e-5, "ggx-anisotropy view: worst %.2e", worst_view);
        }
}

static double worst_relative(const float *a, const float *b) {
    double worst = 0;
    for (int i = 0; i < W * H * 4; i++)
        if (i % 4 != 3) worst = fmax(worst, fabs(a[i] - b[i]) / fmax(fabs(b[i]), 1e-6));
    return worst;
}

static void test_isotropic_and_texture(void) {
    if (!render(&cam, BASE_KEYS, SUN, NULL, NULL, img)) return;
    if (render(&cam, BASE_KEYS ", \"anisotropy\": 0, \"anisotropy_rotation\": 1", SUN, NULL, NULL, img2)) {
        double w = worst_relative(img2, img);
        printf("strength 0 against the isotropic material: worst relative difference %.2e\n", w);
        CHECK_MSG(w < 1e-4, "strength 0 must render the isotropic model (%.2e)", w);
    }
    const char *off[] = {"ggx.layer_anisotropy=false", NULL};
    if (render(&cam, BASE_KEYS ", \"anisotropy\": 0.8, \"anisotropy_rotation\": 1", SUN, off, NULL, img2)) {
        int differ = 0;
        for (int i = 0; i < W * H * 4; i++) differ += img[i] != img2[i];
        printf("ggx.layer_anisotropy=false: %d channel values differ from the material without the key\n", differ);
        CHECK_MSG(differ == 0, "the layer switched off must render the material without it (%d differ)", differ);
    }
    if (render(&cam, BASE_KEYS ", \"anisotropy\": 0.8, \"anisotropy_rotation\": 0.3, \"anisotropy_map\": \"constant:1,1,1\"",
               SUN, NULL, NULL, img) &&
        render(&cam, BASE_KEYS ", \"anisotropy\": 0.8, \"anisotropy_rotation\": 1.0853981634", SUN, NULL, NULL, img2)) {
        double w = worst_relative(img, img2);
        printf("texture (1, 1, 1) rotated by 0.3 against rotation 0.3 + pi/4 without it: worst relative difference %.2e\n", w);
        CHECK_MSG(w < 1e-4, "the texture's direction and strength (%.2e)", w);
    }
}

/* The highlight's principal axis on the plane, for rotation r: the image (specular only: a black
 * base) mapped back onto the plane, each pixel weighted by its footprint there, over the pixels
 * above 0.2 of the peak; the axis angle in the (t0, b0) = (+X, −Z) frame, and the axis ratio. */
static void highlight_axis(double r, double *angle, double *ratio) {
    static const test_camera top = {{0, 5, 0.5}, {0, 0, 0}, 60, W, H};
    char keys[256];
    snprintf(keys, sizeof keys, "\"base_color\": [0, 0, 0], \"roughness\": 0.3, \"anisotropy\": 0.5, \"anisotropy_rotation\": %g", r);
    *angle = *ratio = 0;
    if (!render(&top, keys, "{\"name\": \"bulb\", \"type\": \"point\", \"position\": [0, 5, 0.5], \"intensity\": 30}", NULL,
                NULL, img))
        return;
    float peak = 0;
    for (int i = 0; i < W * H; i++) peak = fmaxf(peak, img[i * 4]);
    double m0 = 0, mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
    for (int y = 0; y + 1 < H; y++)
        for (int x = 0; x + 1 < W; x++) {
            float p[3], px[3], py[3];
            float v = img[(y * W + x) * 4];
            if (v < 0.2f * peak || !test_camera_hit_ground(&top, x, y, 9.5f, p) ||
                !test_camera_hit_ground(&top, x + 1, y, 9.5f, px) || !test_camera_hit_ground(&top, x, y + 1, 9.5f, py))
                continue;
            double ax = px[0] - p[0], az = px[2] - p[2], bx = py[0] - p[0], bz = py[2] - p[2];
            double w = v * fabs(ax * bz - az * bx), X = p[0], Y = -p[2];
            m0 += w, mx += w * X, my += w * Y, mxx += w * X * X, myy += w * Y * Y, mxy += w * X * Y;
        }
    mx /= m0, my /= m0;
    double cxx = mxx / m0 - mx * mx, cyy = myy / m0 - my * my, cxy = mxy / m0 - mx * my;
    double tr = cxx + cyy, det = cxx * cyy - cxy * cxy, disc = sqrt(fmax(tr * tr / 4 - det, 0));
    *angle = 0.5 * atan2(2 * cxy, cxx - cyy);
    *ratio = sqrt((tr / 2 + disc) / fmax(tr / 2 - disc, 1e-12));
}

static void test_highlight_follows_rotation(void) {
    const double rotations[] = {0.0, 0.5, 1.2, 2.0};
    for (size_t k = 0; k < sizeof rotations / sizeof *rotations; k++) {
        double angle, ratio, r = rotations[k];
        highlight_axis(r, &angle, &ratio);
        double diff = remainder(angle - r, M_PI);
        printf("rotation %.2f rad: the highlight's long axis at %.2f rad (off by %.2f deg), axis ratio %.2f\n", r, angle,
               diff * 180 / M_PI, ratio);
        CHECK_MSG(fabs(diff) < 1.5 * M_PI / 180, "rotation %g: long axis at %g (off by %g deg)", r, angle, diff * 180 / M_PI);
        CHECK_MSG(ratio > 2, "rotation %g: the highlight must be elongated (ratio %g)", r, ratio);
    }
}

int main(void) {
    test_lobe_on_paper();
    test_render_closed_form();
    test_isotropic_and_texture();
    test_highlight_follows_rotation();
    return check_result();
}
