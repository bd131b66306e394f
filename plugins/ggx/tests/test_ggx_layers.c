/* ggx's glTF layers (KHR_materials_*, README "Layers") against closed forms:
 *  1. clearcoat under a directional light equals, per pixel, the extension's formula evaluated in
 *     C from the camera rays: mix(base, D·G/(4 n·l n·v), w·F_c(n·v)), F_c Schlick with F0 = 0.04;
 *  2. the coat's energy loss by its Fresnel: the render minus the "ggx-clearcoat" debug view equals
 *     the render without the layer (ggx.layer_clearcoat=false) times 1 − w·F_c(n·v);
 *  3. white furnace of the layer (GLSL ggx_coat_layer over a white Lambert base, integrated in C):
 *     ≤ 1 for every view angle and coat roughness, the base keeping exactly 1 − F_c(μ); the coat
 *     lobe alone equals C's quadrature; the form with F_c(v·h) (the Fresnel of the microfacet, not
 *     the extension's) is integrated in C too and printed: it gains energy at grazing views;
 *  4. envmap lights the coat through the lobe contract: a coated white sphere in a uniform
 *     environment 1 stays ≤ 1 in envmap's Monte Carlo reference (the model's own f), and the
 *     split sum built from the lobes is within a stated bound of it;
 *  5. specular (KHR_materials_specular): strength 0 leaves exactly the Lambert term base/π·E·n·l;
 *     a coloured, partly metallic one equals the extension's formula per pixel: F_d =
 *     Schlick(min(0.04·colour, 1)·k, F90 = k), F = mix(F_d, Schlick(base, 1), m),
 *     f = (1 − m)(1 − max F_d)·base/π + F·D·G/(4 n·l n·v); its furnace (GLSL
 *     ggx_dielectric_layer over a white base, per channel) ≤ 1 where glTF's own dielectric is
 *     (which gains energy at grazing views over smooth surfaces: printed), within its gain where
 *     not, ≤ 1 at F0 = 1;
 *     envmap's split sum from its lobes against the reference;
 *  6. sheen (KHR_materials_sheen): the "ggx-sheen" view equals colour·D·V·(n·l)·E per pixel (Charlie
 *     D, Conty Estevez & Kulla's V, written here again), and the render minus it equals the render
 *     without the layer times 1 − max(colour)·E_s(n·v), E_s the sheen's directional albedo
 *     integrated here; the GLSL BRDF integrates to this file's E_s; a white sheen over a white
 *     base in envmap's uniform environment stays ≤ 1 (the albedo scaling), and the split sum,
 *     which sees the sheen as a diffuse albedo colour·E_s, matches that reference;
 *  7. a material without a layer is untouched by the layer's switch;
 *  8. the coat over the emission (the extension's "Emission"): an emissive black plane under a coat
 *     of weight 1, unlit, seen from above (n·v up to 1) and at grazing views (n·v down to 0.03),
 *     equals emission·(1 − F_c(n·v)) per pixel, F_c Schlick with F0 = 0.04; the emission
 *     itself with ggx.layer_clearcoat=false;
 *  9. the coat's own normal texture is guarded as a mapped normal is (sl:normal_guard.glsl): a
 *     constant texture leaning the coat's normal 20° away from the camera (its reflection valid
 *     at some pixels, below the plane at others, facing away at some): the "ggx-clearcoat" view
 *     equals per pixel w·F_c(n_c·v)·D·G/(4 n_c·l n_c·v)·E·(n_c·l) of the guarded n_c (the C
 *     derivation, tests/view_guard.h). */
#include "camera_rays.h"
#include "ggx_layer_test.h"
#include "view_guard.h"
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 72
static float img[W * H * 4], img2[W * H * 4], img3[W * H * 4];
static const test_camera cam = {{0, 3, 4}, {0, 0, 0}, 50, W, H};
static const double kd[3] = {0.4, 0.3, 0.2}, E = 3;

#define COAT_KEYS "\"fresnel\": \"metallic-roughness\", \"metallic\": 0, \"roughness\": 0.6, \"clearcoat\": 0.7, " \
                  "\"clearcoat_roughness\": 0.4"
static const double coat_w = 0.7, coat_alpha = 0.4 * 0.4, base_alpha = 0.6 * 0.6;

static sl_harness *make(const char *material_keys, const char *const *settings, const char *view) {
    char json[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 4], \"target\": [0, 0, 0], \"fov_y\": 50, \"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"base_color\": [0.4, 0.3, 0.2], %s}],\n"
             " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],\n"
             /* a point-like sun (angular_radius 0: no widening of the lobes), so the closed forms are the BRDF's */
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0.1, -0.6, 0.8], \"intensity\": 3,"
             " \"angular_radius\": 0}]}",
             material_keys);
    return ggx_test_harness(json, W, H, settings, view);
}

static bool render(const char *keys, const char *const *settings, const char *view, float *out) {
    sl_harness *h = make(keys, settings, view);
    if (!h) return false;
    bool ok = ggx_test_render(h, W, H, out, keys);
    sl_harness_destroy(h);
    return ok;
}

/* per pixel of the floor: v, l, and w·F_c(n·v), n = +y; false off the floor */
static bool floor_pixel(int x, int y, double v[3], double l[3], double *fc) {
    float p[3], o[3], d[3];
    if (!test_camera_hit_ground(&cam, x, y, 9.5f, p)) return false;
    test_camera_ray(&cam, x, y, o, d);
    for (int i = 0; i < 3; i++) v[i] = -d[i];
    l[0] = -0.1, l[1] = 0.6, l[2] = -0.8;
    normalize3(l);
    *fc = coat_w * schlick(v[1], 0.04);
    return true;
}

static void test_clearcoat_closed_form(void) {
    if (!render(COAT_KEYS, NULL, NULL, img)) return;
    const double n[3] = {0, 1, 0};
    double worst = 0, coat_peak = 0;
    int checked = 0;
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            double v[3], l[3], fc;
            if (!floor_pixel(x, y, v, l, &fc)) continue;
            double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
            normalize3(h);
            double nl = l[1], F = schlick(dot3(l, h), 0.04), spec = dg_over_4(n, v, l, base_alpha),
                   coat = fc * dg_over_4(n, v, l, coat_alpha) * E * nl;
            coat_peak = fmax(coat_peak, coat);
            for (int c = 0; c < 3; c++) {
                double base = ((1 - F) * kd[c] / M_PI + F * spec) * E * nl, want = base * (1 - fc) + coat;
                worst = fmax(worst, fabs(img[(y * W + x) * 4 + c] - want) / want);
            }
            checked++;
        }
    printf("clearcoat closed form: %d pixels, worst relative error %.2e, coat peak %.3f\n", checked, worst, coat_peak);
    CHECK(checked > 500);
    CHECK_MSG(coat_peak > 0.5, "the coat's highlight must be in view (peak %.3f)", coat_peak);
    CHECK_MSG(worst < 2e-3, "clearcoat: worst relative error %.2e", worst);
}

static void test_clearcoat_fresnel_loss(void) {
    const char *off[] = {"ggx.layer_clearcoat=false", NULL};
    if (!render(COAT_KEYS, NULL, NULL, img) || !render(COAT_KEYS, off, NULL, img2) ||
        !render(COAT_KEYS, NULL, "ggx-clearcoat", img3))
        return;
    double worst = 0, loss_min = 1, loss_max = 0;
    int checked = 0;
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            double v[3], l[3], fc;
            if (!floor_pixel(x, y, v, l, &fc)) continue;
            loss_min = fmin(loss_min, fc), loss_max = fmax(loss_max, fc);
            for (int c = 0; c < 3; c++) {
                int i = (y * W + x) * 4 + c;
                double want = img2[i] * (1 - fc), got = img[i] - img3[i];
                worst = fmax(worst, fabs(got - want) / want);
            }
            checked++;
        }
    printf("clearcoat Fresnel loss: (with − coat view) vs without × (1 − w F_c(n·v)), %d pixels: worst %.2e; w F_c in [%.3f, %.3f]\n",
           checked, worst, loss_min, loss_max);
    CHECK(checked > 500);
    CHECK_MSG(loss_max - loss_min > 0.03, "the view must span a range of coat Fresnel (%.3f..%.3f)", loss_min, loss_max);
    CHECK_MSG(worst < 2e-3, "the base under the coat: worst relative error %.2e", worst);
}

/* ---- 3. furnace of the layer, GLSL evaluated over a hemisphere grid ------------------------- */
#define NT 256
#define NP 256
static float in0[NT * NP * 4], out[NT * NP * 4];

/* ∫ layer(v, l) dl over the upper hemisphere, (cos θ, φ) midpoint grid; below = white Lambert
 * (cos/π) or nothing; also C's quadrature of the coat lobe alone w·F_c·D·G/(4..)·cos. */
static bool furnace(sl_harness *h, double mu, double alpha, bool lambert, double *glsl, double *c_coat, double *c_vh) {
    double v[3] = {sqrt(1 - mu * mu), 0, mu}, n[3] = {0, 0, 1}, sum_c = 0, sum_vh = 0;
    for (int i = 0; i < NT; i++)
        for (int j = 0; j < NP; j++) {
            double ct = (i + 0.5) / NT, st = sqrt(1 - ct * ct), ph = (j + 0.5) * 2 * M_PI / NP;
            double l[3] = {st * cos(ph), st * sin(ph), ct}, hh[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
            normalize3(hh);
            float *p = in0 + (i * NP + j) * 4;
            p[0] = (float)l[0], p[1] = (float)l[1], p[2] = (float)l[2], p[3] = lambert ? (float)(ct / M_PI) : 0;
            double spec = dg_over_4(n, v, l, fmax(alpha, 2e-3)) * ct;
            sum_c += schlick(mu, 0.04) * spec;
            sum_vh += (1 - schlick(dot3(v, hh), 0.04)) * ct / M_PI + schlick(dot3(v, hh), 0.04) * spec;
        }
    char expr[256], err[8192];
    snprintf(expr, sizeof expr, "vec4(ggx_coat_layer(vec3(in0.w), vec3(1.0), 1.0, %.9g, vec3(0, 0, 1), vec3(%.9g, 0, %.9g), in0.xyz), 1.0)",
             alpha, v[0], v[2]);
    const char *files[] = {"ggx_layers.glsl", NULL};
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "ggx", .files = files, .expression = expr,
                           .defines = "SL_MAT_HAS_CLEARCOAT 1\nGGX_LAYER_CLEARCOAT 1", .width = NP, .height = NT, .in0 = in0};
    if (!sl_harness_eval_glsl(h, &d, out, err, sizeof err)) {
        CHECK_MSG(false, "eval: %s", err);
        return false;
    }
    double sum = 0;
    for (int i = 0; i < NT * NP; i++) sum += out[i * 4];
    double dw = (1.0 / NT) * (2 * M_PI / NP);
    *glsl = sum * dw, *c_coat = sum_c * dw, *c_vh = sum_vh * dw;
    return true;
}

static void test_furnace(void) {
    char err[4096];
    const char *plugins[] = {"ggx", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8,
                                                          .plugins = plugins}, err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return;
    const double mus[] = {1.0, 0.7, 0.4, 0.15, 0.05}, alphas[] = {0.1, 0.3, 0.6, 1.0};
    double most = 0, worst_coat = 0, worst_kept = 0;
    for (int a = 0; a < 4; a++)
        for (int m = 0; m < 5; m++) {
            double with_base, coat_only, c_coat, vh, unused;
            if (!furnace(h, mus[m], alphas[a], true, &with_base, &unused, &vh) ||
                !furnace(h, mus[m], alphas[a], false, &coat_only, &c_coat, &unused))
                continue;
            printf("furnace clearcoat alpha %.2f mu %.2f: coat over white Lambert %.4f (with F_c(v.h): %.4f), coat alone %.4f (C %.4f)\n",
                   alphas[a], mus[m], with_base, vh, coat_only, c_coat);
            most = fmax(most, with_base);
            worst_coat = fmax(worst_coat, fabs(coat_only - c_coat));
            CHECK_MSG(with_base <= 1.0 + 2e-3, "coat over white Lambert gains energy: %.4f (alpha %.2f, mu %.2f)", with_base,
                      alphas[a], mus[m]);
            /* what the white base keeps is its albedo 1 times 1 − F_c(μ) (the midpoint rule in cos θ
             * integrates the Lambert term exactly) */
            double kept = with_base - coat_only, want = 1 - schlick(mus[m], 0.04);
            worst_kept = fmax(worst_kept, fabs(kept - want));
        }
    printf("furnace: most %.4f; coat lobe GLSL vs C worst difference %.2e; base kept vs 1 − F_c(mu) worst %.2e\n", most,
           worst_coat, worst_kept);
    CHECK_MSG(worst_kept < 1e-4, "the base under the coat keeps 1 − F_c(mu): off by %.2e", worst_kept);
    CHECK_MSG(worst_coat < 2e-3, "coat lobe alone: GLSL vs C differ by %.2e", worst_coat);
    sl_harness_destroy(h);
}

/* ---- 4. envmap through the lobe contract ------------------------------------------------------ */
#define EW 32
static float env_ref[EW * EW * 4], env_split[EW * EW * 4];
static bool env_render(const char *material, const char *mode, int accumulate, float *o) {
    char json[2048], err[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"envmap\", \"ggx\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40, \"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", %s}],\n"
             " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 128, \"rings\": 64}, \"material\": \"m\"}],\n"
             " \"environment\": {\"map\": \"constant:1,1,1\"}}", material);
    const char *settings[] = {"envmap.cube_size=32", "envmap.samples=128", "envmap.lut_size=64", "envmap.cache=false",
                              "envmap.background=false", "aa.enabled=false", mode, "envmap.reference_samples=64", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = EW, .height = EW,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true, .accumulate = accumulate},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return false;
    bool ok = sl_harness_render(h, o) && sl_harness_count_nonfinite(o, EW, EW) == 0;
    CHECK(ok);
    sl_harness_destroy(h);
    return ok;
}

/* furnace: the reference (the model's own f) ≤ cap (NAN: not checked); the split sum from the
 * lobes within `bound` (relative RMS) of it */
static void test_envmap_lobes(const char *what, const char *material, double cap, double bound) {
    if (!env_render(material, "envmap.mode=reference", 16, env_ref) || !env_render(material, "envmap.mode=split-sum", 1, env_split))
        return;
    double most = 0, rms = 0;
    int count = 0;
    for (int y = 4; y < EW - 4; y++)
        for (int x = 4; x < EW - 4; x++) {
            const float *r = env_ref + (y * EW + x) * 4, *s = env_split + (y * EW + x) * 4;
            if (r[1] <= 0.05f) continue; /* the sphere only */
            most = fmax(most, r[1]);
            rms += pow(s[1] / r[1] - 1, 2), count++;
        }
    rms = sqrt(rms / fmax(count, 1));
    printf("envmap furnace, %s: reference at most %.4f; split sum vs reference relative rms %.4f (%d px)\n", what, most, rms,
           count);
    CHECK(count > 200);
    CHECK_MSG(isnan(cap) || most <= cap, "%s gains energy in a white furnace: %.4f", what, most);
    CHECK_MSG(rms < bound, "%s: the lobes are %.4f off the reference", what, rms);
}

/* ---- 5. specular -------------------------------------------------------------------------- */
static void test_specular_zero(void) {
    if (!render("\"fresnel\": \"metallic-roughness\", \"metallic\": 0, \"roughness\": 0.3, \"dielectric_specular\": 0",
                NULL, NULL, img))
        return;
    double worst = 0;
    int checked = 0;
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            double v[3], l[3], fc;
            if (!floor_pixel(x, y, v, l, &fc)) continue;
            for (int c = 0; c < 3; c++) {
                double want = kd[c] / M_PI * E * l[1];
                worst = fmax(worst, fabs(img[(y * W + x) * 4 + c] - want) / want);
            }
            checked++;
        }
    printf("specular 0: %d pixels equal base/pi E n.l to %.2e (relative)\n", checked, worst);
    CHECK(checked > 500);
    CHECK_MSG(worst < 1e-5, "specular 0 leaves only the diffuse: worst relative error %.2e", worst);
}

static void test_specular_closed_form(void) {
    const double k = 0.7, colour[3] = {1.5, 0.6, 0.2}, m = 0.3, alpha = 0.3 * 0.3;
    if (!render("\"fresnel\": \"metallic-roughness\", \"metallic\": 0.3, \"roughness\": 0.3, \"dielectric_specular\": 0.7, "
                "\"dielectric_specular_color\": [1.5, 0.6, 0.2]", NULL, NULL, img))
        return;
    const double n[3] = {0, 1, 0};
    double worst = 0, peak = 0;
    int checked = 0;
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            double v[3], l[3], fc;
            if (!floor_pixel(x, y, v, l, &fc)) continue;
            double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
            normalize3(h);
            double vh = dot3(v, h), w5 = pow(1 - vh, 5), S = dg_over_4(n, v, l, alpha), Fd[3], fmax_d = 0;
            for (int c = 0; c < 3; c++) {
                double f0 = fmin(0.04 * colour[c], 1) * k;
                Fd[c] = f0 + (k - f0) * w5;
                fmax_d = fmax(fmax_d, Fd[c]);
            }
            for (int c = 0; c < 3; c++) {
                double Fm = kd[c] + (1 - kd[c]) * w5, F = (1 - m) * Fd[c] + m * Fm;
                double want = ((1 - m) * (1 - fmax_d) * kd[c] / M_PI + F * S) * E * l[1];
                worst = fmax(worst, fabs(img[(y * W + x) * 4 + c] - want) / want);
                peak = fmax(peak, F * S * E * l[1]);
            }
            checked++;
        }
    printf("specular closed form (k 0.7, colour (1.5, 0.6, 0.2), metallic 0.3): %d pixels, worst relative error %.2e, "
           "specular peak %.3f\n", checked, worst, peak);
    CHECK(checked > 500);
    CHECK_MSG(peak > 0.5, "the highlight must be in view (peak %.3f)", peak);
    CHECK_MSG(worst < 2e-3, "specular: worst relative error %.2e", worst);
}

/* ∫ ggx_dielectric_layer(white base) dl per channel, as furnace() does for the coat */
static void test_specular_furnace(void) {
    char err[8192];
    const char *plugins[] = {"ggx", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8,
                                                          .plugins = plugins}, err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return;
    /* colour, strength: glTF's default (appendix B's dielectric, case 0); a coloured F0; F0
     * clamped to 1 (colour 25: no diffuse left, the GGX lobe alone); half strength */
    const char *cases[][2] = {{"vec3(1.0)", "1.0"}, {"vec3(2.0, 1.0, 0.2)", "1.0"}, {"vec3(25.0)", "1.0"}, {"vec3(1.0)", "0.5"}};
    const double mus[] = {1.0, 0.5, 0.15, 0.05}, alphas[] = {0.1, 0.5, 1.0};
    double most = 0, core[3][4], most_lobe = 0;
    for (int c = 0; c < 4; c++)
        for (int a = 0; a < 3; a++)
            for (int m = 0; m < 4; m++) {
                double mu = mus[m], v[3] = {sqrt(1 - mu * mu), 0, mu};
                for (int i = 0; i < NT; i++)
                    for (int j = 0; j < NP; j++) {
                        double ct = (i + 0.5) / NT, st = sqrt(1 - ct * ct), ph = (j + 0.5) * 2 * M_PI / NP;
                        float *p = in0 + (i * NP + j) * 4;
                        p[0] = (float)(st * cos(ph)), p[1] = (float)(st * sin(ph)), p[2] = (float)ct, p[3] = 0;
                    }
                char expr[400];
                snprintf(expr, sizeof expr, "vec4(ggx_dielectric_layer(vec3(1.0), 0.04, %s, %s, %g, vec3(0, 0, 1), vec3(%.9g, 0, %.9g), in0.xyz), 1.0)",
                         cases[c][0], cases[c][1], alphas[a], v[0], v[2]);
                const char *files[] = {"ggx_layers.glsl", NULL};
                sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "ggx", .files = files, .expression = expr,
                                       .width = NP, .height = NT, .in0 = in0};
                if (!sl_harness_eval_glsl(h, &d, out, err, sizeof err)) {
                    CHECK_MSG(false, "eval: %s", err);
                    continue;
                }
                double sum[3] = {0, 0, 0}, dw = (1.0 / NT) * (2 * M_PI / NP);
                for (int i = 0; i < NT * NP; i++)
                    for (int k = 0; k < 3; k++) sum[k] += out[i * 4 + k] * dw;
                printf("furnace specular colour %s strength %s, alpha %.1f, mu %.2f: (%.4f, %.4f, %.4f)\n", cases[c][0],
                       cases[c][1], alphas[a], mu, sum[0], sum[1], sum[2]);
                if (c == 0) core[a][m] = sum[0];
                if (c == 2) most_lobe = fmax(most_lobe, sum[0]);
                /* glTF's dielectric itself (the diffuse under 1 − F(v·h) of each light) gains energy
                 * at grazing views over a smooth surface (printed): the extension stays ≤ 1 where that
                 * does, and within its gain where it does not */
                for (int k = 0; k < 3; k++) {
                    most = fmax(most, sum[k]);
                    CHECK_MSG(sum[k] <= fmax(1.0, core[a][m]) + 1e-3, "specular %s x %s, alpha %.1f, mu %.2f: %.4f (glTF's own %.4f)",
                              cases[c][0], cases[c][1], alphas[a], mu, sum[k], core[a][m]);
                }
            }
    printf("furnace specular, white base: at most %.4f (glTF's dielectric at mu 0.05, alpha 0.1: %.4f); F0 = 1, the lobe "
           "alone: at most %.4f\n", most, core[0][3], most_lobe);
    CHECK_MSG(most_lobe <= 1.0, "the GGX lobe alone reflects more than it receives: %.4f", most_lobe);
    sl_harness_destroy(h);
}

/* ---- 6. sheen ------------------------------------------------------------------------------ */
static double sheen_L(double x, double a) {
    double t = (1 - a) * (1 - a);
    return (25.3245 * t + 21.5473 * (1 - t)) / (1 + (3.32435 * t + 3.82987 * (1 - t)) * pow(x, 0.16801 * t + 0.19823 * (1 - t))) +
           (-1.27393 * t - 1.97760 * (1 - t)) * x + (-4.85967 * t - 4.32054 * (1 - t));
}
static double sheen_lambda(double c, double a) { return c < 0.5 ? exp(sheen_L(c, a)) : exp(2 * sheen_L(0.5, a) - sheen_L(1 - c, a)); }
/* D·V·(n·l) for unit n = +y or +z given as n */
static double sheen_brdf_cos(const double n[3], const double v[3], const double l[3], double a) {
    double nl = dot3(n, l), nv = dot3(n, v), h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    if (nl <= 0 || nv <= 0) return 0;
    a = fmax(a, 0.07 * 0.07);
    normalize3(h);
    double nh = dot3(n, h), D = (2 + 1 / a) * pow(fmax(1 - nh * nh, 0), 0.5 / a) / (2 * M_PI);
    return D / ((1 + sheen_lambda(nv, a) + sheen_lambda(nl, a)) * 4 * nv);
}
/* E_s(μ) by a finer midpoint rule than the plugin's table */
static double sheen_E(double mu, double a) {
    double v[3] = {sqrt(1 - mu * mu), 0, mu}, n[3] = {0, 0, 1}, sum = 0;
    for (int i = 0; i < 200; i++)
        for (int j = 0; j < 200; j++) {
            double ct = (i + 0.5) / 200, st = sqrt(1 - ct * ct), ph = (j + 0.5) * 2 * M_PI / 200;
            double l[3] = {st * cos(ph), st * sin(ph), ct};
            sum += sheen_brdf_cos(n, v, l, a);
        }
    return sum * (1.0 / 200) * (2 * M_PI / 200);
}

#define SHEEN_KEYS "\"fresnel\": \"metallic-roughness\", \"metallic\": 0, \"roughness\": 0.5, \"sheen_color\": [0.9, 0.5, 0.3], " \
                   "\"sheen_roughness\": 0.5"
static void test_sheen_closed_form(void) {
    const double colour[3] = {0.9, 0.5, 0.3}, a = 0.25;
    const char *off[] = {"ggx.layer_sheen=false", NULL};
    if (!render(SHEEN_KEYS, NULL, NULL, img) || !render(SHEEN_KEYS, off, NULL, img2) || !render(SHEEN_KEYS, NULL, "ggx-sheen", img3))
        return;
    const double n[3] = {0, 1, 0};
    double worst_view = 0, worst_scale = 0, peak = 0, e_cache[2] = {-1, 0};
    int checked = 0;
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            double v[3], l[3], fc;
            if (!floor_pixel(x, y, v, l, &fc)) continue;
            double f = sheen_brdf_cos(n, v, l, a) * E, mu = v[1];
            if (fabs(mu - e_cache[0]) > 1e-4) e_cache[0] = mu, e_cache[1] = sheen_E(mu, a);
            double scale = 1 - 0.9 * e_cache[1];
            for (int c = 0; c < 3; c++) {
                int i = (y * W + x) * 4 + c;
                double want = colour[c] * f;
                peak = fmax(peak, want);
                worst_view = fmax(worst_view, fabs(img3[i] - want) / fmax(want, 1e-3));
                worst_scale = fmax(worst_scale, fabs((img[i] - img3[i]) - img2[i] * scale) / img2[i]);
            }
            checked++;
        }
    printf("sheen closed form: %d pixels; the ggx-sheen view vs colour D V n.l E worst %.2e (peak %.3f); with − view vs "
           "without x (1 − max(colour) E_s(mu)) worst %.2e\n", checked, worst_view, peak, worst_scale);
    CHECK(checked > 200);
    CHECK_MSG(peak > 0.02, "the sheen must show (peak %.3f)", peak);
    CHECK_MSG(worst_view < 2e-3, "sheen view: worst %.2e", worst_view);
    /* the plugin's table (32 × 8, bilinear) against this file's integral */
    CHECK_MSG(worst_scale < 5e-3, "albedo scaling: worst %.2e", worst_scale);
}

static void test_sheen_integral(void) {
    char err[8192];
    const char *plugins[] = {"ggx", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8,
                                                          .plugins = plugins}, err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return;
    const double mus[] = {1.0, 0.5, 0.15}, alphas[] = {0.05, 0.25, 1.0};
    double worst = 0;
    for (int a = 0; a < 3; a++)
        for (int m = 0; m < 3; m++) {
            double mu = mus[m], v[3] = {sqrt(1 - mu * mu), 0, mu};
            for (int i = 0; i < NT; i++)
                for (int j = 0; j < NP; j++) {
                    double ct = (i + 0.5) / NT, st = sqrt(1 - ct * ct), ph = (j + 0.5) * 2 * M_PI / NP;
                    float *p = in0 + (i * NP + j) * 4;
                    p[0] = (float)(st * cos(ph)), p[1] = (float)(st * sin(ph)), p[2] = (float)ct, p[3] = 0;
                }
            char expr[300];
            snprintf(expr, sizeof expr, "vec4(ggx_sheen_brdf_cos(vec3(0, 0, 1), vec3(%.9g, 0, %.9g), in0.xyz, %g))", v[0], v[2], alphas[a]);
            const char *files[] = {"ggx_layers.glsl", NULL};
            sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "ggx", .files = files, .expression = expr,
                                   .width = NP, .height = NT, .in0 = in0};
            if (!sl_harness_eval_glsl(h, &d, out, err, sizeof err)) {
                CHECK_MSG(false, "eval: %s", err);
                continue;
            }
            double sum = 0;
            for (int i = 0; i < NT * NP; i++) sum += out[i * 4];
            sum *= (1.0 / NT) * (2 * M_PI / NP);
            double want = sheen_E(mu, alphas[a]);
            printf("sheen albedo alpha %.2f mu %.2f: GLSL %.4f, C %.4f\n", alphas[a], mu, sum, want);
            worst = fmax(worst, fabs(sum - want));
            CHECK_MSG(sum <= 1.0, "the sheen alone reflects more than it receives: %.4f", sum);
        }
    CHECK_MSG(worst < 5e-3, "sheen albedo: GLSL vs C worst %.2e", worst);
    sl_harness_destroy(h);
}

/* ---- 8. the coat over the emission ---------------------------------------------------------- */
/* An unlit, black, emissive plane under a coat seen from `eye`: per pixel of the plane, the
 * render against emission·(1 − w·F_c(n·v)) (w = 0: the emission itself); the range of n·v seen. */
static void coat_over_emission(const float eye[3], const float target[3], const char *const *settings, double w,
                               double *worst, double *mu_min, double *mu_max) {
    const double e[3] = {0.8 * 2, 0.5 * 2, 0.25 * 2}; /* emissive × emissive_strength */
    char json[2048];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [%g, %g, %g], \"target\": [%g, %g, %g], \"fov_y\": 50, "
             "\"near\": 0.05, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 0, "
             "\"roughness\": 0.5, \"base_color\": [0, 0, 0], \"emissive\": [0.8, 0.5, 0.25], \"emissive_strength\": 2, "
             "\"clearcoat\": 1, \"clearcoat_roughness\": 0.3}],\n"
             " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],\n"
             " \"lights\": []}",
             eye[0], eye[1], eye[2], target[0], target[1], target[2]);
    sl_harness *h = ggx_test_harness(json, W, H, settings, NULL);
    if (!h) return;
    bool ok = ggx_test_render(h, W, H, img, "the coated emissive plane");
    sl_harness_destroy(h);
    if (!ok) return;
    const test_camera view = {{eye[0], eye[1], eye[2]}, {target[0], target[1], target[2]}, 50, W, H};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float p[3], o[3], d[3];
            if (!test_camera_hit_ground(&view, x, y, 9.9f, p)) continue;
            test_camera_ray(&view, x, y, o, d);
            double mu = -d[1], keep = 1 - w * schlick(mu, 0.04);
            *mu_min = fmin(*mu_min, mu), *mu_max = fmax(*mu_max, mu);
            for (int c = 0; c < 3; c++) *worst = fmax(*worst, fabs(img[(y * W + x) * 4 + c] - e[c] * keep) / (e[c] * keep));
        }
}

static void test_clearcoat_emission(void) {
    const float above[3] = {0, 3, 0.3f}, origin[3] = {0, 0, 0}, low[3] = {0, 0.35f, 9}, far[3] = {0, 0, -10};
    const char *off[] = {"ggx.layer_clearcoat=false", NULL};
    double worst = 0, mu_min = 1, mu_max = 0, worst_off = 0, unused0 = 1, unused1 = 0;
    coat_over_emission(above, origin, NULL, 1, &worst, &mu_min, &mu_max);
    double top = mu_max;
    coat_over_emission(low, far, NULL, 1, &worst, &mu_min, &mu_max);
    coat_over_emission(low, far, off, 0, &worst_off, &unused0, &unused1);
    printf("clearcoat over emission: emission (1 - F_c(n.v)) per pixel for n.v in [%.3f, %.4f], worst relative error "
           "%.2e; layer off: the emission itself, worst %.2e\n", mu_min, top, worst, worst_off);
    CHECK_MSG(top > 0.999 && mu_min < 0.05, "the views must reach normal incidence and grazing (n.v %.4f..%.3f)", mu_min, top);
    CHECK_MSG(worst < 2e-3, "the coat over the emission: worst relative error %.2e", worst);
    CHECK_MSG(worst_off < 1e-5, "without the layer the emission is undimmed: worst relative error %.2e", worst_off);
}

static void test_clearcoat_normal_guard(void) {
    const double s20 = sin(20 * M_PI / 180), c20 = cos(20 * M_PI / 180), g[3] = {0, 1, 0};
    char keys[512];
    snprintf(keys, sizeof keys, COAT_KEYS ", \"clearcoat_normal_map\": \"constant:0.5,%.9g,%.9g\"", 0.5 + 0.5 * s20,
             0.5 + 0.5 * c20);
    if (!render(keys, NULL, "ggx-clearcoat", img)) return;
    double worst = 0, peak = 0;
    int checked = 0, bent = 0, away = 0;
    static double want[W * H];
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            double v[3], l[3], fc;
            if (!floor_pixel(x, y, v, l, &fc)) continue;
            const float vf[3] = {(float)v[0], (float)v[1], (float)v[2]};
            double n[3] = {0, c20, -s20};
            away += vg_dot(n, v) < 0;
            vg_view_guard(n, vf, g);
            bent += n[2] != -s20;
            double nl = vg_dot(n, l), nv = vg_dot(n, v);
            want[y * W + x] = coat_w * schlick(fmax(nv, 0), 0.04) * dg_over_4(n, v, l, coat_alpha) * E * fmax(nl, 0);
            peak = fmax(peak, want[y * W + x]);
            checked++;
        }
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            double v[3], l[3], fc;
            if (!floor_pixel(x, y, v, l, &fc)) continue;
            worst = fmax(worst, fabs(img[(y * W + x) * 4 + 1] - want[y * W + x]) / fmax(want[y * W + x], 0.01 * peak));
        }
    printf("clearcoat normal texture leaning 20 deg away: %d px (%d bent, %d facing away before), coat peak %.3f, worst "
           "relative error %.2e\n", checked, bent, away, peak, worst);
    CHECK_MSG(bent > 50 && checked - bent > 50 && away > 50, "%d of %d pixels bent, %d facing away", bent, checked, away);
    CHECK_MSG(peak > 0.2, "the coat's highlight must be in view (peak %.3f)", peak);
    CHECK_MSG(worst < 2e-3, "guarded coat normal: worst relative error %.2e", worst);
}

int main(void) {
    test_clearcoat_closed_form();
    test_clearcoat_fresnel_loss();
    test_clearcoat_emission();
    test_clearcoat_normal_guard();
    test_furnace();
    test_envmap_lobes("coated white sphere", "\"metallic\": 0, \"roughness\": 1, \"base_color\": [1, 1, 1], \"clearcoat\": 1, "
                      "\"clearcoat_roughness\": 0.5", 1.0, 0.01);
    test_specular_zero();
    test_specular_closed_form();
    test_specular_furnace();
    test_envmap_lobes("white sphere, specular colour (2, 1, 0.2)", "\"metallic\": 0, \"roughness\": 0.4, \"base_color\": [1, 1, 1], "
                      "\"dielectric_specular_color\": [2, 1, 0.2]", NAN, 0.05);
    test_sheen_closed_form();
    test_sheen_integral();
    test_envmap_lobes("white sheen over a white sphere", "\"metallic\": 0, \"roughness\": 1, \"base_color\": [1, 1, 1], "
                      "\"sheen_color\": [1, 1, 1], \"sheen_roughness\": 0.6", 1.0, 0.01);
    /* 7. a material without a layer: the layers' switches change nothing */
    const char *off[] = {"ggx.layer_clearcoat=false", "ggx.layer_specular=false", "ggx.layer_sheen=false", NULL};
    const char *plain = "\"fresnel\": \"metallic-roughness\", \"metallic\": 0.2, \"roughness\": 0.5";
    if (render(plain, NULL, NULL, img) && render(plain, off, NULL, img2))
        CHECK_MSG(!memcmp(img, img2, sizeof img), "a material without a layer changed with ggx.layer_*");
    return check_result();
}
