/* The exporter against closed forms (issue 40 item 2): small scenes whose Cycles image has a
 * known value, rendered through shadelab-xcheck --reference-only. What is checked is the export
 * (units, axes, cameras, lights, the environment's orientation), not Cycles: each expected value
 * is derived here from the scene's own numbers and shadelab's documented conventions.
 *
 *   sun        Lambert plane under a sun at 40°: L = ρ·E·cos θ / π
 *   furnace    Lambert sphere in a uniform environment: L = ρ·L_env (a convex object)
 *   unoccluded the furnace sphere over a black ground (--unoccluded): still ρ·L_env, the ground
 *              neither occludes nor shadows it; the full path-traced scene (the default) is darker
 *              by the ground's occlusion, so the option is what makes the figure; the export
 *              carries the option as scene.json's render.object_rays ("camera"; absent without it)
 *   point      point light over a plane, perspective camera: L = ρ/π · I·h / d³
 *   spot       spots over a plane (linear and glTF fall-off, one tilted): L = ρ/π · I·f(θ)·cos θ_i / d²
 *   sky-sun    the procedural sky's sun disk seen through a narrow camera: its energy (E) and its
 *              edge (each pixel's share of the disk, box-filtered)
 *   sky-sun-lit what the same disk adds to a Lambert plane: ρ/π · (E/Ω) · π sin²r · cos θc
 *   mirror     mirror sphere in a lat-long whose colour is a linear function of the direction, in
 *              Blender's orientation (u = ½ at +X growing towards +Z, v = 0 up), turned by yaw
 *   gltf-quad  an animated glTF quad opened directly (Blender's importer): its edges where the
 *              spec's projection puts them at time 0 through the file's camera
 *   unmapped   a ggx layer set on a material (clear coat) is listed as not cross-checked, naming
 *              the key and the material; a layer key at its default is not (no Blender needed)
 *
 * Blender missing: exit 77 (skipped), said on stderr. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "camera_rays.h"
#include "test_tmp.h"
#include "toolkit.h"

#define W 64
#define H 64
#define SKIP 77

static const double PI = 3.14159265358979323846;

typedef struct render {
    sl_image img, index;
} render;

static void write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    if (!f || fputs(text, f) < 0) { fprintf(stderr, "cannot write %s\n", path); exit(1); }
    fclose(f);
}

/* Renders the scene file `scene` with Cycles through shadelab-xcheck (with the options `extra`);
 * exits 77 when Blender is missing. */
static bool cycles_file(const char *name, const char *scene, int samples, const char *extra, render *r) {
    char path[4200], out[4096], cmd[9000];
    snprintf(out, sizeof out, "%s/%s", sl_test_dir(), name);
    snprintf(cmd, sizeof cmd, "'%s' --reference-only %s --size %dx%d --samples %d --out '%s' '%s'", SL_XCHECK_EXE, extra,
             W, H, samples, out, scene);
    int status = system(cmd);
    if (WIFEXITED(status) && WEXITSTATUS(status) == SKIP) {
        fprintf(stderr, "SKIPPED: Blender is not installed (tools/install-deps.sh --with-tests installs it)\n");
        exit(SKIP);
    }
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s: shadelab-xcheck failed (%d)", name, status);
    char err[1024];
    snprintf(path, sizeof path, "%s/cycles.exr", out);
    bool ok = sl_image_load(&r->img, path, err, sizeof err);
    snprintf(path, sizeof path, "%s/index.exr", out);
    ok = ok && sl_image_load(&r->index, path, err, sizeof err);
    CHECK_MSG(ok, "%s: %s", name, err);
    return ok;
}

/* The same for scene text, written to NAME.json. */
static bool cycles_with(const char *name, const char *scene, int samples, const char *extra, render *r) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.json", sl_test_dir(), name);
    write_text(path, scene);
    return cycles_file(name, path, samples, extra, r);
}

static bool cycles(const char *name, const char *scene, int samples, render *r) {
    return cycles_with(name, scene, samples, "", r);
}

static void free_render(render *r) {
    sl_image_free(&r->img);
    sl_image_free(&r->index);
}

/* The world point an orthographic camera at (0, 0, 5) looking down −Z sees at pixel (x, y), on z = 0. */
static void ortho_point(int x, int y, double ymag, double p[3]) {
    p[0] = (2 * (x + 0.5) / W - 1) * ymag * W / H;
    p[1] = (1 - 2 * (y + 0.5) / H) * ymag;
    p[2] = 0;
}

/* The same for a perspective camera there (vertical field of view fov_deg). */
static void perspective_point(int x, int y, double fov_deg, double p[3]) {
    double t = tan(fov_deg * PI / 360);
    p[0] = 5 * (2 * (x + 0.5) / W - 1) * t * W / H;
    p[1] = 5 * (1 - 2 * (y + 0.5) / H) * t;
    p[2] = 0;
}

typedef double (*closed_form)(const double p[3], int channel, void *user);

/* Compares the image with the closed form over the pixels of object `index` (−1: all) whose
 * expected value is at least `floor` (a closed form returns −1 where it makes no claim): the
 * relative difference of the means (the 1 %), the relative RMS difference (where in the
 * image the light falls: a mirrored or turned export keeps the mean but not this) and the worst
 * pixel, relative to the mean (pixel filters at steep gradients allowed for). */
static void compare(const char *name, const render *r, int index, closed_form f, void *user, bool perspective,
                    double view, double floor, double mean_tol, double rms_tol, double pixel_tol) {
    double sum_e = 0, sum_c = 0, sum_e2 = 0, sum_d2 = 0, worst = 0;
    long count = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t px = ((size_t)y * W + x) * 4;
                if (index >= 0 && lroundf(r->index.pixels[px]) != index) continue;
                double p[3];
                if (perspective) perspective_point(x, y, view, p);
                else ortho_point(x, y, view, p);
                for (int c = 0; c < 3; c++) {
                    double e = f(p, c, user), v = r->img.pixels[px + c];
                    if (e < floor || e < 0) continue;
                    if (pass == 0) {
                        sum_e += e, sum_c += v, sum_e2 += e * e, sum_d2 += (v - e) * (v - e);
                        count++;
                    } else {
                        worst = fmax(worst, fabs(v - e) / (sum_e / count));
                    }
                }
            }
    double rel = count ? sum_c / sum_e - 1 : NAN, rms = count ? sqrt(sum_d2 / sum_e2) : NAN;
    printf("%-12s %6ld values  mean: Cycles %.5f, closed form %.5f (%+.3f %%)  rel-RMS %.3f %%  worst %.2f %% of the "
           "mean\n",
           name, count, count ? sum_c / count : 0, count ? sum_e / count : 0, 100 * rel, 100 * rms, 100 * worst);
    CHECK_MSG(count > 100, "%s: only %ld values compared", name, count);
    CHECK_MSG(fabs(rel) <= mean_tol, "%s: mean %+.4f %% off (tolerance %.2f %%)", name, 100 * rel, 100 * mean_tol);
    CHECK_MSG(rms <= rms_tol, "%s: relative RMS %.4f %% (tolerance %.2f %%)", name, 100 * rms, 100 * rms_tol);
    CHECK_MSG(worst <= pixel_tol, "%s: worst pixel %.4f of the mean off (tolerance %.3f)", name, worst, pixel_tol);
}

/* ---- sun --------------------------------------------------------------------------------- */

static double sun_form(const double p[3], int c, void *u) {
    (void)p, (void)c, (void)u;
    return 0.5 * 3.0 * cos(40 * PI / 180) / PI;
}

/* ---- furnace ----------------------------------------------------------------------------- */

static double furnace_sphere(const double p[3], int c, void *u) {
    (void)c, (void)u;
    return p[0] * p[0] + p[1] * p[1] < 0.9 * 0.9 ? 0.8 : -1; /* inside the silhouette */
}

static double furnace_background(const double p[3], int c, void *u) {
    (void)c, (void)u;
    return p[0] * p[0] + p[1] * p[1] > 1.05 * 1.05 ? 1.0 : -1; /* clear of the silhouette */
}

/* ---- unoccluded -------------------------------------------------------------------------- */

/* The furnace sphere over a black ground plane just below it (seen edge-on by the camera). */
static const char *const OVER_GROUND =
    "{ \"cameras\": [{ \"type\": \"orthographic\", \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"ymag\": 1.5 }],\n"
    "  \"materials\": [{ \"name\": \"m\", \"base_color\": [0.8, 0.8, 0.8] }, { \"name\": \"black\", \"base_color\": [0, 0, 0] }],\n"
    "  \"nodes\": [{ \"name\": \"ball\", \"mesh\": { \"primitive\": \"sphere\", \"radius\": 1 }, \"material\": \"m\" },\n"
    "            { \"name\": \"ground\", \"translate\": [0, -1.02, 0], \"mesh\": { \"primitive\": \"plane\", \"size\": 8 }, \"material\": \"black\" }],\n"
    "  \"environment\": { \"color\": [1, 1, 1], \"intensity\": 1 } }\n";

/* scene.json's render.object_rays of `--export-only [extra]` of OVER_GROUND ("" when absent). */
static void exported_rays(const char *name, const char *extra, char *rays, size_t n) {
    char path[4096], out[4096], cmd[9000];
    snprintf(path, sizeof path, "%s/%s.json", sl_test_dir(), name);
    snprintf(out, sizeof out, "%s/%s", sl_test_dir(), name);
    write_text(path, OVER_GROUND);
    snprintf(cmd, sizeof cmd, "'%s' --export-only %s --out '%s' '%s' > /dev/null", SL_XCHECK_EXE, extra, out, path);
    int status = system(cmd);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s: shadelab-xcheck --export-only failed (%d)", name, status);
    snprintf(path, sizeof path, "%s/blender/scene.json", out);
    FILE *f = fopen(path, "rb");
    char text[1 << 16] = "";
    size_t k = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[k] = 0;
    cJSON *doc = cJSON_Parse(text);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(doc, "render"), "object_rays");
    CHECK_MSG(doc, "%s: %s is not readable JSON", name, path);
    snprintf(rays, n, "%s", cJSON_IsString(v) ? v->valuestring : "");
    cJSON_Delete(doc);
}

/* ---- what the exporter does not map ------------------------------------------------------ */

/* A ggx layer set on a material (clear coat here) is listed as not cross-checked, naming the key
 * and the material; a layer key at its default (anisotropy 0) is not, nor is a normal-mapped ggx
 * material. No Blender needed. */
static void unmapped_layer_case(void) {
    const char *scene =
        "{ \"plugins\": [\"ggx\", \"normal-map\"],\n"
        "  \"cameras\": [{ \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"fov_y\": 40 }],\n"
        "  \"materials\": [{ \"name\": \"coated\", \"model\": \"ggx\", \"roughness\": 0.5, \"clearcoat\": 1 },\n"
        "                { \"name\": \"plain\", \"model\": \"ggx\", \"roughness\": 0.5, \"anisotropy\": 0 },\n"
        "                { \"name\": \"bumpy\", \"model\": \"ggx\", \"roughness\": 0.5, \"normal_map\": \"waves:8:0.3:7\" }],\n"
        "  \"nodes\": [{ \"name\": \"a\", \"translate\": [-1, 0, 0], \"mesh\": { \"primitive\": \"sphere\" }, \"material\": \"coated\" },\n"
        "            { \"name\": \"b\", \"translate\": [1, 0, 0], \"mesh\": { \"primitive\": \"sphere\" }, \"material\": \"plain\" },\n"
        "            { \"name\": \"c\", \"translate\": [0, 1, 0], \"mesh\": { \"primitive\": \"sphere\" }, \"material\": \"bumpy\" }],\n"
        "  \"lights\": [{ \"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 1 }] }\n";
    char path[4096], out[4096], listing[4096], cmd[14000];
    snprintf(path, sizeof path, "%s/unmapped.json", sl_test_dir());
    snprintf(out, sizeof out, "%s/unmapped", sl_test_dir());
    snprintf(listing, sizeof listing, "%s/unmapped.txt", sl_test_dir());
    write_text(path, scene);
    snprintf(cmd, sizeof cmd, "'%s' --export-only --out '%s' '%s' > '%s'", SL_XCHECK_EXE, out, path, listing);
    int status = system(cmd);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "unmapped: shadelab-xcheck --export-only failed (%d)", status);
    FILE *f = fopen(listing, "rb");
    char text[1 << 14] = "";
    size_t k = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[k] = 0;
    CHECK_MSG(strstr(text, "not cross-checked: ggx's layers not mapped to Cycles: clearcoat (coated)\n"),
              "the clear coat is not listed as not cross-checked:\n%s", text);
    CHECK_MSG(!strstr(text, "plain)") && !strstr(text, "anisotropy"), "a layer key at its default is listed:\n%s", text);
    /* a normal-mapped ggx material is mapped as it is: normal-map bends grazing normals as Cycles'
     * Normal Map node does (docs/xcheck.md), so nothing is noted */
    CHECK_MSG(!strstr(text, "bumpy"), "the normal-mapped material is noted:\n%s", text);
}

/* The sphere's mean over its interior in the render (its closed form 0.8 where unoccluded). */
static double sphere_mean(const render *r) {
    double sum = 0;
    long count = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t px = ((size_t)y * W + x) * 4;
            double p[3];
            ortho_point(x, y, 1.5, p);
            if (lroundf(r->index.pixels[px]) != 1 || furnace_sphere(p, 0, NULL) < 0) continue;
            sum += r->img.pixels[px], count++;
        }
    return count ? sum / count : NAN;
}

static void unoccluded_case(void) {
    char rays[64];
    exported_rays("unoccluded-export", "--unoccluded", rays, sizeof rays);
    CHECK_MSG(!strcmp(rays, "camera"), "--unoccluded: render.object_rays is \"%s\", expected \"camera\"", rays);
    exported_rays("full-export", "", rays, sizeof rays);
    CHECK_MSG(!rays[0], "without --unoccluded: render.object_rays is \"%s\", expected none", rays);
    render r = {0};
    if (cycles_with("unoccluded", OVER_GROUND, 64, "--unoccluded", &r)) {
        compare("unoccluded", &r, 1, furnace_sphere, NULL, false, 1.5, 0, 0.01, 0.02, 0.08);
        compare("unocc-bg", &r, 0, furnace_background, NULL, false, 1.5, 0, 0.01, 0.005, 0.01);
    }
    free_render(&r);
    /* the default reference of the same scene: the ground takes light from the sphere's lower half */
    if (cycles("occluded", OVER_GROUND, 64, &r)) {
        double m = sphere_mean(&r);
        printf("%-12s sphere mean %.5f: %.1f %% under the unoccluded closed form 0.8\n", "occluded", m, 100 * (1 - m / 0.8));
        CHECK_MSG(m < 0.8 * 0.95, "occluded: the sphere's mean %.4f is within 5 %% of 0.8: the ground does not occlude", m);
    }
    free_render(&r);
}

/* ---- point ------------------------------------------------------------------------------- */

static const double POINT_POS[3] = {0.3, -0.2, 1.0};

static double point_form(const double p[3], int c, void *u) {
    (void)c, (void)u;
    double d[3] = {POINT_POS[0] - p[0], POINT_POS[1] - p[1], POINT_POS[2] - p[2]};
    double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return 0.5 / PI * 2.0 * (d[2] / dist) / (dist * dist);
}

/* ---- spot -------------------------------------------------------------------------------- */

typedef struct spot {
    double pos[3], axis[3], intensity, outer_deg, inner_deg;
    bool gltf;
} spot;

static double spot_form(const double p[3], int c, void *u) {
    (void)c;
    const spot *s = u;
    double d[3] = {p[0] - s->pos[0], p[1] - s->pos[1], p[2] - s->pos[2]};
    double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double cos_axis = (d[0] * s->axis[0] + d[1] * s->axis[1] + d[2] * s->axis[2]) / dist;
    double theta = acos(fmax(-1, fmin(1, cos_axis))), outer = s->outer_deg * PI / 180, f;
    if (s->gltf) {
        double scale = 1 / fmax(0.001, cos(s->inner_deg * PI / 180) - cos(outer)), offset = -cos(outer) * scale;
        f = fmin(1, fmax(0, cos_axis * scale + offset));
        f *= f;
    } else {
        f = fmin(1, fmax(0, (1.1 * outer - theta) / (0.2 * outer)));
    }
    double cos_in = -d[2] / dist; /* the plane's normal is +Z */
    return 0.5 / PI * s->intensity * f * cos_in / (dist * dist);
}

static void spot_case(const char *name, const spot *s, const char *falloff) {
    char scene[4096];
    snprintf(scene, sizeof scene,
             "{ \"plugins\": [\"spotlight-shadow\"],\n"
             "  \"cameras\": [{ \"type\": \"orthographic\", \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"ymag\": 1.2 }],\n"
             "  \"materials\": [{ \"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5] }],\n"
             "  \"nodes\": [{ \"name\": \"plane\", \"rotate\": [90, 0, 0], \"mesh\": { \"primitive\": \"plane\", \"size\": 8 }, \"material\": \"m\" }],\n"
             "  \"lights\": [{ \"name\": \"s\", \"type\": \"spot\", \"position\": [%g, %g, %g], \"direction\": [%.9g, %.9g, %.9g],\n"
             "    \"intensity\": %g, \"cone_angle\": %g, \"inner_cone_angle\": %g, \"falloff\": \"%s\" }] }\n",
             s->pos[0], s->pos[1], s->pos[2], s->axis[0], s->axis[1], s->axis[2], s->intensity, s->outer_deg,
             s->inner_deg, falloff);
    render r = {0};
    if (cycles(name, scene, 16, &r))
        compare(name, &r, -1, spot_form, (void *)s, false, 1.2, 0.02, 0.01, 0.01, 0.08);
    free_render(&r);
}

/* ---- sky-sun ----------------------------------------------------------------------------- */

/* envmap's procedural sky's sun disk as its README documents it: towards (cos e sin a, sin e,
 * cos e cos a) for elevation e and azimuth a, angular radius 1.5°, radiance E/Ω times the colour
 * (1, 0.95, 0.88), Ω = 2π(1 − cos r). Looking at it (elevation 30°, azimuth 20°, E = 3) through a
 * 12° camera at the origin, a third of a pixel off its centre: the sky under the disk is taken as
 * the mean of a ring 3–5 pixels outside it (smooth: sky and halo), and each pixel's excess over
 * it, over the disk's radiance, is the share of the pixel inside the disk (16 × 16 rays per
 * pixel: the 1-pixel box filter the export asks of Cycles). The disk's energy (excess times the
 * pixels' solid angles) is E in red; the pixels along the edge match their shares. A disk baked
 * into the exported lat-long (2048 texels around) was blurred over its texels: rms 0.08 along
 * the edge (measured before the disk went to the world's nodes). */
static const double SUN_E = 3, SUN_R = 1.5 * PI / 180, SUN_FOV = 12;

static void sun_dir(double d[3]) {
    double e = 30 * PI / 180, a = 20 * PI / 180;
    d[0] = cos(e) * sin(a), d[1] = sin(e), d[2] = cos(e) * cos(a);
}

static void sun_case(void) {
    double sun[3], px = 2 * tan(SUN_FOV * PI / 360) / H;
    sun_dir(sun);
    test_camera cam = {{0, 0, 0}, {(float)(sun[0] + px / 3), (float)(sun[1] + px / 3), (float)sun[2]}, SUN_FOV, W, H};
    char scene[1024];
    snprintf(scene, sizeof scene,
             "{ \"plugins\": [\"envmap\"],\n"
             "  \"params\": { \"envmap.sun_elevation\": 30, \"envmap.sun_azimuth\": 20, \"envmap.sun_irradiance\": %g,"
             " \"envmap.sun_light\": false },\n"
             "  \"cameras\": [{ \"position\": [0, 0, 0], \"target\": [%.9g, %.9g, %.9g], \"fov_y\": %g }],\n"
             "  \"materials\": [{ \"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5] }],\n"
             "  \"nodes\": [{ \"name\": \"speck\", \"translate\": [0, -50, 0], \"mesh\": { \"primitive\": \"sphere\", \"radius\": 0.1 }, \"material\": \"m\" }] }\n",
             SUN_E, cam.target[0], cam.target[1], cam.target[2], SUN_FOV);
    render r = {0};
    if (!cycles("sky-sun", scene, 64, &r)) { free_render(&r); return; }
    double L = SUN_E / (2 * PI * (1 - cos(SUN_R))), fwd[3] = {cam.target[0], cam.target[1], cam.target[2]};
    double fl = sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]);
    for (int i = 0; i < 3; i++) fwd[i] /= fl;
    double ring = 0, energy = 0, sum2 = 0, worst = 0;
    int ring_n = 0, edge_n = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                float o[3], d[3];
                test_camera_ray(&cam, x, y, o, d);
                double mu = d[0] * fwd[0] + d[1] * fwd[1] + d[2] * fwd[2];
                double off = (acos(fmin(1, d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2])) - SUN_R) / (px * mu * mu);
                double v = r.img.pixels[((size_t)y * W + x) * 4];
                if (pass == 0) {
                    if (off > 3 && off < 5) ring += v, ring_n++;
                    continue;
                }
                if (off > 3) continue;
                energy += (v - ring / ring_n) * px * px * mu * mu * mu;
                if (fabs(off) > 1.5) continue;
                double share = 0;
                for (int j = 0; j < 16; j++)
                    for (int i = 0; i < 16; i++) {
                        test_camera_ray_at(&cam, x + (i + 0.5f) / 16, y + (j + 0.5f) / 16, o, d);
                        share += (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > cos(SUN_R)) / 256.0;
                    }
                double e = (v - ring / ring_n) / L - share;
                sum2 += e * e, worst = fmax(worst, fabs(e)), edge_n++;
            }
    double rms = sqrt(sum2 / (edge_n ? edge_n : 1));
    printf("%-12s energy %.4f (closed form %g), %d edge pixels: rms %.4f, largest %.4f of the disk's radiance\n",
           "sky-sun", energy, SUN_E, edge_n, rms, worst);
    CHECK_MSG(ring_n > 100 && edge_n > 50, "sky-sun: %d ring and %d edge pixels", ring_n, edge_n);
    CHECK_MSG(fabs(energy / SUN_E - 1) < 0.01, "sky-sun: the disk's energy is %.4f, expected %g", energy, SUN_E);
    CHECK_MSG(rms < 0.03, "sky-sun: the disk's edge differs from the box filter by rms %.4f", rms);
    free_render(&r);
}

/* The same sun lighting a Lambert plane facing +Z (ρ = 0.5): the render with the sun's irradiance E
 * less the render with none (the sky's gradient, halo and ground do not depend on E) is what the
 * disk adds, ρ/π · (E/Ω) · ∫cap cos θ dω = ρ/π · (E/Ω) · π sin²r · cos θc, θc the angle of the
 * disk's centre from the normal (the whole cap above the plane's horizon), the sky turned by a yaw
 * of 40° (shadelab looks up R_y(−yaw)·d: the sun is at R_y(yaw)·s). The export gives the
 * disk's lighting to a sun lamp of the same cone (docs/xcheck.md), so this checks the lamp's
 * strength and direction. */
static const double SKY_YAW = 40;
static double sky_sun_add[3];

static double sky_sun_lit_form(const double p[3], int c, void *user) {
    (void)p, (void)user;
    return sky_sun_add[c];
}

static void sky_sun_lit_case(void) {
    static const double colour[3] = {1.0, 0.95, 0.88};
    render lit = {0}, unlit = {0};
    char scene[1024], name[32];
    for (int k = 0; k < 2; k++) {
        snprintf(scene, sizeof scene,
                 "{ \"plugins\": [\"envmap\"],\n"
                 "  \"params\": { \"envmap.sun_elevation\": 30, \"envmap.sun_azimuth\": 20, \"envmap.sun_irradiance\": %g,"
                 " \"envmap.sun_light\": false },\n"
                 "  \"cameras\": [{ \"type\": \"orthographic\", \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"ymag\": 1 }],\n"
                 "  \"materials\": [{ \"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5] }],\n"
                 "  \"nodes\": [{ \"name\": \"plane\", \"rotate\": [90, 0, 0], \"mesh\": { \"primitive\": \"plane\", \"size\": 8 },"
                 " \"material\": \"m\" }],\n"
                 "  \"environment\": { \"yaw\": %g } }\n",
                 k ? 0.0 : SUN_E, SKY_YAW);
        snprintf(name, sizeof name, "sky-sun-lit-%d", k);
        if (!cycles(name, scene, 32, k ? &unlit : &lit)) goto done;
    }
    double sun[3], yaw = SKY_YAW * PI / 180;
    sun_dir(sun);
    double cos_c = -sun[0] * sin(yaw) + sun[2] * cos(yaw); /* z of R_y(yaw)·sun */
    for (int c = 0; c < 3; c++)
        sky_sun_add[c] = 0.5 / PI * SUN_E / (2 * PI * (1 - cos(SUN_R))) * colour[c] * PI * sin(SUN_R) * sin(SUN_R) * cos_c;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) lit.img.pixels[i] -= unlit.img.pixels[i];
    compare("sky-sun-lit", &lit, 1, sky_sun_lit_form, NULL, false, 1, 0, 0.01, 0.05, 0.25);
done:
    free_render(&lit);
    free_render(&unlit);
}

/* ---- mirror ------------------------------------------------------------------------------ */

/* The lat-long convention of Blender and three.js, from its statement: u = ½ at +X, growing
 * towards +Z; v = 0 straight up (Y). Direction of the texel centre (u, v). */
static void latlong_dir(double u, double v, double d[3]) {
    double phi = 2 * PI * (u - 0.5), theta = PI * v;
    d[0] = sin(theta) * cos(phi);
    d[1] = cos(theta);
    d[2] = sin(theta) * sin(phi);
}

static const double YAW = 30;

/* The map's colour for a world direction: d turned by R_y(−yaw), then 0.5 + 0.4·d per channel. */
static double map_colour(const double r[3], int c) {
    double a = -YAW * PI / 180;
    double d[3] = {cos(a) * r[0] + sin(a) * r[2], r[1], -sin(a) * r[0] + cos(a) * r[2]};
    return 0.5 + 0.4 * d[c];
}

static double mirror_form(const double p[3], int c, void *u) {
    (void)u;
    double rr = p[0] * p[0] + p[1] * p[1];
    if (rr > 0.9 * 0.9) return -1; /* away from the rim, where a pixel spans a wide cone */
    double n[3] = {p[0], p[1], sqrt(1 - rr)}, v[3] = {0, 0, 1};
    double nv = n[2], r[3];
    for (int i = 0; i < 3; i++) r[i] = 2 * nv * n[i] - v[i];
    return map_colour(r, c);
}

static double mirror_background(const double p[3], int c, void *u) {
    (void)u;
    const double view[3] = {0, 0, -1};
    if (p[0] * p[0] + p[1] * p[1] < 1.05 * 1.05) return -1; /* clear of the silhouette */
    return map_colour(view, c);
}

static void write_pattern_map(const char *path) {
    int w = 256, h = 128;
    float *px = malloc((size_t)w * h * 4 * sizeof *px);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d[3];
            latlong_dir((x + 0.5) / w, (y + 0.5) / h, d);
            for (int c = 0; c < 3; c++) px[((size_t)y * w + x) * 4 + c] = (float)(0.5 + 0.4 * d[c]);
            px[((size_t)y * w + x) * 4 + 3] = 1;
        }
    char err[512];
    if (!sl_image_write(path, px, w, h, false, err, sizeof err)) { fprintf(stderr, "%s\n", err); exit(1); }
    free(px);
}

/* ---- glTF model: camera and time -------------------------------------------------------- */

/* A glTF file opened directly (Blender's importer reads it): an unlit black quad [−1, 1]² at z = 0
 * whose translation is animated from (0, 0, 0) at 0 s to (2.4, 0, 0) at 1 s, seen by the file's
 * camera at (0, 0, 3) looking down −Z (yfov 0.8, no aspectRatio: the image's). shadelab renders
 * scene time 0, so the reference must show the quad at the origin. By the spec's perspective
 * projection (glTF 2.0 §3.10.3: x_ndc = x / (−z · aspect · tan(yfov/2))), its edges are at pixel
 * x = W/2 · (1 ± 1 / (3 · (W/H) · tan 0.4)), y = H/2 · (1 ± 1 / (3 · tan 0.4)): centred, and
 * H / (3 tan 0.4) px across both ways (50.46 at H = 64). At Blender's frame 1 (1/24 s) the quad
 * would be 0.1 m, 2.5 px, to the right. */

static void write_quad_gltf(const char *gltf) {
    const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const unsigned short idx[6] = {0, 1, 2, 0, 2, 3};
    const float times[2] = {0, 1}, moves[6] = {0, 0, 0, 2.4f, 0, 0};
    char bin[4200];
    snprintf(bin, sizeof bin, "%s/quad.bin", sl_test_dir());
    FILE *f = fopen(bin, "wb");
    bool ok = f && fwrite(pos, sizeof pos, 1, f) && fwrite(nrm, sizeof nrm, 1, f) && fwrite(idx, sizeof idx, 1, f) &&
              fwrite(times, sizeof times, 1, f) && fwrite(moves, sizeof moves, 1, f);
    if (f) ok &= fclose(f) == 0;
    if (!ok) { fprintf(stderr, "cannot write %s\n", bin); exit(1); }
    write_text(gltf,
        "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0, 1]}],\n"
        " \"extensionsUsed\": [\"KHR_materials_unlit\"],\n"
        " \"nodes\": [{\"name\": \"quad\", \"mesh\": 0}, {\"name\": \"eye\", \"camera\": 0, \"translation\": [0, 0, 3]}],\n"
        " \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.8, \"znear\": 0.1, \"zfar\": 20}}],\n"
        " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1}, \"indices\": 2, \"material\": 0}]}],\n"
        " \"materials\": [{\"name\": \"black\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [0, 0, 0, 1]},\n"
        "                \"extensions\": {\"KHR_materials_unlit\": {}}}],\n"
        " \"animations\": [{\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}],\n"
        "                 \"samplers\": [{\"input\": 3, \"output\": 4}]}],\n"
        " \"buffers\": [{\"uri\": \"quad.bin\", \"byteLength\": 140}],\n"
        " \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48}, {\"buffer\": 0, \"byteOffset\": 48, \"byteLength\": 48},\n"
        "                 {\"buffer\": 0, \"byteOffset\": 96, \"byteLength\": 12}, {\"buffer\": 0, \"byteOffset\": 108, \"byteLength\": 8},\n"
        "                 {\"buffer\": 0, \"byteOffset\": 116, \"byteLength\": 24}],\n"
        " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\": [-1, -1, 0], \"max\": [1, 1, 0]},\n"
        "               {\"bufferView\": 1, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"},\n"
        "               {\"bufferView\": 2, \"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\"},\n"
        "               {\"bufferView\": 3, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\", \"min\": [0], \"max\": [1]},\n"
        "               {\"bufferView\": 4, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC3\"}]}\n");
}

/* The black quad's extent along one row (vertical = false) or column k of the image: each pixel's
 * coverage 1 − v/b, b the background's mean over the 4 pixels at that end of the line (the near
 * end's, so the environment's gradient across the line plays no part), summed over the quad's
 * pixels and 3 either side: the span in pixels; the coverage-weighted mean of pixel centres: its
 * centre (both exact for a box filter). */
static void quad_extent(const render *r, int k, bool vertical, double *span, double *centre) {
    int n = vertical ? H : W;
    double v[W > H ? W : H], lo = 0, hi = 0;
    for (int i = 0; i < n; i++) {
        size_t px = 4 * (vertical ? (size_t)i * W + k : (size_t)k * W + i);
        v[i] = r->img.pixels[px] + r->img.pixels[px + 1] + r->img.pixels[px + 2];
    }
    for (int i = 0; i < 4; i++) lo += v[i] / 4, hi += v[n - 1 - i] / 4;
    int a = n, b = -1;
    for (int i = 0; i < n; i++)
        if (v[i] < 0.5 * (i < n / 2 ? lo : hi)) a = i < a ? i : a, b = i;
    double sum = 0, moment = 0;
    for (int i = a - 3 < 4 ? 4 : a - 3; i <= b + 3 && i < n - 4; i++) {
        double c = 1 - v[i] / (i < n / 2 ? lo : hi);
        sum += c, moment += c * (i + 0.5);
    }
    *span = sum, *centre = sum > 0 ? moment / sum : NAN;
}

static void gltf_case(void) {
    char gltf[4200];
    snprintf(gltf, sizeof gltf, "%s/quad.gltf", sl_test_dir());
    write_quad_gltf(gltf);
    render r = {0};
    if (!cycles_file("gltf-quad", gltf, 64, "--unoccluded", &r)) return;
    for (int vertical = 0; vertical < 2; vertical++) {
        double span = 0, centre = 0, e_span = H / (3 * tan(0.4)), e_centre = 0.5 * (vertical ? H : W);
        int lines = 0;
        for (int k = 16; k < (vertical ? W : H) - 16; k++, lines++) {
            double s, c;
            quad_extent(&r, k, vertical, &s, &c);
            span += s, centre += c;
        }
        span /= lines, centre /= lines;
        printf("%-12s %s: centre %.3f px (closed form %.3f), span %.3f px (closed form %.3f), %d lines\n", "gltf-quad",
               vertical ? "columns" : "rows", centre, e_centre, span, e_span, lines);
        CHECK_MSG(fabs(centre - e_centre) <= 0.15, "gltf-quad: the quad's centre along the %s is %.3f px, expected %.3f",
                  vertical ? "columns" : "rows", centre, e_centre);
        CHECK_MSG(fabs(span - e_span) <= 0.3, "gltf-quad: the quad spans %.3f px along the %s, expected %.3f", span,
                  vertical ? "columns" : "rows", e_span);
    }
    free_render(&r);
}

int main(void) {
    render r = {0};
    /* sun: plane facing +Z (a +Y plane turned 90° about X), sun 40° from its normal */
    const char *sun =
        "{ \"cameras\": [{ \"type\": \"orthographic\", \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"ymag\": 1 }],\n"
        "  \"materials\": [{ \"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5] }],\n"
        "  \"nodes\": [{ \"name\": \"plane\", \"rotate\": [90, 0, 0], \"mesh\": { \"primitive\": \"plane\", \"size\": 8 }, \"material\": \"m\" }],\n"
        "  \"lights\": [{ \"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.6427876097, 0, -0.7660444431], \"intensity\": 3 }] }\n";
    if (cycles("sun", sun, 8, &r)) compare("sun", &r, 1, sun_form, NULL, false, 1, 0, 0.01, 0.005, 0.01);
    free_render(&r);

    /* furnace: no lights, a white environment of radiance 1 */
    const char *furnace =
        "{ \"cameras\": [{ \"type\": \"orthographic\", \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"ymag\": 1.5 }],\n"
        "  \"materials\": [{ \"name\": \"m\", \"base_color\": [0.8, 0.8, 0.8] }],\n"
        "  \"nodes\": [{ \"name\": \"ball\", \"mesh\": { \"primitive\": \"sphere\", \"radius\": 1 }, \"material\": \"m\" }],\n"
        "  \"environment\": { \"color\": [1, 1, 1], \"intensity\": 1 } }\n";
    if (cycles("furnace", furnace, 64, &r)) {
        compare("furnace", &r, 1, furnace_sphere, NULL, false, 1.5, 0, 0.01, 0.02, 0.08);
        compare("furnace-bg", &r, 0, furnace_background, NULL, false, 1.5, 0, 0.01, 0.005, 0.01);
    }
    free_render(&r);
    unoccluded_case();
    unmapped_layer_case();

    /* point light 1 m over a plane, seen through a 40° perspective camera */
    char point[2048];
    snprintf(point, sizeof point,
             "{ \"cameras\": [{ \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"fov_y\": 40 }],\n"
             "  \"materials\": [{ \"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5] }],\n"
             "  \"nodes\": [{ \"name\": \"plane\", \"rotate\": [90, 0, 0], \"mesh\": { \"primitive\": \"plane\", \"size\": 8 }, \"material\": \"m\" }],\n"
             "  \"lights\": [{ \"name\": \"p\", \"type\": \"point\", \"position\": [%g, %g, %g], \"intensity\": 2 }] }\n",
             POINT_POS[0], POINT_POS[1], POINT_POS[2]);
    if (cycles("point", point, 8, &r)) compare("point", &r, 1, point_form, NULL, true, 40, 0, 0.01, 0.005, 0.03);
    free_render(&r);

    /* spots: straight down with the linear fall-off, tilted 20° towards +X with glTF's */
    spot down = {{0, 0, 1.5}, {0, 0, -1}, 3, 25, 0, false};
    spot_case("spot-linear", &down, "linear");
    double t = 20 * PI / 180;
    spot tilted = {{-0.2, 0.1, 1.5}, {sin(t), 0, -cos(t)}, 3, 25, 15, true};
    spot_case("spot-gltf", &tilted, "gltf");

    /* mirror sphere in a lat-long turned by yaw */
    char map[4096], mirror[4096];
    snprintf(map, sizeof map, "%s/pattern.exr", sl_test_dir());
    write_pattern_map(map);
    snprintf(mirror, sizeof mirror,
             "{ \"plugins\": [\"envmap\"],\n"
             "  \"cameras\": [{ \"type\": \"orthographic\", \"position\": [0, 0, 5], \"target\": [0, 0, 0], \"ymag\": 1.2 }],\n"
             "  \"materials\": [{ \"name\": \"m\", \"model\": \"mirror\" }],\n"
             "  \"nodes\": [{ \"name\": \"ball\", \"mesh\": { \"primitive\": \"sphere\", \"radius\": 1, \"segments\": 256, \"rings\": 128 }, \"material\": \"m\" }],\n"
             "  \"environment\": { \"map\": \"%s\", \"yaw\": %g } }\n",
             map, YAW);
    if (cycles("mirror", mirror, 8, &r)) {
        compare("mirror", &r, 1, mirror_form, NULL, false, 1.2, 0, 0.01, 0.01, 0.1);
        compare("mirror-bg", &r, 0, mirror_background, NULL, false, 1.2, 0, 0.01, 0.005, 0.01);
    }
    free_render(&r);
    sun_case();
    sky_sun_lit_case();
    gltf_case();
    return check_result();
}
