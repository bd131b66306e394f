/* Spot lights: the fall-off GLSL against C; a plane under a spot light equals
 * k_d/π · I/d² · fall-off · cos θ_i at sampled pixels for both fall-off modes (a fall-off in
 * cos θ instead of θ, or without the square, is caught); the same with the light casting
 * shadows (nothing occludes: unchanged to 1e-4); a glTF KHR_lights_punctual spot comes in with
 * the gltf fall-off; an orbiting spot equals a static spot placed where the orbit puts it. */
#include "shadow_test.h"

#define W 96
#define H 72
#define N 32
static float img[W * H * 4], img2[W * H * 4];
static const test_camera cam = {{0, 6, 3}, {0, 0, 0}, 60, W, H};

static double falloff_linear(double theta, double cone) {
    double f = (1.1 * cone - theta) / fmax(0.2 * cone, 1e-6);
    return f < 0 ? 0 : f > 1 ? 1 : f;
}

static double falloff_gltf(double cos_t, double inner, double outer) {
    double scale = 1 / fmax(0.001, cos(inner) - cos(outer)), offset = -cos(outer) * scale;
    double a = cos_t * scale + offset;
    a = a < 0 ? 0 : a > 1 ? 1 : a;
    return a * a;
}

/* A ground plane under one spot; every ground pixel against the closed form. */
typedef struct spot { double pos[3], dir[3], cone, inner, I, color[3]; bool gltf; } spot;

static int compare_plane(const float *im, const spot *s, double kd, double *worst, int *band, double *mutant_gap) {
    int checked = 0;
    *worst = 0;
    *band = 0;
    *mutant_gap = 0;
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            float p[3];
            if (!test_camera_hit_ground(&cam, x, y, 5.5f, p)) continue;
            double d[3] = {s->pos[0] - p[0], s->pos[1] - p[1], s->pos[2] - p[2]};
            double d2 = ss_dot(d, d), dist = sqrt(d2);
            double l[3] = {d[0] / dist, d[1] / dist, d[2] / dist};
            double cos_t = -ss_dot(l, s->dir), theta = acos(fmin(1, fmax(-1, cos_t)));
            double f = s->gltf ? falloff_gltf(cos_t, s->inner, s->cone) : falloff_linear(theta, s->cone);
            /* plausible mistakes: linear in cos θ instead of θ; gltf without the square */
            double wrong;
            if (s->gltf) wrong = sqrt(falloff_gltf(cos_t, s->inner, s->cone));
            else {
                double c0 = cos(0.9 * s->cone), c1 = cos(1.1 * s->cone);
                wrong = fmin(1, fmax(0, (cos_t - c1) / (c0 - c1)));
            }
            double nl = l[1] > 0 ? l[1] : 0;
            if (f > 0 && f < 1) (*band)++;
            for (int c = 0; c < 3; c++) {
                double e = kd / M_PI * s->I * s->color[c] / d2 * f * nl;
                double got = im[(y * W + x) * 4 + c];
                double err = fabs(got - e) / fmax(e, 1e-3);
                if (err > *worst) *worst = err;
                double w = kd / M_PI * s->I * s->color[c] / d2 * wrong * nl;
                double gap = fabs(w - e) / fmax(e, 1e-3);
                if (gap > *mutant_gap) *mutant_gap = gap;
            }
            checked++;
        }
    return checked;
}

static void spot_json(char *buf, size_t n, const spot *s, bool shadows) {
    snprintf(buf, n,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 6, 3], \"target\": [0, 0, 0], \"fov_y\": 60}],\n"
             " \"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
             " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 12}, \"material\": \"m\"}],\n"
             " \"lights\": [{\"name\": \"s\", \"type\": \"spot\", \"position\": [%g, %g, %g], \"direction\": [%g, %g, %g],\n"
             "   \"intensity\": %g, \"color\": [%g, %g, %g], \"cone_angle\": %g, \"inner_cone_angle\": %g,\n"
             "   \"falloff\": \"%s\", \"cast_shadows\": %s}]}",
             s->pos[0], s->pos[1], s->pos[2], s->dir[0], s->dir[1], s->dir[2], s->I, s->color[0], s->color[1], s->color[2],
             s->cone * 180 / M_PI, s->inner * 180 / M_PI, s->gltf ? "gltf" : "linear", shadows ? "true" : "false");
}

int main(void) {
    char err[8192], json[4096];
    /* 1. GLSL fall-off functions against C */
    sl_harness *h = ss_make(8, 8, NULL, NULL);
    CHECK(h != NULL);
    if (!h) return check_result();
    static float in0[N * N * 4], out[N * N * 4];
    for (int i = 0; i < N * N; i++) {
        in0[i * 4 + 0] = 1.4f * (i % N) / (N - 1);               /* θ / cone */
        in0[i * 4 + 1] = (float)(M_PI / 180 * (1 + 88.0 * (i / N) / (N - 1))); /* cone, 1°..89° */
        in0[i * 4 + 2] = in0[i * 4 + 1] * 0.6f;                 /* inner */
    }
    const char *files[] = {"spot_falloff.glsl", NULL};
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "spotlight-shadow", .files = files, .width = N, .height = N,
                           .in0 = in0,
                           .expression = "vec4(spotlight_shadow_falloff_linear(in0.x * in0.y, in0.y), "
                                         "spotlight_shadow_falloff_gltf(cos(in0.x * in0.y), in0.z, in0.y), "
                                         "spotlight_shadow_falloff(vec3(sin(in0.x * in0.y), 0.0, cos(in0.x * in0.y)), "
                                         "vec3(0.0, 0.0, 1.0), in0.y, in0.z, 0.0), "
                                         "spotlight_shadow_falloff(vec3(0.0, -sin(in0.x * in0.y), cos(in0.x * in0.y)), "
                                         "vec3(0.0, 0.0, 1.0), in0.y, in0.z, 1.0))"};
    CHECK_MSG(sl_harness_eval_glsl(h, &d, out, err, sizeof err), "%s", err);
    double worst = 0;
    for (int i = 0; i < N * N; i++) {
        double theta = (double)in0[i * 4] * in0[i * 4 + 1], cone = in0[i * 4 + 1], inner = in0[i * 4 + 2];
        double e[4] = {falloff_linear(theta, cone), falloff_gltf(cos(theta), inner, cone), falloff_linear(theta, cone),
                       falloff_gltf(cos(theta), inner, cone)};
        for (int k = 0; k < 4; k++) worst = fmax(worst, fabs(out[i * 4 + k] - e[k]));
    }
    printf("fall-off GLSL vs C: worst %.2e\n", worst);
    CHECK_MSG(worst < 2e-4, "fall-off differs from C by %g", worst);
    sl_harness_destroy(h);

    /* 2. the plane under a spot, both fall-off modes, shadows off and on */
    spot spots[2] = {{{0.4, 3, -0.3}, {0.2, -1, 0.1}, 28 * M_PI / 180, 0, 20, {1, 0.9, 0.7}, false},
                     {{-0.3, 2.5, 0.2}, {-0.1, -1, -0.15}, 32 * M_PI / 180, 18 * M_PI / 180, 15, {0.8, 1, 0.6}, true}};
    for (int k = 0; k < 2; k++) {
        ss_normalize(spots[k].dir);
        for (int shadows = 0; shadows < 2; shadows++) {
            spot_json(json, sizeof json, &spots[k], shadows);
            h = ss_make(W, H, json, NULL);
            CHECK(h && sl_harness_render(h, img));
            if (!h) continue;
            double mutant;
            int band;
            int checked = compare_plane(img, &spots[k], 0.5, &worst, &band, &mutant);
            printf("%s fall-off, shadows %s: %d pixels (%d in the fall-off band), worst relative error %.2e; "
                   "the plausible mistake would differ by %.2f\n",
                   spots[k].gltf ? "gltf" : "linear", shadows ? "on" : "off", checked, band, worst, mutant);
            CHECK(checked > 500 && band > 40);
            CHECK_MSG(worst < 1e-3, "plane under a spot differs from I/d^2 falloff cos by %g (relative)", worst);
            CHECK_MSG(mutant > 0.05, "the test would not see a wrong fall-off (%g)", mutant);
            CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
            if (shadows) {
                CHECK(ss_has_pass(h, "shadow-maps"));
            } else {
                CHECK(!ss_has_pass(h, "shadow-maps"));
            }
            sl_harness_destroy(h);
        }
    }

    /* 3. a glTF spot (KHR_lights_punctual) with the gltf fall-off, inner 15°, outer 30° */
    snprintf(json, sizeof json,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 6, 3], \"target\": [0, 0, 0], \"fov_y\": 60}],\n"
             " \"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
             " \"nodes\": [{\"name\": \"g\", \"mesh\": {\"file\": \"%s/spot_ground.gltf\"}, \"material\": \"m\"}]}",
             SS_TEST_DIR);
    h = ss_make(W, H, json, NULL);
    CHECK(h && sl_harness_render(h, img));
    if (h) {
        spot g = {{0.5, 3, -0.2}, {0.15, -1, 0.1}, 30 * M_PI / 180, 15 * M_PI / 180, 25, {1, 0.8, 0.6}, true};
        ss_normalize(g.dir);
        double mutant;
        int band;
        int checked = compare_plane(img, &g, 0.5, &worst, &band, &mutant);
        printf("glTF spot: %d pixels (%d in the fall-off band), worst relative error %.2e\n", checked, band, worst);
        CHECK(checked > 500 && band > 40);
        CHECK_MSG(worst < 2e-3, "glTF spot differs by %g", worst);
        sl_harness_destroy(h);
    }

    /* 4. animation: an orbiting spot at time t equals a static spot where the orbit puts it
     *    (the GLSL light and the C shadow-map code agree); the shadow pass re-runs each frame */
    const char *orbit_scene =
        "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 6, 3], \"target\": [0, 0, 0], \"fov_y\": 60}],\n"
        " \"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
        " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 12}, \"material\": \"m\"},\n"
        "           {\"name\": \"ball\", \"translate\": [0.3, 0.7, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.5}, \"material\": \"m\"}],\n"
        " \"lights\": [{\"name\": \"s\", \"type\": \"spot\", \"position\": [%.9g, 3.5, %.9g], \"direction\": [%.9g, -1, %.9g],\n"
        "   \"intensity\": 30, \"cone_angle\": 35, \"cast_shadows\": true, \"animate\": \"%s\", \"animate_speed\": 30}]}";
    snprintf(json, sizeof json, orbit_scene, 1.5, 0.0, -0.4, 0.0, "orbit");
    /* the second frame alone, not blended with the first by the default TAA (plugins/aa) */
    h = ss_make(W, H, json, (const char *[]){"aa.enabled=false", NULL});
    CHECK(h && sl_harness_render(h, img)); /* t = 0 */
    CHECK(h && sl_harness_render(h, img)); /* t = 1/60: 0.5 rad */
    bool ran_again = h && ss_has_pass(h, "shadow-maps");
    sl_harness_destroy(h);
    double a = 30.0 / 60.0, c = cos(a), s = sin(a);
    /* rotation about +Y by a: x' = c x + s z, z' = -s x + c z */
    double px = c * 1.5, pz = -s * 1.5, dx = c * -0.4, dz = -s * -0.4;
    snprintf(json, sizeof json, orbit_scene, px, pz, dx, dz, "none");
    h = ss_make(W, H, json, NULL);
    CHECK(h && sl_harness_render(h, img2));
    sl_harness_destroy(h);
    sl_compare cmp;
    sl_harness_compare(img, img2, W, H, 1e-3, &cmp);
    printf("orbiting spot at t = 1/60 s vs the static spot: max difference %.2e, %ld pixels over 1e-3\n", cmp.max_abs,
           cmp.pixels_over);
    CHECK_MSG(cmp.pixels_over <= 2, "animated and static spot differ (%ld pixels)", cmp.pixels_over);
    CHECK_MSG(ran_again, "an animated shadowed light must re-render its map every frame");
    return check_result();
}
