/* many-lights tests (headless, llvmpipe). Every method against the brute-force loop with the same
 * cut-off, for the lambert and ggx models, point and spot lights, at two animation frames; the
 * lights each tile/froxel sees for known cells against a count made here on the CPU with this
 * file's own camera, ray casting and sphere-box code (the plugin's culling code is not used);
 * epsilon = 0 against the core's own light loop (no plugin); off costs nothing; live equals fresh;
 * hostile values. */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;
#define CHECK(c, ...) do { if (!(c)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

enum { W = 160, H = 96, NL = 64 };
static const float EPS = 0.01f;
static const float CAM_POS[3] = {0, 6, 9}, CAM_TARGET[3] = {0, 0, 0}, FOV_Y = 50, ZN = 0.05f, ZF = 100;

/* the fixed 64-light scene: 56 point and 8 spot lights on a jittered 8×8 grid, a dim sun */
typedef struct tl { float pos[3], color[3], I; bool spot; } tl;
static tl lights[NL];
static bool hostile; /* adds a light on the ground, one behind the camera reaching past the near plane, a black one */

static char *scene_json(void) {
    static char buf[65536];
    int n = snprintf(buf, sizeof buf,
        "{ \"cameras\": [{\"name\": \"main\", \"position\": [%g, %g, %g], \"target\": [%g, %g, %g], \"fov_y\": %g, "
        "\"near\": %g, \"far\": %g}],\n"
        "  \"environment\": {\"color\": [0, 0, 0], \"intensity\": 0},\n"
        "  \"materials\": [ {\"name\": \"ground\", \"base_color_map\": \"checker:8:0.8,0.8,0.8:0.4,0.4,0.4\"},\n"
        "    {\"name\": \"matte\", \"base_color\": [0.7, 0.5, 0.3]},\n"
        "    {\"name\": \"rough\", \"model\": \"ggx\", \"base_color\": [0.3, 0.5, 0.8], \"roughness\": 0.6},\n"
        "    {\"name\": \"glossy\", \"model\": \"ggx\", \"base_color\": [0.8, 0.2, 0.2], \"roughness\": 0.25} ],\n"
        "  \"nodes\": [ {\"name\": \"ground\", \"mesh\": {\"primitive\": \"plane\", \"size\": 14}, \"material\": \"ground\"},\n"
        "    {\"name\": \"box\", \"translate\": [0, 1, -3], \"mesh\": {\"primitive\": \"cube\", \"size\": 2}, \"material\": \"matte\"},\n"
        "    {\"name\": \"s1\", \"translate\": [-2.5, 0.6, -0.5], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6}, \"material\": \"rough\"},\n"
        "    {\"name\": \"s2\", \"translate\": [2.5, 0.6, -0.5], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6}, \"material\": \"glossy\"} ],\n"
        "  \"lights\": [ {\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.3, -1, -0.2], \"intensity\": 0.15}",
        CAM_POS[0], CAM_POS[1], CAM_POS[2], CAM_TARGET[0], CAM_TARGET[1], CAM_TARGET[2], FOV_Y, ZN, ZF);
    unsigned seed = 12345;
#define RND() ((seed = seed * 1103515245u + 12345u) >> 8 & 0xffff) / 65535.0f
    for (int i = 0; i < NL; i++) {
        tl *L = &lights[i];
        L->pos[0] = -6.1f + 12.2f * ((i % 8) + 0.2f + 0.6f * RND()) / 8;
        L->pos[2] = -6.1f + 12.2f * ((i / 8) + 0.2f + 0.6f * RND()) / 8;
        L->pos[1] = 0.25f + 1.2f * RND();
        L->color[0] = 0.4f + 0.6f * RND(), L->color[1] = 0.4f + 0.6f * RND(), L->color[2] = 0.4f + 0.6f * RND();
        L->I = 0.05f + 0.1f * RND();
        L->spot = i % 8 == 3;
        n += snprintf(buf + n, sizeof buf - n,
                      ",\n    {\"name\": \"l%d\", \"type\": \"%s\", \"position\": [%.4f, %.4f, %.4f], \"color\": [%.4f, %.4f, %.4f], "
                      "\"intensity\": %.4f%s%s}",
                      i, L->spot ? "spot" : "point", L->pos[0], L->pos[1], L->pos[2], L->color[0], L->color[1], L->color[2],
                      L->I, L->spot ? ", \"direction\": [0.2, -1, 0.1], \"cone_angle\": 50" : "",
                      i % 5 == 0 ? ", \"animate\": \"orbit\", \"animate_speed\": 0.4" : "");
    }
    if (hostile)
        n += snprintf(buf + n, sizeof buf - n,
                      ",\n    {\"name\": \"on_ground\", \"type\": \"point\", \"position\": [0.5, 0, 2], \"intensity\": 0.05},\n"
                      "    {\"name\": \"behind\", \"type\": \"point\", \"position\": [0.3, 6.3, 9.6], \"intensity\": 2},\n"
                      "    {\"name\": \"black\", \"type\": \"point\", \"position\": [1, 1, 1], \"intensity\": 0}");
    snprintf(buf + n, sizeof buf - n, " ]\n}\n");
    return buf;
}

static sl_harness *make(const char *const *settings, bool with_plugin) {
    char err[4096];
    const char *with[] = {MANY_LIGHTS_PLUGIN, "ggx", "spotlight-shadow", NULL};
    const char *without[] = {"ggx", "spotlight-shadow", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = scene_json(), .plugins = with_plugin ? with : without,
                                                         .settings = settings, .strict = true, .float32 = true},
                                      err, sizeof err);
    if (!h) { printf("harness: %s\n", err); exit(1); }
    char v[64];
    if (sl_harness_get(h, "aa.enabled", v, sizeof v)) sl_harness_set(h, "aa.enabled=false", err, sizeof err);
    return h;
}

static void set(sl_harness *h, const char *a) {
    char err[1024];
    if (!sl_harness_set(h, a, err, sizeof err)) { printf("set %s: %s\n", a, err); failures++; }
}

static void render(sl_harness *h, uint64_t frame, float *img) {
    sl_harness_set_frame(h, frame);
    if (!sl_harness_render(h, img)) { printf("render failed\n"); exit(1); }
}

/* ---- the CPU side, written here: camera, ray casting against the ground, cells ---- */
static void sub(const float *a, const float *b, float *o) { for (int i = 0; i < 3; i++) o[i] = a[i] - b[i]; }
static void norm(float *v) { float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); for (int i = 0; i < 3; i++) v[i] /= l; }
static void cross3(const float *a, const float *b, float *o) {
    o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static float cam_f[3], cam_r[3], cam_u[3], tan_y, aspect;
static void camera(void) {
    sub(CAM_TARGET, CAM_POS, cam_f), norm(cam_f);
    const float up[3] = {0, 1, 0};
    cross3(cam_f, up, cam_r), norm(cam_r);
    cross3(cam_r, cam_f, cam_u);
    tan_y = tanf(FOV_Y * 0.5f * (float)M_PI / 180), aspect = (float)W / H;
}
/* view coordinates (x, y, d) of a world point */
static void to_view(const float *p, float *o) {
    float q[3];
    sub(p, CAM_POS, q);
    o[0] = dot3(q, cam_r), o[1] = dot3(q, cam_u), o[2] = dot3(q, cam_f);
}
/* view distance d of the ground (y = 0) seen through pixel centre (x, y from the bottom), or -1 */
static float ground_d(float px, float py) {
    float sx = (2 * px / W - 1) * tan_y * aspect, sy = (2 * py / H - 1) * tan_y, dir[3];
    for (int i = 0; i < 3; i++) dir[i] = cam_f[i] + sx * cam_r[i] + sy * cam_u[i];
    if (dir[1] >= 0) return -1;
    float t = -CAM_POS[1] / dir[1]; /* dir has f-component 1: t is the view distance */
    float hit[3] = {CAM_POS[0] + t * dir[0], 0, CAM_POS[2] + t * dir[2]};
    /* the objects: two spheres (with a margin for their tessellation) and the box */
    const float sph[2][3] = {{-2.5f, 0.6f, -0.5f}, {2.5f, 0.6f, -0.5f}};
    float dl = sqrtf(dot3(dir, dir)), u[3] = {dir[0] / dl, dir[1] / dl, dir[2] / dl};
    for (int k = 0; k < 2; k++) {
        float oc[3];
        sub(CAM_POS, sph[k], oc);
        float b = dot3(oc, u), c = dot3(oc, oc) - 0.65f * 0.65f;
        if (b * b - c >= 0) return -1;
    }
    float tmin = 0, tmax = INFINITY;
    const float bl[3] = {-1.05f, -0.05f, -4.05f}, bh[3] = {1.05f, 2.05f, -1.95f};
    for (int k = 0; k < 3; k++) {
        float t0 = (bl[k] - CAM_POS[k]) / u[k], t1 = (bh[k] - CAM_POS[k]) / u[k];
        if (t0 > t1) { float x = t0; t0 = t1, t1 = x; }
        tmin = fmaxf(tmin, t0), tmax = fminf(tmax, t1);
    }
    if (tmin <= tmax) return -1;
    return fabsf(hit[0]) < 7 && fabsf(hit[2]) < 7 ? t : -1;
}
/* A sphere holding the part of a spot's range sphere (apex p, radius r) that its cone lights:
 * the test scene's spots have cone_angle 50° with the linear fall-off, zero from 1.1·50° = 55° on
 * (conventions); with a = 56° > 45° the rim circle of the cap, centre p + r·cos(a)·axis and radius
 * r·sin(a), holds the apex (r·cos a < r·sin a) and the whole cap. */
static void spot_bound(const float *p, float r, float *c, float *R) {
    float axis[3] = {0.2f, -1, 0.1f}, a = 56 * (float)M_PI / 180;
    norm(axis);
    for (int k = 0; k < 3; k++) c[k] = p[k] + r * cosf(a) * axis[k];
    *R = r * sinf(a);
}
static float box_dist2(const float *c, const float *lo, const float *hi) {
    float s2 = 0;
    for (int k = 0; k < 3; k++) {
        float e = c[k] < lo[k] ? lo[k] - c[k] : c[k] > hi[k] ? c[k] - hi[k] : 0;
        s2 += e * e;
    }
    return s2;
}
/* lights whose range sphere meets the view-space box of pixels [x0,x1]×[y0,y1], distances
 * [d0,d1]; cone: a spot's cone bound (spot_bound) must meet it as well */
static int count_cell(float x0, float x1, float y0, float y1, float d0, float d1, bool cone) {
    float lo[3] = {INFINITY, INFINITY, d0}, hi[3] = {-INFINITY, -INFINITY, d1};
    float xs[2] = {(2 * x0 / W - 1) * tan_y * aspect, (2 * x1 / W - 1) * tan_y * aspect};
    float ys[2] = {(2 * y0 / H - 1) * tan_y, (2 * y1 / H - 1) * tan_y}, ds[2] = {d0, d1};
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            lo[0] = fminf(lo[0], xs[a] * ds[b]), hi[0] = fmaxf(hi[0], xs[a] * ds[b]);
            lo[1] = fminf(lo[1], ys[a] * ds[b]), hi[1] = fmaxf(hi[1], ys[a] * ds[b]);
        }
    int n = 0;
    for (int i = 0; i < NL; i++) {
        float c[3], s2 = 0;
        to_view(lights[i].pos, c);
        float I = fmaxf(lights[i].color[0], fmaxf(lights[i].color[1], lights[i].color[2])) * lights[i].I;
        float r2 = I / EPS;
        s2 = box_dist2(c, lo, hi);
        if (cone && lights[i].spot && s2 <= r2) {
            float w[3], v[3], R;
            spot_bound(lights[i].pos, sqrtf(r2), w, &R);
            to_view(w, v);
            s2 = box_dist2(v, lo, hi) <= R * R ? s2 : INFINITY;
        }
        n += s2 <= r2;
    }
    return n;
}

static double max_diff(const float *a, const float *b) {
    sl_compare c;
    sl_harness_compare(a, b, W, H, 1.0 / 255, &c);
    return c.nonfinite ? INFINITY : c.max_abs;
}

int main(void) {
    camera();
    char err[1024];
    float *ref = malloc(sizeof(float) * W * H * 4), *img = malloc(sizeof(float) * W * H * 4);
    static const char *const names[] = {"brute", "deferred", "tiled", "clustered"};

    /* 1. every method equals brute force with the same cut-off (lambert, ggx; points, spots; two frames) */
    const char *s_eps[] = {"many-lights.epsilon=0.01", "many-lights.method=brute", NULL};
    sl_harness *h = make(s_eps, true);
    for (int f = 0; f < 2; f++) {
        uint64_t frame = f ? 7 : 0;
        set(h, "many-lights.method=brute");
        render(h, frame, ref);
        double peak = 0;
        for (int i = 0; i < W * H * 4; i++) if (i % 4 != 3 && ref[i] > peak) peak = ref[i];
        CHECK(peak > 0.2 && sl_harness_count_nonfinite(ref, W, H) == 0, "brute: peak %.3f", peak);
        for (int m = 1; m < 4; m++) {
            char a[96];
            snprintf(a, sizeof a, "many-lights.method=%s", names[m]);
            set(h, a);
            render(h, frame, img);
            double d = max_diff(ref, img);
            printf("frame %2d: %-9s vs brute: max |diff| %.2e (peak %.3f)\n", (int)frame, names[m], d, peak);
            CHECK(d <= 1.0 / 255, "%s differs from brute force by %.4f", names[m], d);
        }
    }
    /* the cut-off does cut: epsilon 0.01 vs 0 differ somewhere, by at most the cut-off's bound */
    set(h, "many-lights.method=brute");
    set(h, "many-lights.epsilon=0");
    render(h, 0, img);
    render(h, 0, ref); /* deterministic */
    set(h, "many-lights.epsilon=0.01");
    float *cut = malloc(sizeof(float) * W * H * 4);
    render(h, 0, cut);
    double dcut = max_diff(ref, cut);
    printf("epsilon 0.01 vs no cut-off: max |diff| %.4f\n", dcut);
    CHECK(dcut > 1e-4, "the cut-off changes nothing (%.2e)", dcut);

    /* 2. culling culls: lights per cell against the count made here, spots culled by their range
     * sphere only (spot_cone off: then every light within range of the pixel must be listed), and
     * by their cone as well (on, the default; the images above were made with it) */
    int cone_fewer = 0;
    char e2[256];
    for (int cone = 0; cone < 2; cone++) {
    set(h, cone ? "many-lights.spot_cone=true" : "many-lights.spot_cone=false");
    set(h, "many-lights.method=clustered");
    set(h, "many-lights.cluster_tile=16");
    set(h, "many-lights.cluster_slices=16");
    if (!sl_harness_set_debug_view(h, "many-lights-count", e2, sizeof e2)) { printf("debug view: %s\n", e2); return 1; }
    render(h, 0, img);
    /* froxel near/far from the scene bounds [-7,0,-7]..[7,2,7] (ml_cull.h) */
    float dmin = INFINITY, dmax = 0;
    for (int k = 0; k < 8; k++) {
        float p[3] = {k & 1 ? 7.f : -7.f, k & 2 ? 2.f : 0.f, k & 4 ? 7.f : -7.f}, q[3];
        to_view(p, q);
        dmin = fminf(dmin, q[2]), dmax = fmaxf(dmax, q[2]);
    }
    float nd = fminf(fmaxf(dmin, 0.1f), 0.5f * dmax), S = 16, T = 16;
    int checked = 0, culled = 0;
    const int probe[][2] = {{8, 8}, {40, 20}, {72, 30}, {120, 10}, {150, 40}, {24, 45}, {100, 45}, {136, 24}};
    for (size_t p = 0; p < sizeof probe / sizeof *probe; p++) {
        int x = probe[p][0], y = probe[p][1]; /* from the bottom */
        float d = ground_d(x + 0.5f, y + 0.5f);
        if (d < 0) continue;
        int k = (int)floorf(logf(d / nd) * S / logf(dmax / nd));
        k = k < 0 ? 0 : k > S - 1 ? S - 1 : k;
        int tx = x / (int)T, ty = y / (int)T;
        /* the froxel is culled for the distances of the samples in it (the pre-pass's), widened
         * by 1e-4: here the ground's under the tile's pixels in slice k; a tile with an object
         * pixel is left out */
        float d0 = INFINITY, d1 = 0;
        bool ground = true;
        for (int py = ty * (int)T; py < (ty + 1) * (int)T && py < H; py++)
            for (int qx = tx * (int)T; qx < (tx + 1) * (int)T && qx < W; qx++) {
                float e = ground_d(qx + 0.5f, py + 0.5f);
                ground &= e > 0;
                int ke = e > 0 ? (int)floorf(logf(e / nd) * S / logf(dmax / nd)) : -1;
                ke = ke < 0 ? 0 : ke > S - 1 ? S - 1 : ke;
                if (e > 0 && ke == k) d0 = fminf(d0, e), d1 = fmaxf(d1, e);
            }
        if (!ground) continue;
        d0 *= 1 - 1e-4f, d1 *= 1 + 1e-4f;
        int want = count_cell(tx * T, fminf((tx + 1) * T, W), ty * T, fminf((ty + 1) * T, H), d0, d1, cone);
        cone_fewer += cone && want < count_cell(tx * T, fminf((tx + 1) * T, W), ty * T, fminf((ty + 1) * T, H), d0, d1, 0);
        const float *px = img + 4 * ((size_t)(H - 1 - y) * W + x);
        printf("spot_cone %d: froxel (%d,%d,%d) at pixel (%d,%d): %g lights listed, %d counted here, %g within range, %g ranged\n",
               cone, tx, ty, k, x, y, px[0], want, px[1], px[2]);
        CHECK((int)px[0] == want, "froxel (%d,%d,%d): %g listed, %d expected", tx, ty, k, px[0], want);
        CHECK(cone || px[1] <= px[0], "froxel (%d,%d,%d): a light within range is not listed", tx, ty, k);
        checked++, culled += px[0] < NL;
    }
    CHECK(checked >= 5 && culled == checked, "froxels checked %d, culled %d", checked, culled);
    /* tiles: depth bounds of the ground under a 16×16 tile wholly on the ground */
    set(h, "many-lights.method=tiled");
    render(h, 0, img);
    checked = 0;
    const int tprobe[][2] = {{0, 0}, {2, 1}, {4, 0}, {9, 1}, {7, 2}};
    for (size_t p = 0; p < sizeof tprobe / sizeof *tprobe; p++) {
        int tx = tprobe[p][0], ty = tprobe[p][1];
        float lo = INFINITY, hi = 0;
        bool ground = true;
        for (int y = ty * 16; y < ty * 16 + 16 && y < H; y++)
            for (int x = tx * 16; x < tx * 16 + 16 && x < W; x++) {
                float d = ground_d(x + 0.5f, y + 0.5f);
                ground &= d > 0;
                lo = fminf(lo, d), hi = fmaxf(hi, d);
            }
        if (!ground) continue;
        /* no object over the tile either: the ground's colour count must match at every pixel */
        int want = count_cell(tx * 16, fminf(tx * 16 + 16, W), ty * 16, fminf(ty * 16 + 16, H), lo, hi, cone);
        const float *px = img + 4 * ((size_t)(H - 1 - (ty * 16 + 8)) * W + tx * 16 + 8);
        printf("spot_cone %d: tile (%d,%d) depth %.3f..%.3f: %g lights listed, %d counted here, %g within range\n", cone, tx, ty, lo, hi, px[0],
               want, px[1]);
        CHECK((int)px[0] == want && px[0] < NL, "tile (%d,%d): %g listed, %d expected", tx, ty, px[0], want);
        checked++;
    }
    CHECK(checked >= 3, "tiles checked %d", checked);
    sl_harness_set_debug_view(h, NULL, e2, sizeof e2);
    }
    CHECK(cone_fewer > 0, "the spot cones cull nothing at the probed froxels");

    /* stability: a light on the surface, one behind the camera straddling the near plane (no
     * screen rectangle: every tile), a black light (range 0); epsilon tiny (huge ranges) and 1
     * (ranges of centimetres): every method finite and equal to brute force */
    sl_harness_destroy(h);
    hostile = true;
    h = make(s_eps, true);
    const char *const eps_cases[] = {"many-lights.epsilon=0.01", "many-lights.epsilon=0.0001", "many-lights.epsilon=1"};
    for (int e = 0; e < 3; e++) {
        set(h, eps_cases[e]);
        set(h, "many-lights.method=brute");
        render(h, 2, ref);
        CHECK(sl_harness_count_nonfinite(ref, W, H) == 0 && sl_harness_count_negative(ref, W, H) == 0,
              "%s: brute force not finite", eps_cases[e]);
        for (int m = 1; m < 4; m++) {
            char a2[96];
            snprintf(a2, sizeof a2, "many-lights.method=%s", names[m]);
            set(h, a2);
            render(h, 2, img);
            double d = max_diff(ref, img);
            printf("stability %s: %-9s vs brute: max |diff| %.2e\n", eps_cases[e], names[m], d);
            CHECK(d <= 1.0 / 255, "stability %s: %s differs by %.4f", eps_cases[e], names[m], d);
        }
    }
    sl_harness_destroy(h);
    hostile = false;
    h = make(s_eps, true);

    /* 3. live equals fresh: method and epsilon changed live vs a harness started with them */
    set(h, "many-lights.method=tiled");
    set(h, "many-lights.epsilon=0.02");
    render(h, 3, img);
    sl_harness_destroy(h);
    const char *s_fresh[] = {"many-lights.method=tiled", "many-lights.epsilon=0.02", NULL};
    h = make(s_fresh, true);
    render(h, 3, ref);
    CHECK(max_diff(ref, img) == 0, "live vs fresh differ by %.2e", max_diff(ref, img));
    /* hostile values: refused with a message, nothing changes */
    CHECK(!sl_harness_set(h, "many-lights.epsilon=-1", err, sizeof err), "epsilon -1 accepted");
    CHECK(!sl_harness_set(h, "many-lights.method=nope", err, sizeof err), "method nope accepted");
    CHECK(!sl_harness_set(h, "many-lights.tile_size=0", err, sizeof err), "tile_size 0 accepted");
    sl_harness_destroy(h);

    /* 4. epsilon 0 with brute force equals the core's own loop (no plugin); off costs nothing */
    const char *s_zero[] = {"many-lights.method=brute", "many-lights.epsilon=0", NULL};
    h = make(s_zero, true);
    render(h, 0, img);
    set(h, "many-lights.enabled=false");
    render(h, 0, cut);
    sl_harness_structure off;
    sl_harness_structure_of(h, &off);
    sl_harness_destroy(h);
    h = make(NULL, false);
    render(h, 0, ref);
    sl_harness_structure none;
    sl_harness_structure_of(h, &none);
    sl_harness_destroy(h);
    double dz = max_diff(ref, img);
    printf("epsilon 0 brute vs the core's loop: max |diff| %.2e\n", dz);
    CHECK(dz <= 1e-5, "epsilon 0 differs from the core loop by %.2e", dz);
    CHECK(sl_harness_structure_equal(&off, &none), "switched off differs from not loaded (structure)");
    CHECK(max_diff(ref, cut) == 0, "switched off differs from not loaded (image)");

    free(ref), free(img), free(cut);
    printf(failures ? "%d failure(s)\n" : "all passed\n", failures);
    return failures != 0;
}
