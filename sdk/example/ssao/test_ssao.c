/* Headless test of the ssao example (link shadelab::harness), each claim against a closed form:
 *   open plane   a plane with nothing above it is not occluded: the image equals ssao off
 *   corner       in a 90° corner lit by a uniform environment only, ambient at the crease is
 *                halved (the wall closes half of the cosine-weighted hemisphere: occluded share
 *                1/2), and points farther than ssao.radius from the other plane are not darkened
 *   far occluder a wall with a ball in front of it, farther than ssao.radius from the wall: no wall
 *                pixel is darkened (nothing is within the radius of the wall: the range check
 *                keeps the ball's depth, which lies in front of the samples, from occluding)
 *   direct       the same corner lit by a directional light only: the image equals ssao off
 *   live         half resolution and strength change live; strength 0 equals ssao off
 *   pass view    the "ssao-visibility" debug view shows the visibility as it is (no tone mapping)
 *   normal view  the "ssao-normal" view shows the core's "normal" target, the planes' view-space
 *                normals; the core's depth pre-pass runs only while ssao is on
 *   other lights the corner under envmap's sky (sun included, no light) is occluded exactly as
 *                under the uniform environment (the same visibility); a shadowed spot
 *                (spotlight-shadow) and a rectangle area light (extras/area-light, in tree only)
 *                are untouched; with aa's TAA on, the crease is still halved
 * Ambient-only Lambert: radiance = base_color × environment × visibility, so the ratio of the
 * images with ssao on and off is the visibility. */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

/* a floor (y = 0, z in [0, 6]) meeting a wall (z = 0, y in [0, 6]) along the x axis */
static const char *corner =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 2.2, 4.2], \"target\": [0, 0.4, 0.4], \"fov_y\": 50}],\n"
    " \"materials\": [{\"name\": \"m\", \"model\": \"lambert\", \"base_color\": [0.8, 0.8, 0.8]}],\n"
    " \"nodes\": [{\"name\": \"floor\", \"translate\": [0, 0, 3], \"mesh\": {\"primitive\": \"plane\", \"size\": 6}, \"material\": \"m\"},\n"
    "           {\"name\": \"wall\", \"translate\": [0, 3, 0], \"rotate\": [90, 0, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 6}, \"material\": \"m\"}],\n"
    " \"environment\": {\"color\": [1, 1, 1], \"intensity\": %s}%s}\n";
static const char *sun = ",\n \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.3, -1, -0.6], \"intensity\": 2}]";

static const char *open_plane =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 3], \"target\": [0, 0, 0], \"fov_y\": 50}],\n"
    " \"materials\": [{\"name\": \"m\", \"model\": \"lambert\", \"base_color\": [0.8, 0.8, 0.8]}],\n"
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"m\"}],\n"
    " \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1}}\n";

/* a wall (z = 0) seen obliquely and a ball (radius 0.3) centred 1.2 m in front of it: the ball's
 * base colour has no red, so the wall's pixels are those with red */
static const char *far_ball =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [2.0, 1.0, 4.5], \"target\": [0, 0, 0], \"fov_y\": 45}],\n"
    " \"materials\": [{\"name\": \"wall\", \"model\": \"lambert\", \"base_color\": [0.8, 0.8, 0.8]},\n"
    "                {\"name\": \"ball\", \"model\": \"lambert\", \"base_color\": [0, 0.8, 0.8]}],\n"
    " \"nodes\": [{\"name\": \"wall\", \"rotate\": [90, 0, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 8}, \"material\": \"wall\"},\n"
    "           {\"name\": \"ball\", \"translate\": [0, 0, 1.2], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.3}, \"material\": \"ball\"}],\n"
    " \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1}}\n";

/* the corner with the plugins `plugins` (a JSON list's items) named by the scene */
static void corner_with(char *scene, size_t n, const char *plugins, const char *intensity, const char *lights) {
    char body[4096];
    snprintf(body, sizeof body, corner, intensity, lights);
    snprintf(scene, n, "{\"plugins\": [%s],\n %s", plugins, body + 1);
}

static sl_harness *open_harness(const char *scene, const char *const *settings) {
    const char *plugins[] = {SSAO_PLUGIN_PATH, NULL};
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = scene, .plugins = plugins, .settings = settings,
                                                         .float32 = true, .strict = true},
                                      err, sizeof err);
    if (!h) { printf("FAIL: harness: %s\n", err); exit(1); }
    return h;
}

static float *render(const char *scene, const char *const *settings) {
    sl_harness *h = open_harness(scene, settings);
    float *img = malloc(sizeof(float) * W * H * 4);
    if (!sl_harness_render(h, img)) { printf("FAIL: render\n"); exit(1); }
    sl_harness_destroy(h);
    return img;
}

static const char *off[] = {"ssao.enabled=false", NULL};

static double max_diff(const float *a, const float *b) {
    double m = 0;
    for (int i = 0; i < W * H * 4; i++) m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

/* visibility per pixel: ratio of the green channels (0 where nothing was drawn) */
static void visibility(const float *on, const float *ref, float *v) {
    for (int i = 0; i < W * H; i++) v[i] = ref[i * 4 + 1] > 1e-3f ? on[i * 4 + 1] / ref[i * 4 + 1] : 0;
}

int main(void) {
    char scene[4096];
    static float v[W * H], v_ambient[W * H];

    /* open plane: nothing above it, nothing occluded */
    float *on = render(open_plane, NULL), *ref = render(open_plane, off);
    CHECK(max_diff(on, ref) <= 1e-5, "open plane: ssao darkened it (max diff %g)", max_diff(on, ref));
    free(on), free(ref);

    /* corner, ambient light only */
    snprintf(scene, sizeof scene, corner, "1", "");
    on = render(scene, NULL), ref = render(scene, off);
    visibility(on, ref, v);
    /* down the middle column: the wall, the crease, the floor; the crease is where v is least */
    int x = W / 2, crease = 0;
    for (int y = 0; y < H; y++)
        if (v[y * W + x] > 0 && v[y * W + x] < v[crease * W + x]) crease = y;
    float least = v[crease * W + x];
    CHECK(least > 0.40f && least < 0.62f, "corner: visibility at the crease %.3f, expected about 1/2", least);
    /* the top rows of the wall and the bottom rows of the floor are farther than the radius (0.5)
     * from the other plane: open */
    float top = v[2 * W + x], bottom = v[(H - 3) * W + x];
    CHECK(fabsf(top - 1) < 1e-3f && fabsf(bottom - 1) < 1e-3f, "corner: far from the crease visibility %.4f (wall) "
          "%.4f (floor), expected 1", top, bottom);
    /* it falls towards the crease from both sides */
    CHECK(v[(crease - 3) * W + x] > least && v[(crease + 3) * W + x] > least, "corner: not least at the crease");
    printf("corner: visibility %.3f at the crease (row %d), %.4f and %.4f far from it\n", least, crease, top, bottom);
    CHECK(sl_harness_count_nonfinite(on, W, H) == 0, "corner: non-finite pixels");
    memcpy(v_ambient, v, sizeof v);

    /* the pass view shows the visibility as it is */
    {
        sl_harness *h = open_harness(scene, NULL);
        char err[512];
        CHECK(sl_harness_set_debug_view(h, "ssao-visibility", err, sizeof err), "%s", err);
        static float display[W * H * 4];
        CHECK(sl_harness_render(h, NULL) && sl_harness_read_display(h, display), "pass view: render");
        float shown_top = display[(2 * W + x) * 4], shown_crease = display[(crease * W + x) * 4];
        CHECK(fabsf(shown_top - 1) < 1.5f / 255 && fabsf(shown_crease - least) < 0.03f,
              "pass view: shows %.3f far and %.3f at the crease, the pass computed 1 and %.3f", shown_top,
              shown_crease, least);
        sl_harness_destroy(h);
    }

    /* live: half resolution still darkens the crease about as much; strength 0 is no change */
    {
        sl_harness *h = open_harness(scene, NULL);
        char err[512];
        float *img = malloc(sizeof(float) * W * H * 4);
        CHECK(sl_harness_set(h, "ssao.half_resolution=true", err, sizeof err), "%s", err);
        CHECK(sl_harness_render(h, img), "half resolution: render");
        visibility(img, ref, v);
        /* the crease's row is blurred into the rows beside it by the half-size target's filtering */
        CHECK(v[crease * W + x] < 0.75f && v[crease * W + x] != least, "half resolution: crease %.3f, full %.3f",
              v[crease * W + x], least);
        CHECK(fabsf(v[2 * W + x] - 1) < 1e-3f, "half resolution: far from the crease %.4f", v[2 * W + x]);
        CHECK(sl_harness_set(h, "ssao.strength=0", err, sizeof err), "%s", err);
        CHECK(sl_harness_render(h, img), "strength 0: render");
        CHECK(max_diff(img, ref) <= 1e-5, "strength 0 differs from off (max %g)", max_diff(img, ref));
        free(img);
        sl_harness_destroy(h);
    }
    free(on), free(ref);

    /* far occluder: the ball's nearest point is 0.9 m (1.8 radii) from the wall, so no sample
     * point of a wall pixel is inside anything: visibility 1 on every wall pixel. Without a range
     * check (or with one that still weights an occluder 2.4 radii in front, as
     * smoothstep(0, 1, radius/|dz|) does by 0.35) the ball draws a dark halo on the wall around
     * its silhouette, the samples that land on it being behind its depth. */
    {
        on = render(far_ball, NULL), ref = render(far_ball, off);
        visibility(on, ref, v);
        float least = 1;
        int wall = 0;
        for (int i = 0; i < W * H; i++)
            if (ref[i * 4] > 0.1f) least = fminf(least, v[i]), wall++;
        CHECK(wall > W * H / 2 && least > 0.99f, "far occluder: a wall pixel darkened to %.3f (%d wall pixels)", least,
              wall);
        printf("far occluder: least visibility on the wall %.4f (%d pixels)\n", least, wall);
        free(on), free(ref);
    }

    /* direct light only (no environment): untouched */
    snprintf(scene, sizeof scene, corner, "0", sun);
    on = render(scene, NULL), ref = render(scene, off);
    CHECK(max_diff(on, ref) <= 1e-5, "direct light: ssao changed it (max diff %g)", max_diff(on, ref));
    float lit = 0;
    for (int i = 0; i < W * H; i++) lit = fmaxf(lit, ref[i * 4 + 1]);
    CHECK(lit > 0.1f, "direct light: the scene is dark (%g)", lit);
    free(on), free(ref);

    /* the "normal" target and the depth pre-pass */
    {
        /* the camera looks along f = normalize(target - position) with +Y up: the view's axes are
         * right (1, 0, 0), up (0, -f.z, f.y) and back -f, so the floor's normal (0, 1, 0) is
         * (0, -f.z, -f.y) in view space and the wall's (0, 0, 1) is (0, f.y, -f.z) */
        snprintf(scene, sizeof scene, corner, "1", "");
        double fy = 0.4 - 2.2, fz = 0.4 - 4.2, fl = sqrt(fy * fy + fz * fz);
        fy /= fl, fz /= fl;
        const double want[2][3] = {{0, fy, -fz}, {0, -fz, -fy}}; /* wall (row 2), floor (row H - 3) */
        const int rows[2] = {2, H - 3};
        sl_harness *h = open_harness(scene, NULL);
        char err[512];
        static float display[W * H * 4];
        CHECK(sl_harness_set_debug_view(h, "ssao-normal", err, sizeof err), "%s", err);
        CHECK(sl_harness_render(h, NULL) && sl_harness_read_display(h, display), "normal view: render");
        double worst = 0;
        for (int k = 0; k < 2; k++)
            for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(display[(rows[k] * W + x) * 4 + c] - (0.5 + 0.5 * want[k][c])));
        CHECK(worst < 0.01, "normal view: the planes' view-space normals off by %.4f (shown n/2 + 1/2)", worst);
        printf("normal view: wall and floor normals as expected within %.4f\n", worst);
        sl_harness_structure st;
        sl_harness_structure_of(h, &st);
        bool prepass = false;
        for (int i = 0; i < st.pass_count; i++) prepass |= !strcmp(st.passes[i], "depth-prepass");
        CHECK(prepass, "ssao on: the core's depth-prepass did not run");
        sl_harness_destroy(h);
        h = open_harness(scene, off);
        CHECK(sl_harness_render(h, NULL), "ssao off: render");
        sl_harness_structure_of(h, &st);
        for (int i = 0; i < st.pass_count; i++)
            CHECK(strcmp(st.passes[i], "depth-prepass"), "ssao off: the core's depth-prepass still runs");
        sl_harness_destroy(h);
    }

    /* other lights. envmap's sky (its sun included, no light): the same visibility as the uniform
     * environment, for ssao scales whatever ambient light arrives */
    {
        const char *env_on[] = {"aa.enabled=false", "envmap.background=false", "envmap.cube_size=32",
                                "envmap.sun_elevation=30", "envmap.sun_azimuth=150", NULL};
        const char *env_off[] = {"aa.enabled=false", "envmap.background=false", "envmap.cube_size=32",
                                 "envmap.sun_elevation=30", "envmap.sun_azimuth=150", "ssao.enabled=false", NULL};
        corner_with(scene, sizeof scene, "\"envmap\"", "1", "");
        on = render(scene, env_on), ref = render(scene, env_off);
        visibility(on, ref, v);
        double worst = 0;
        int rows = 0;
        for (int y = 0; y < H; y++)
            if (v_ambient[y * W + x] > 0) worst = fmax(worst, fabs(v[y * W + x] - v_ambient[y * W + x])), rows++;
        CHECK(rows > H / 2 && worst < 0.01, "envmap: visibility differs from the uniform environment's by %.4f (%d rows)",
              worst, rows);
        CHECK(v[crease * W + x] < 0.62f, "envmap: crease not darkened (%.3f)", v[crease * W + x]);
        printf("envmap: crease %.3f, the uniform environment's visibility within %.4f on %d rows\n", v[crease * W + x],
               worst, rows);
        free(on), free(ref);
    }
    /* a shadowed spot, and a rectangle area light: direct light, untouched */
    {
        struct { const char *name, *plugin, *light; } direct[] = {
            {"spotlight-shadow", "\"spotlight-shadow\"",
             ",\n \"lights\": [{\"name\": \"spot\", \"type\": \"spot\", \"position\": [1.5, 3.5, 3.0], \"direction\": [-0.3, -0.75, -0.6],"
             " \"intensity\": 30, \"cone_angle\": 40, \"cast_shadows\": true}]"},
#ifdef SSAO_AREA_LIGHT
            {"area-light", "\"area-light\"",
             ",\n \"lights\": [{\"name\": \"box\", \"type\": \"area\", \"position\": [0, 2.0, 2.5], \"direction\": [0, -0.6, -0.8],"
             " \"intensity\": 8, \"width\": 2, \"height\": 1, \"axis\": [1, 0, 0]}]"},
#endif
        };
        const char *plain_on[] = {"aa.enabled=false", NULL}, *plain_off[] = {"aa.enabled=false", "ssao.enabled=false", NULL};
        for (size_t k = 0; k < sizeof direct / sizeof *direct; k++) {
            corner_with(scene, sizeof scene, direct[k].plugin, "0", direct[k].light);
            on = render(scene, plain_on), ref = render(scene, plain_off);
            float lit = 0;
            for (int i = 0; i < W * H; i++) lit = fmaxf(lit, ref[i * 4 + 1]);
            CHECK(max_diff(on, ref) <= 1e-5 && lit > 0.05f, "%s: ssao changed its light (max diff %g; peak %g)",
                  direct[k].name, max_diff(on, ref), lit);
            printf("%s: ssao on - off max diff %g (peak %.3f)\n", direct[k].name, max_diff(on, ref), lit);
            free(on), free(ref);
        }
#ifndef SSAO_AREA_LIGHT
        printf("area-light: skipped (built out of tree: area-light, an extra, is not installed)\n");
#endif
    }
    /* aa's TAA on (its jittered projection reaches the pre-pass and the pass): still about 1/2 */
    {
        const char *aa_on[] = {"aa.method=taa", NULL}, *aa_off[] = {"aa.method=taa", "ssao.enabled=false", NULL};
        corner_with(scene, sizeof scene, "\"aa\"", "1", "");
        on = render(scene, aa_on), ref = render(scene, aa_off);
        visibility(on, ref, v);
        float c = v[crease * W + x];
        for (int y = crease - 1; y <= crease + 1; y++) c = fminf(c, v[y * W + x]);
        CHECK(c > 0.40f && c < 0.62f && fabsf(v[2 * W + x] - 1) < 1e-3f, "aa: crease %.3f, far %.4f", c, v[2 * W + x]);
        printf("aa: crease %.3f, far %.4f\n", c, v[2 * W + x]);
        free(on), free(ref);
    }

    if (failures) { printf("%d check(s) failed\n", failures); return 1; }
    printf("ssao: open plane, corner, direct light, live changes, the pass views and other lights match\n");
    return 0;
}
