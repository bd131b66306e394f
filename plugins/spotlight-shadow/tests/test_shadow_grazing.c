/* A shadowed cheek (issue 42: lit triangles inside the nose's shadow, with sss wrap): a "head"
 * (sphere of radius 1, finely tessellated, so that some facets are lit within a degree of edge-on)
 * and a "nose" (sphere of radius 0.3 grown out of its front); the light comes from the side, so
 * the nose's shadow falls across the head's terminator, on facets lit at grazing incidence and on
 * facets facing away. The model is wrap-lit (tests/wrap_lit.c: k_d/π·E·(1 + n·l)/2), so shadowed /
 * unshadowed is the visibility on all of them, as sss's wrap shows it. Spot and directional
 * light, every filter:
 *   umbra: head pixels whose segment to the light passes 0.06 or more inside the nose's silhouette
 *     (the penumbra's bound: wider than every filter's kernel here) and whose receiver lies 0.15
 *     or more behind the nose (over 60 texel widths; the biases reach less than that once the
 *     receiver point is known to be shadowed) have visibility below 0.02;
 *   lit: head pixels facing the light (n·l > 0.2) whose segment passes 0.06 clear of the nose
 *     have visibility above 0.999 (no acne on the curved receiver);
 *   the measurement sees a leak: a constant bias of 1000 texels lights the umbra. */
#include "shadow_test.h"

#define W 128
#define H 96
static float img[W * H * 4], lit[W * H * 4];

static const test_camera cam = {{0, 0.25f, 4}, {-0.1f, 0, 0.8f}, 30, W, H};
static const double nose[3] = {0.35, 0, 1.0}, nose_r = 0.3;
static const double margin = 0.06, behind = 0.15;

#define SCENE_HEAD \
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0.25, 4], \"target\": [-0.1, 0, 0.8], \"fov_y\": 30}],\n" \
    " \"materials\": [{\"name\": \"skin\", \"model\": \"ss-wrap-lit\", \"base_color\": [0.7, 0.7, 0.7]}],\n" \
    " \"nodes\": [{\"name\": \"head\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 384, \"rings\": 192}, \"material\": \"skin\"},\n" \
    "           {\"name\": \"nose\", \"translate\": [0.35, 0, 1.0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.3}, \"material\": \"skin\"}],\n"

typedef struct light_case {
    const char *name, *json, *map_size;
    double pos[3]; /* spot position, or for directional: -direction (towards the light) */
    bool directional;
} light_case;

/* the light along (1, 0, 0.15) from (0, 0, 0.9): the head's terminator runs through the shadow */
static const light_case cases[] = {
    {"spot", " \"lights\": [{\"name\": \"L\", \"type\": \"spot\", \"position\": [5.934, 0, 1.790], \"direction\": [-1, 0, -0.15],"
             " \"intensity\": 36, \"cone_angle\": 15, \"radius\": 0.02, \"cast_shadows\": true}]}",
     "spotlight-shadow.map_size=2048", {5.934, 0, 1.790}, false},
    {"directional", " \"lights\": [{\"name\": \"L\", \"type\": \"directional\", \"direction\": [-1, 0, -0.15], \"intensity\": 1,"
                    " \"angular_radius\": 0.2, \"cast_shadows\": true}]}",
     "spotlight-shadow.map_size=1024", {1, 0, 0.15}, true},
};

/* Nearest hit of the pixel's ray with a sphere; -1 when missed. */
static double ray_sphere(const float *o, const float *d, const double *c, double r) {
    double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]}, dd[3] = {d[0], d[1], d[2]};
    double b = ss_dot(oc, dd), q = ss_dot(oc, oc) - r * r, disc = b * b - q;
    if (disc < 0) return -1;
    double t = -b - sqrt(disc);
    return t > 0 ? t : -1;
}

typedef struct classes {
    int umbra, umbra_grazing, umbra_facing_away, umbra_bright, lit;
    double umbra_max, lit_min;
    int umbra_max_x, umbra_max_y;
} classes;

static void classify(const light_case *lc, const float *sh, const float *un, classes *k) {
    memset(k, 0, sizeof *k);
    k->lit_min = 1;
    const double head[3] = {0, 0, 0};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float o[3], d[3];
            test_camera_ray(&cam, x, y, o, d);
            double th = ray_sphere(o, d, head, 1), tn = ray_sphere(o, d, nose, nose_r);
            if (th < 0 || (tn > 0 && tn < th)) continue; /* not the head, or the nose in front of it */
            double p[3], l[3], to[3];
            for (int i = 0; i < 3; i++) p[i] = o[i] + th * d[i];
            for (int i = 0; i < 3; i++) l[i] = lc->directional ? lc->pos[i] : lc->pos[i] - p[i];
            ss_normalize(l);
            for (int i = 0; i < 3; i++) to[i] = lc->directional ? p[i] + 100 * l[i] : lc->pos[i];
            int i = y * W + x;
            if (un[i * 4] < 1e-4) continue; /* outside the spot's cone */
            double n_dot_l = ss_dot(p, l), v = ss_ratio(sh, un, i);
            double dist = ss_segment_distance(p, to, nose);
            double cp[3] = {nose[0] - p[0], nose[1] - p[1], nose[2] - p[2]};
            double along = ss_dot(cp, l); /* distance from p to where the ray passes the nose's centre */
            if (dist < nose_r - margin && along - sqrt(nose_r * nose_r - dist * dist) > behind) {
                k->umbra++;
                k->umbra_grazing += fabs(n_dot_l) < 0.1;
                k->umbra_facing_away += n_dot_l < 0;
                k->umbra_bright += v >= 0.02;
                if (v > k->umbra_max) {
                    k->umbra_max = v;
                    k->umbra_max_x = x;
                    k->umbra_max_y = y;
                }
            } else if (dist > nose_r + margin && n_dot_l > 0.2) {
                k->lit++;
                if (v < k->lit_min) k->lit_min = v;
            }
        }
}

int main(void) {
    char json[4096];
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        snprintf(json, sizeof json, SCENE_HEAD "%s", cases[c].json);
        char err[8192];
        sl_harness *h = sl_harness_create(
            &(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H, .scene_json = json,
                               .float32 = true, .strict = true, .settings = (const char *[]){cases[c].map_size, NULL},
                               .plugins = (const char *[]){"spotlight-shadow", SS_WRAP_LIT_PATH, NULL}},
            err, sizeof err);
        CHECK_MSG(h != NULL, "harness: %s", err);
        if (!h) continue;
        /* the unshadowed image does not depend on the filter */
        CHECK(ss_set(h, "spotlight-shadow.shadows=false") && sl_harness_render(h, lit));
        CHECK(ss_set(h, "spotlight-shadow.shadows=true"));
        classes k;
        for (int f = 0; f < 4; f++) {
            CHECK(ss_set(h, "spotlight-shadow.filter=%s", ss_filters[f]) && sl_harness_render(h, img));
            classify(&cases[c], img, lit, &k);
            printf("%-11s %-7s umbra: %4d px (%d within 0.1 of edge-on, %d facing away), %d at 0.02 or more, brightest "
                   "%.4f at (%d, %d); lit: %4d px, darkest %.6f\n",
                   cases[c].name, ss_filters[f], k.umbra, k.umbra_grazing, k.umbra_facing_away, k.umbra_bright, k.umbra_max,
                   k.umbra_max_x, k.umbra_max_y, k.lit, k.lit_min);
            CHECK_MSG(k.umbra > 150 && k.umbra_grazing > 40 && k.umbra_facing_away > 20 && k.lit > 1000,
                      "%s/%s: too few classified pixels", cases[c].name, ss_filters[f]);
            CHECK_MSG(k.umbra_max < 0.02, "%s/%s: lit pixels in the umbra (visibility %.4f at %d, %d)", cases[c].name,
                      ss_filters[f], k.umbra_max, k.umbra_max_x, k.umbra_max_y);
            CHECK_MSG(k.lit_min > 0.999, "%s/%s: acne on the lit side (visibility %.6f)", cases[c].name, ss_filters[f],
                      k.lit_min);
            CHECK(sl_harness_count_nonfinite(img, W, H) == 0 && sl_harness_count_negative(img, W, H) == 0);
        }
        /* a lookup moved 1000 texels towards the light passes the nose: the measurement sees it */
        CHECK(ss_set(h, "spotlight-shadow.filter=pcf") && ss_set(h, "spotlight-shadow.bias_constant=1000") &&
              sl_harness_render(h, img));
        classify(&cases[c], img, lit, &k);
        printf("%-11s constant bias 1000 texels: umbra brightest %.4f\n", cases[c].name, k.umbra_max);
        CHECK_MSG(k.umbra_max > 0.5, "%s: a leaking bias was not detected (%.4f)", cases[c].name, k.umbra_max);
        sl_harness_destroy(h);
    }
    return check_result();
}
