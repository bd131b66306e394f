/* Shadows end to end, each filter and light type:
 *   umbra and lit: a sphere over a plane, ground pixels classified in C by whether the segment
 *     to the light passes through the sphere (with a margin for the kernel) must be dark / lit;
 *   lights inside or behind geometry: finite, non-negative, and a light enclosed in a sphere
 *     leaves the floor below dark;
 *   shadows off equals the unshadowed image exactly, and runs no pass;
 *   the pass runs only when something changed, and not at all without shadowed lights;
 *   the reference is soft, and PCSS is closer to it than hard shadows;
 *   PCF with taps one texel apart (texels gathered 2×2) equals the per-tap comparisons (a step of
 *     1 + 1e-6, the same taps within float rounding), every light type, pcf_size 3, 5 and 9;
 *   scenes/shadow_head.json (when the data directory has the head scan): finite, shadowed. */
#include "shadow_test.h"

#define W 96
#define H 72
static float img[W * H * 4], lit[W * H * 4];

static const test_camera cam = {{0, 4, 5}, {0, 0, 0}, 50, W, H};
static const double ball[3] = {0, 1.2, 0}, ball_r = 0.5;

#define SCENE_HEAD \
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 4, 5], \"target\": [0, 0, 0], \"fov_y\": 50}],\n" \
    " \"materials\": [{\"name\": \"m\", \"base_color\": [0.6, 0.6, 0.6]}],\n" \
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 12}, \"material\": \"m\"},\n" \
    "           {\"name\": \"ball\", \"translate\": [0, 1.2, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.5}, \"material\": \"m\"}],\n"

typedef struct light_case {
    const char *name, *json;
    double pos[3];   /* point/spot position, or for directional: -direction (towards the light) */
    bool directional;
} light_case;

static const light_case cases[] = {
    {"spot", " \"lights\": [{\"name\": \"L\", \"type\": \"spot\", \"position\": [0.6, 5, 0.3], \"direction\": [-0.12, -1, -0.06],"
             " \"intensity\": 40, \"cone_angle\": 40, \"radius\": 0.02, \"cast_shadows\": true}]}",
     {0.6, 5, 0.3}, false},
    {"directional", " \"lights\": [{\"name\": \"L\", \"type\": \"directional\", \"direction\": [-0.3, -1, -0.2],"
                    " \"intensity\": 3, \"angular_radius\": 0.2, \"cast_shadows\": true}]}",
     {0.3, 1, 0.2}, true},
    {"point", " \"lights\": [{\"name\": \"L\", \"type\": \"point\", \"position\": [-0.4, 4, 0.5], \"intensity\": 40,"
              " \"radius\": 0.02, \"cast_shadows\": true}]}",
     {-0.4, 4, 0.5}, false},
};

/* Classifies ground pixels: umbra (segment to the light deep inside the sphere) or lit (well
 * clear of it); returns the worst visibility found in each class. */
static void umbra_and_lit(const light_case *lc, const float *sh, const float *un, double margin, int *n_umbra, int *n_lit,
                          double *umbra_max, double *lit_min) {
    *n_umbra = *n_lit = 0;
    *umbra_max = 0;
    *lit_min = 1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float pf[3];
            if (!test_camera_hit_ground(&cam, x, y, 5.5f, pf) || ss_ray_hits_sphere(&cam, x, y, ball, ball_r)) continue;
            double p[3] = {pf[0], pf[1], pf[2]}, to[3];
            if (lc->directional) {
                double l[3] = {lc->pos[0], lc->pos[1], lc->pos[2]};
                ss_normalize(l);
                for (int i = 0; i < 3; i++) to[i] = p[i] + 100 * l[i];
            } else {
                for (int i = 0; i < 3; i++) to[i] = lc->pos[i];
            }
            double dist = ss_segment_distance(p, to, ball);
            int i = y * W + x;
            if (un[i * 4] < 1e-4) continue; /* outside the spot's cone */
            double v = ss_ratio(sh, un, i);
            if (dist < ball_r - margin) {
                (*n_umbra)++;
                if (v > *umbra_max) *umbra_max = v;
            } else if (dist > ball_r + margin) {
                (*n_lit)++;
                if (v < *lit_min) *lit_min = v;
            }
        }
}

static void test_umbra(void) {
    char json[4096];
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        snprintf(json, sizeof json, SCENE_HEAD "%s", cases[c].json);
        sl_harness *h = ss_make(W, H, json, (const char *[]){"spotlight-shadow.map_size=1024", NULL});
        CHECK(h != NULL);
        if (!h) continue;
        for (int f = 0; f < 4; f++) {
            CHECK(ss_set(h, "spotlight-shadow.filter=%s", ss_filters[f]));
            CHECK(ss_render_pair(h, img, lit));
            int nu, nl;
            double umax, lmin;
            umbra_and_lit(&cases[c], img, lit, 0.1, &nu, &nl, &umax, &lmin);
            printf("%-11s %-7s umbra: %4d px, brightest %.4f; lit: %4d px, darkest %.6f\n", cases[c].name, ss_filters[f], nu,
                   umax, nl, lmin);
            CHECK_MSG(nu > 40 && nl > 400, "%s/%s: too few classified pixels (%d umbra, %d lit)", cases[c].name,
                      ss_filters[f], nu, nl);
            CHECK_MSG(umax < 0.02, "%s/%s: umbra not dark (visibility %.4f)", cases[c].name, ss_filters[f], umax);
            CHECK_MSG(lmin > 0.999, "%s/%s: far points not fully lit (visibility %.6f)", cases[c].name, ss_filters[f], lmin);
            CHECK(sl_harness_count_nonfinite(img, W, H) == 0 && sl_harness_count_negative(img, W, H) == 0);
        }
        sl_harness_destroy(h);
    }
}

/* Lights inside and behind geometry, degenerate keys: finite and non-negative everywhere. */
static void test_stability(void) {
    const char *json =
        "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 4, 6], \"target\": [0, 0.5, 0], \"fov_y\": 55}],\n"
        " \"materials\": [{\"name\": \"m\", \"base_color\": [0.6, 0.6, 0.6]}],\n"
        " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 12}, \"material\": \"m\"},\n"
        "           {\"name\": \"shell\", \"translate\": [-1.5, 1.5, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6}, \"material\": \"m\"},\n"
        "           {\"name\": \"box\", \"translate\": [1.5, 0.5, 0], \"mesh\": {\"primitive\": \"cube\", \"size\": 1}, \"material\": \"m\"}],\n"
        " \"lights\": [\n"
        "  {\"name\": \"inside\", \"type\": \"spot\", \"position\": [-1.5, 1.5, 0], \"direction\": [0, -1, 0], \"intensity\": 30, \"cone_angle\": 60, \"cast_shadows\": true},\n"
        "  {\"name\": \"below\", \"type\": \"spot\", \"position\": [0, -1, 0], \"direction\": [0, 1, 0], \"intensity\": 30, \"cone_angle\": 50, \"cast_shadows\": true},\n"
        "  {\"name\": \"on_surface\", \"type\": \"spot\", \"position\": [0.5, 0, 1], \"direction\": [0, -1, 0], \"intensity\": 30, \"cone_angle\": 89.9, \"cast_shadows\": true},\n"
        "  {\"name\": \"grazing\", \"type\": \"spot\", \"position\": [-5, 0.01, 2], \"direction\": [1, 0, 0], \"intensity\": 30, \"cone_angle\": 90, \"cast_shadows\": true},\n"
        "  {\"name\": \"zero_cone\", \"type\": \"spot\", \"position\": [0, 3, 0], \"direction\": [0, -1, 0], \"intensity\": 30, \"cone_angle\": 0, \"cast_shadows\": true},\n"
        "  {\"name\": \"far\", \"type\": \"spot\", \"position\": [0, 3000, 0], \"direction\": [0, -1, 0], \"intensity\": 1e7, \"cone_angle\": 1, \"radius\": 50, \"cast_shadows\": true},\n"
        "  {\"name\": \"in_box\", \"type\": \"point\", \"position\": [1.5, 0.5, 0], \"intensity\": 30, \"cast_shadows\": true},\n"
        "  {\"name\": \"from_below\", \"type\": \"directional\", \"direction\": [0.2, 1, 0.1], \"intensity\": 3, \"cast_shadows\": true},\n"
        "  {\"name\": \"huge_sun\", \"type\": \"directional\", \"direction\": [0.3, -1, 0.2], \"intensity\": 1, \"angular_radius\": 45, \"cast_shadows\": true}]}";
    sl_harness *h = ss_make(W, H, json, (const char *[]){"spotlight-shadow.map_size=512", NULL});
    CHECK(h != NULL);
    if (!h) return;
    for (int f = 0; f < 5; f++) {
        const char *name = f < 4 ? ss_filters[f] : "reference";
        CHECK(ss_set(h, "spotlight-shadow.filter=%s", name));
        if (f == 4) CHECK(ss_set(h, "spotlight-shadow.reference_map_size=512"));
        CHECK(sl_harness_render(h, img));
        long bad = sl_harness_count_nonfinite(img, W, H), neg = sl_harness_count_negative(img, W, H);
        printf("stability scene, %-9s: %ld non-finite, %ld negative\n", name, bad, neg);
        CHECK(bad == 0 && neg == 0);
    }
    /* the spot enclosed by the shell lights nothing: the floor under the shell stays dark */
    for (const char *const *l = (const char *[]){"below", "on_surface", "grazing", "zero_cone", "far", "in_box", "from_below",
                                                 "huge_sun", NULL}; *l; l++)
        CHECK(ss_set(h, "light.%s.enabled=false", *l));
    CHECK(ss_set(h, "spotlight-shadow.filter=pcf"));
    CHECK(ss_render_pair(h, img, lit));
    double under_on = 0, under_off = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            test_camera c2 = {{0, 4, 6}, {0, 0.5, 0}, 55, W, H};
            float p[3];
            if (!test_camera_hit_ground(&c2, x, y, 5.5f, p) || hypot(p[0] + 1.5, p[2]) > 0.8) continue;
            under_on = fmax(under_on, img[(y * W + x) * 4]);
            under_off = fmax(under_off, lit[(y * W + x) * 4]);
        }
    printf("spot inside a closed sphere: floor below %.2e (unshadowed %.3f)\n", under_on, under_off);
    CHECK_MSG(under_off > 0.1 && under_on < 1e-3 * under_off, "a light enclosed in a sphere leaks: %g", under_on);
    sl_harness_destroy(h);
}

/* Shadows off is exactly the image without shadowed lights; no pass runs. */
static void test_off_exact(void) {
    char json[4096];
    snprintf(json, sizeof json, SCENE_HEAD
             " \"lights\": [{\"name\": \"a\", \"type\": \"spot\", \"position\": [0.6, 5, 0.3], \"direction\": [-0.12, -1, -0.06], \"intensity\": 40, \"cone_angle\": 40, \"cast_shadows\": true},\n"
             "  {\"name\": \"b\", \"type\": \"directional\", \"direction\": [-0.3, -1, -0.2], \"intensity\": 2, \"cast_shadows\": true},\n"
             "  {\"name\": \"c\", \"type\": \"point\", \"position\": [-2, 3, 1], \"intensity\": 20, \"cast_shadows\": true}],\n"
             " \"environment\": {\"color\": [0.05, 0.05, 0.05]}}");
    static float off[W * H * 4], none[W * H * 4];
    for (int f = 0; f < 4; f++) {
        const char *filter[] = {NULL, NULL};
        char fs[64];
        snprintf(fs, sizeof fs, "spotlight-shadow.filter=%s", ss_filters[f]);
        filter[0] = fs;
        sl_harness *h = ss_make(W, H, json, filter);
        CHECK(h && sl_harness_render(h, img));
        CHECK(h && ss_has_pass(h, "shadow-maps"));
        CHECK(h && ss_set(h, "spotlight-shadow.shadows=false") && sl_harness_render(h, off));
        CHECK(h && !ss_has_pass(h, "shadow-maps"));
        CHECK(h && ss_set(h, "spotlight-shadow.shadows=true"));
        for (const char *const *l = (const char *[]){"a", "b", "c", NULL}; h && *l; l++)
            CHECK(ss_set(h, "light.%s.cast_shadows=false", *l));
        CHECK(h && sl_harness_render(h, none));
        CHECK(h && !ss_has_pass(h, "shadow-maps"));
        sl_compare a, b;
        sl_harness_compare(off, none, W, H, 0, &a);
        sl_harness_compare(img, none, W, H, 1e-3, &b);
        printf("%-7s shadows off vs no shadowed light: max difference %g; shadows on differ in %ld pixels\n", ss_filters[f],
               a.max_abs, b.pixels_over);
        CHECK_MSG(a.max_abs == 0, "shadows off is not exactly the unshadowed image (%g)", a.max_abs);
        CHECK_MSG(b.pixels_over > 200, "the shadows are missing (%ld pixels differ)", b.pixels_over);
        CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
        sl_harness_destroy(h);
    }
}

/* The pass runs when something changed and is skipped otherwise; without shadowed lights the
 * programs are those of a scene without the plugin's shadows. */
static void test_pass_skipping(void) {
    char json[4096];
    snprintf(json, sizeof json, SCENE_HEAD "%s", cases[0].json);
    sl_harness *h = ss_make(W, H, json, NULL);
    CHECK(h && sl_harness_render(h, NULL) && ss_has_pass(h, "shadow-maps"));
    CHECK(h && sl_harness_render(h, NULL) && !ss_has_pass(h, "shadow-maps"));
    /* a parameter change re-plans the graph (the core re-runs every pass once), then skips again */
    CHECK(h && ss_set(h, "spotlight-shadow.filter=hard") && sl_harness_render(h, NULL) && sl_harness_render(h, NULL) &&
          !ss_has_pass(h, "shadow-maps"));
    CHECK(h && ss_set(h, "light.L.position=0.5,5,0.3") && sl_harness_render(h, NULL) && ss_has_pass(h, "shadow-maps"));
    CHECK(h && sl_harness_render(h, NULL) && !ss_has_pass(h, "shadow-maps"));
    CHECK(h && ss_set(h, "spotlight-shadow.map_size=512") && sl_harness_render(h, NULL) && ss_has_pass(h, "shadow-maps"));
    CHECK(h && ss_set(h, "spotlight-shadow.always_render=true") && sl_harness_render(h, NULL) && sl_harness_render(h, NULL) &&
          ss_has_pass(h, "shadow-maps"));
    sl_harness_destroy(h);

    /* a directional light without cast_shadows: no pass, and the same program as without the plugin */
    const char *plain = SCENE_HEAD " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, 0]}]}";
    h = ss_make(W, H, plain, NULL);
    sl_harness_structure with, without;
    CHECK(h && sl_harness_render(h, NULL));
    if (h) sl_harness_structure_of(h, &with);
    sl_harness_destroy(h);
    char err[2048];
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                             .scene_json = plain, .float32 = true}, err, sizeof err);
    CHECK(h && sl_harness_render(h, NULL));
    if (h) sl_harness_structure_of(h, &without);
    sl_harness_destroy(h);
    CHECK(with.pass_count == without.pass_count);
    CHECK_MSG(with.program_hashes[0] == without.program_hashes[0] && with.program_hashes[1] == without.program_hashes[1],
              "loading spotlight-shadow changed a scene without shadowed lights");
    printf("no shadowed light: %d passes with the plugin, %d without; programs identical\n", with.pass_count,
           without.pass_count);
}

/* A new render scale (the frame-time budget's knob) re-plans the graph at another size, but no
 * caster or light moved: the maps are kept, and the image is the one a fresh start at that scale
 * renders, which draws them. */
static void test_render_scale_keeps_maps(void) {
    char json[4096];
    snprintf(json, sizeof json, SCENE_HEAD "%s", cases[1].json);
    sl_harness *h = ss_make(W, H, json, NULL);
    CHECK(h && sl_harness_render(h, NULL) && ss_has_pass(h, "shadow-maps"));
    CHECK(h && ss_set(h, "core.render_scale=0.5") && sl_harness_render(h, img) && !ss_has_pass(h, "shadow-maps"));
    CHECK(h && ss_set(h, "core.render_scale=1") && sl_harness_render(h, NULL) && !ss_has_pass(h, "shadow-maps"));
    CHECK(h && ss_set(h, "core.render_scale=0.5") && sl_harness_render(h, img) && !ss_has_pass(h, "shadow-maps"));
    sl_harness_destroy(h);
    h = ss_make(W, H, json, (const char *[]){"core.render_scale=0.5", NULL});
    CHECK(h && sl_harness_render(h, lit) && ss_has_pass(h, "shadow-maps"));
    CHECK_MSG(h && !memcmp(img, lit, sizeof img), "the kept maps shade differently from freshly drawn ones");
    sl_harness_destroy(h);
}

/* The reference (area light, accumulated) is soft; PCSS is closer to it than hard shadows. */
static void test_reference(void) {
    char json[4096];
    snprintf(json, sizeof json, SCENE_HEAD
             " \"lights\": [{\"name\": \"L\", \"type\": \"spot\", \"position\": [0.6, 3.5, 0.3], \"direction\": [-0.15, -1, -0.08],"
             " \"intensity\": 40, \"cone_angle\": 45, \"radius\": 0.3, \"cast_shadows\": true}]}");
    static float ref[W * H * 4], un[W * H * 4];
    char err[2048];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = json, .float32 = true, .strict = true, .accumulate = 24,
                                                         .plugins = (const char *[]){"spotlight-shadow", NULL},
                                                         .settings = (const char *[]){"spotlight-shadow.filter=reference",
                                                                                      "spotlight-shadow.reference_map_size=1024", NULL}},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    CHECK(sl_harness_render(h, ref));
    CHECK(ss_set(h, "spotlight-shadow.shadows=false") && sl_harness_render(h, un));
    sl_harness_destroy(h);
    int soft_ref = 0;
    for (int i = 0; i < W * H; i++) {
        double v = ss_ratio(ref, un, i);
        soft_ref += v > 0.1 && v < 0.9;
    }
    h = ss_make(W, H, json, (const char *[]){"spotlight-shadow.map_size=1024", NULL});
    double rmse[4];
    int soft[4];
    for (int f = 0; f < 4 && h; f++) {
        CHECK(ss_set(h, "spotlight-shadow.filter=%s", ss_filters[f]) && sl_harness_render(h, img));
        sl_compare c;
        sl_harness_compare(img, ref, W, H, 0.01, &c);
        rmse[f] = c.rmse;
        soft[f] = 0;
        for (int i = 0; i < W * H; i++) {
            double v = ss_ratio(img, un, i);
            soft[f] += v > 0.1 && v < 0.9;
        }
        printf("light radius 0.3 m: %-7s RMSE vs the reference %.5f, penumbra pixels %d (reference %d)\n", ss_filters[f],
               rmse[f], soft[f], soft_ref);
    }
    sl_harness_destroy(h);
    CHECK_MSG(soft_ref > 3 * soft[0] && soft_ref > 50, "the reference is not soft (%d penumbra pixels, hard %d)", soft_ref,
              soft[0]);
    CHECK_MSG(rmse[3] < 0.6 * rmse[0], "PCSS (%.5f) is not closer to the area-light reference than hard shadows (%.5f)",
              rmse[3], rmse[0]);
}

/* The head assignment's extra: the head under its three shadowed directional lights. Needs the
 * data directory (SHADELAB_DATA, set by ctest when ../shared/assets exists); skipped without. */
static void test_head(void) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_file = SL_SCENES_DIR "/shadow_head.json", .float32 = true,
                                                         .strict = true, .settings = (const char *[]){"spotlight-shadow.map_size=1024", NULL}},
                                      err, sizeof err);
    if (!h) {
        printf("shadow_head.json: skipped (%.200s)\n", err);
        return;
    }
    CHECK(ss_render_pair(h, img, lit));
    int darker = 0;
    for (int i = 0; i < W * H; i++) darker += ss_ratio(img, lit, i) < 0.9;
    printf("shadow_head.json: %d of %d pixels shadowed\n", darker, W * H);
    CHECK(sl_harness_count_nonfinite(img, W, H) == 0 && sl_harness_count_negative(img, W, H) == 0);
    CHECK_MSG(darker > W * H / 20, "the head casts almost no shadow (%d pixels)", darker);
    sl_harness_destroy(h);
}

/* The gathered PCF (pcf_step 1) against the hardware taps at a step 1e-6 larger: the same filter,
 * so the same image up to rounding; a shadow must be in it. */
static void test_pcf_gather(void) {
    static float tap[W * H * 4];
    for (int c = 0; c < 3; c++)
        for (int k = 3; k <= 9; k += k == 5 ? 4 : 2) {
            char json[4096], size[64];
            snprintf(json, sizeof json, SCENE_HEAD "%s", cases[c].json);
            snprintf(size, sizeof size, "spotlight-shadow.pcf_size=%d", k);
            sl_harness *h = ss_make(W, H, json, (const char *[]){"spotlight-shadow.filter=pcf", size, "spotlight-shadow.map_size=512", NULL});
            CHECK(h != NULL);
            if (!h) continue;
            CHECK(sl_harness_render(h, img));
            CHECK(ss_set(h, "spotlight-shadow.pcf_step=1.000001") && sl_harness_render(h, tap));
            CHECK(ss_set(h, "spotlight-shadow.shadows=false") && sl_harness_render(h, lit));
            sl_compare d, sh;
            sl_harness_compare(img, tap, W, H, 1e-5, &d);
            sl_harness_compare(img, lit, W, H, 0.05, &sh);
            printf("pcf %dx%d %-11s gathered vs taps: max difference %.3g, %ld pixels over 1e-5 (shadowed pixels: %ld)\n",
                   k, k, cases[c].name, d.max_abs, d.pixels_over, sh.pixels_over);
            CHECK_MSG(d.pixels_over == 0 && d.max_abs < 1e-5, "gathered PCF differs from the taps by %g", d.max_abs);
            CHECK_MSG(sh.pixels_over > 50, "no shadow to compare (%ld pixels)", sh.pixels_over);
            sl_harness_destroy(h);
        }
}

int main(void) {
    test_pcf_gather();
    test_head();
    test_umbra();
    test_stability();
    test_off_exact();
    test_pass_skipping();
    test_render_scale_keeps_maps();
    test_reference();
    return check_result();
}
