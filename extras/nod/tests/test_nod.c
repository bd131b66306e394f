/* nod against closed forms and independent computations (harness, OSMesa):
 *  1. rest: at t = 0 the frame equals the frame without the plugin, exactly (θ = 0 and the colour
 *     pulse is 0; the displacement is an increment that is exactly 0).
 *  2. read-back: nod_displace (the GLSL the vertex hook runs) at a quarter period, over a grid of
 *     points above and below the pivot, against Rodrigues' rotation by the amplitude in C.
 *  3. exact normals: nod_normal with nod.normals=exact in the blend band against the normal of
 *     the C displacement differentiated numerically (central differences along two tangents).
 *  4. image at a quarter period, rigid case (the whole cube above the pivot, blend 0): equals a
 *     static frame whose node is rotated by the amplitude about the pivot with scene transforms
 *     (the core's node matrices: an independent path), and the untagged floor does not move.
 *  5. shadows follow: the same comparison with a shadow-casting spot light (spotlight-shadow):
 *     the moved cube's shadow on the floor equals the rotated static cube's, and differs from the
 *     rest pose's.
 *  6. colour: at half a colour period (pulse 1) pixels at the region's centre on a Lambert sphere
 *     equal the base frame × mix(base, nod_color, strength)/base per channel.
 *  7. costs nothing: switched off, or on with no tagged node and no nod_color material, the
 *     frame's structure (passes, draws, program hashes) equals the one without the plugin.
 *  stability: ±90°, a 1 cm band, a pivot 1000 km away, zero axis/region/radius: finite pixels.
 *  8. live equals fresh: nod.amplitude and nod.normals changed with set() give the frame a new
 *     harness with those settings gives. */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 120
static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)
static const double PI = 3.14159265358979323846;

static sl_harness *make(const char *json, const char *const *settings, bool with_nod) {
    const char *plugins[] = {NOD_PLUGIN_PATH, "spotlight-shadow", NULL};
    const char *only_shadow[] = {"spotlight-shadow", NULL};
    char err[4096];
    sl_harness_desc d = {.struct_size = sizeof d, .width = W, .height = H, .scene_json = json,
                         .plugins = with_nod ? plugins : only_shadow, .settings = settings, .strict = true};
    sl_harness *h = sl_harness_create(&d, err, sizeof err);
    if (!h) { printf("FAIL: harness: %s\n", err); exit(1); }
    return h;
}

static float *render_at(sl_harness *h, uint64_t frame) {
    float *img = malloc(sizeof(float) * W * H * 4);
    sl_harness_set_frame(h, frame);
    if (!sl_harness_render(h, img)) { printf("FAIL: render\n"); exit(1); }
    return img;
}

static float *render(const char *json, const char *const *settings, bool with_nod, uint64_t frame) {
    sl_harness *h = make(json, settings, with_nod);
    float *img = render_at(h, frame);
    sl_harness_destroy(h);
    return img;
}

/* Rodrigues: x rotated by a about unit k */
static void rotate(const double x[3], const double k[3], double a, double out[3]) {
    double c = cos(a), s = sin(a), kx[3] = {k[1] * x[2] - k[2] * x[1], k[2] * x[0] - k[0] * x[2], k[0] * x[1] - k[1] * x[0]};
    double kd = k[0] * x[0] + k[1] * x[1] + k[2] * x[2];
    for (int i = 0; i < 3; i++) out[i] = x[i] * c + kx[i] * s + k[i] * kd * (1 - c);
}

/* the deformation, written from the README's definition (not from the GLSL) */
typedef struct { double amp_deg, freq, pivot[3], axis[3], region[3], blend, mirror[3]; } motion;
static void displace_unmirrored(const motion *m, const double p[3], double t, double out[3]) {
    double d[3] = {p[0] - m->pivot[0], p[1] - m->pivot[1], p[2] - m->pivot[2]};
    double ul = sqrt(m->region[0] * m->region[0] + m->region[1] * m->region[1] + m->region[2] * m->region[2]);
    double kl = sqrt(m->axis[0] * m->axis[0] + m->axis[1] * m->axis[1] + m->axis[2] * m->axis[2]);
    double h = (d[0] * m->region[0] + d[1] * m->region[1] + d[2] * m->region[2]) / ul;
    double w;
    if (m->blend <= 0) w = h >= 0;
    else { double x = fmin(1, fmax(0, h / m->blend)); w = x * x * (3 - 2 * x); }
    double k[3] = {m->axis[0] / kl, m->axis[1] / kl, m->axis[2] / kl}, r[3];
    rotate(d, k, m->amp_deg * PI / 180 * sin(2 * PI * m->freq * t) * w, r);
    for (int i = 0; i < 3; i++) out[i] = m->pivot[i] + r[i];
}
/* nod.mirror: on the negative side of the plane through the origin with normal `mirror`, the
 * motion of the reflected point, reflected back */
static void displace(const motion *m, const double p[3], double t, double out[3]) {
    double ml = sqrt(m->mirror[0] * m->mirror[0] + m->mirror[1] * m->mirror[1] + m->mirror[2] * m->mirror[2]);
    double pm = ml > 0 ? (p[0] * m->mirror[0] + p[1] * m->mirror[1] + p[2] * m->mirror[2]) / ml : 0;
    if (pm >= 0) { displace_unmirrored(m, p, t, out); return; }
    double q[3], r[3];
    for (int i = 0; i < 3; i++) q[i] = p[i] - 2 * pm * m->mirror[i] / ml;
    displace_unmirrored(m, q, t, r);
    double rm = (r[0] * m->mirror[0] + r[1] * m->mirror[1] + r[2] * m->mirror[2]) / ml;
    for (int i = 0; i < 3; i++) out[i] = r[i] - 2 * rm * m->mirror[i] / ml;
}

static char *defines_of(const motion *m, const char *normals) {
    static char buf[1024];
    snprintf(buf, sizeof buf,
             "nod_amplitude %.9g\nnod_frequency %.9g\nnod_pivot vec3(%.9g,%.9g,%.9g)\nnod_axis vec3(%.9g,%.9g,%.9g)\n"
             "nod_region vec3(%.9g,%.9g,%.9g)\nnod_blend %.9g\nNOD_NORMALS_REST 0\nNOD_NORMALS_RIGID 1\nNOD_NORMALS_EXACT 2\n"
             "NOD_NORMALS %s\nnod_pose_time -1.0\nnod_mirror vec3(%.9g,%.9g,%.9g)",
             m->amp_deg, m->freq, m->pivot[0], m->pivot[1], m->pivot[2], m->axis[0], m->axis[1], m->axis[2],
             m->region[0], m->region[1], m->region[2], m->blend, normals, m->mirror[0], m->mirror[1], m->mirror[2]);
    return buf;
}

/* a cube (size 1, centre 0.5 above the node) and a floor; `extra` goes into the cube node */
static void cube_scene(char *out, size_t n, const char *cube_node, const char *material_extra, bool spot) {
    snprintf(out, n,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [2.2, 2.6, 5.2], \"target\": [0, 0.8, 0], \"fov_y\": 45}],"
             " \"materials\": [{\"name\": \"floor\", \"base_color\": [0.7, 0.7, 0.7]},"
             "                 {\"name\": \"box\", \"base_color\": [0.3, 0.5, 0.8]%s}],"
             " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 8}, \"material\": \"floor\"}, %s],"
             " \"lights\": [%s]}",
             material_extra, cube_node,
             spot ? "{\"name\": \"s\", \"type\": \"spot\", \"position\": [-2.5, 4.5, 1.5], \"direction\": [0.45, -0.85, -0.2],"
                    " \"intensity\": 60, \"cone_angle\": 40, \"cast_shadows\": true}"
                  : "{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.4, -1, -0.6], \"intensity\": 3}");
}

int main(void) {
    /* ---- 2. read-back of the displacement at a quarter period ---- */
    {
        motion m = {.amp_deg = 30, .freq = 0.25, .pivot = {0.1, 0.4, -0.2}, .axis = {1, 0.2, 0}, .region = {0, 1, 0.3}, .blend = 0.3};
        const char *files[] = {"nod_motion.glsl", NULL};
        enum { N = 16 };
        float in0[N * N * 4], out[N * N * 4];
        for (int i = 0; i < N * N; i++) {
            in0[i * 4 + 0] = -1 + 2.0f * (i % N) / (N - 1);
            in0[i * 4 + 1] = -0.5f + 2.0f * (i / N) / (N - 1);
            in0[i * 4 + 2] = 0.3f * sinf(i);
            in0[i * 4 + 3] = 0;
        }
        sl_harness *h = make(NULL, NULL, true);
        char err[4096];
        for (int tcase = 0; tcase < 3; tcase++) {
            double t = tcase == 0 ? 1.0 : 0.37; /* quarter period (f = 0.25 Hz), and any time */
            /* third case: mirrored across the plane x + 0.2 z = 0 (both ears), points on both sides */
            if (tcase == 2) m.mirror[0] = 1, m.mirror[2] = 0.2, m.pivot[0] = 0.5;
            char expr[128];
            snprintf(expr, sizeof expr, "vec4(nod_displace(in0.xyz, %.9g), 0.0)", t);
            sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "nod", .files = files, .expression = expr,
                                   .defines = defines_of(&m, "NOD_NORMALS_EXACT"), .width = N, .height = N, .in0 = in0};
            if (!sl_harness_eval_glsl(h, &d, out, err, sizeof err)) { printf("FAIL: eval: %s\n", err); return 1; }
            double worst = 0, moved_max = 0;
            for (int i = 0; i < N * N; i++) {
                double p[3] = {in0[i * 4], in0[i * 4 + 1], in0[i * 4 + 2]}, q[3];
                displace(&m, p, t, q);
                for (int k = 0; k < 3; k++) {
                    worst = fmax(worst, fabs(q[k] - out[i * 4 + k]));
                    moved_max = fmax(moved_max, fabs(q[k] - p[k]));
                }
            }
            printf("displacement t=%.2f%s: max |GLSL - C Rodrigues| = %.3g (largest motion %.3g)\n", t,
                   tcase == 2 ? " mirrored" : "", worst, moved_max);
            CHECK(worst < 2e-5, "displacement differs from the closed-form rotation by %g", worst);
            CHECK(moved_max > 0.3, "the region did not move (max %g)", moved_max);
        }
        /* ---- 3. exact normals vs the numerically differentiated C displacement ---- */
        float in1[N * N * 4];
        for (int i = 0; i < N * N; i++) {
            /* points in and around the band (h in [-0.1, 0.4]); rest normal: any unit vector */
            double th = 0.4 * i, ph = 0.7 * i;
            in0[i * 4 + 0] = -0.8f + 1.6f * (i % N) / (N - 1);
            in0[i * 4 + 1] = 0.3f + 0.5f * (i / N) / (N - 1);
            in0[i * 4 + 2] = 0.2f * cosf(i);
            in1[i * 4 + 0] = (float)(sin(th) * cos(ph)), in1[i * 4 + 1] = (float)cos(th), in1[i * 4 + 2] = (float)(sin(th) * sin(ph));
            in1[i * 4 + 3] = 0;
        }
        /* a band that does not fold over (1 + u·v' stays well above 0): 20° over 0.8 */
        m.amp_deg = 20, m.blend = 0.8;
        for (int i = 0; i < N * N; i++) in0[i * 4 + 1] = 0.3f + 0.9f * (i / N) / (N - 1);
        const char *modes[] = {"NOD_NORMALS_EXACT", "NOD_NORMALS_RIGID"};
        double worst_mode[2] = {0, 0};
        for (int mi = 0; mi < 2; mi++) {
            sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "nod", .files = files,
                                   .expression = "vec4(normalize(nod_normal(in0.xyz, in1.xyz, 1.0)), 0.0)",
                                   .defines = defines_of(&m, modes[mi]), .width = N, .height = N, .in0 = in0, .in1 = in1};
            if (!sl_harness_eval_glsl(h, &d, out, err, sizeof err)) { printf("FAIL: eval: %s\n", err); return 1; }
            for (int i = 0; i < N * N; i++) {
                double p[3] = {in0[i * 4], in0[i * 4 + 1], in0[i * 4 + 2]}, n[3] = {in1[i * 4], in1[i * 4 + 1], in1[i * 4 + 2]};
                /* two unit tangents orthogonal to n, mapped by the displacement (central differences) */
                double a[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0}, t1[3], t2[3];
                double an = a[0] * n[0] + a[1] * n[1] + a[2] * n[2], l = 0;
                for (int k = 0; k < 3; k++) t1[k] = a[k] - an * n[k], l += t1[k] * t1[k];
                for (int k = 0; k < 3; k++) t1[k] /= sqrt(l);
                t2[0] = n[1] * t1[2] - n[2] * t1[1], t2[1] = n[2] * t1[0] - n[0] * t1[2], t2[2] = n[0] * t1[1] - n[1] * t1[0];
                const double e = 1e-5;
                double d1[3], d2[3], pp[3], pm[3], qp[3], qm[3];
                for (int k = 0; k < 3; k++) pp[k] = p[k] + e * t1[k], pm[k] = p[k] - e * t1[k];
                displace(&m, pp, 1.0, qp), displace(&m, pm, 1.0, qm);
                for (int k = 0; k < 3; k++) d1[k] = qp[k] - qm[k];
                for (int k = 0; k < 3; k++) pp[k] = p[k] + e * t2[k], pm[k] = p[k] - e * t2[k];
                displace(&m, pp, 1.0, qp), displace(&m, pm, 1.0, qm);
                for (int k = 0; k < 3; k++) d2[k] = qp[k] - qm[k];
                double c[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]};
                double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot = 0;
                for (int k = 0; k < 3; k++) dot += c[k] / cl * out[i * 4 + k];
                worst_mode[mi] = fmax(worst_mode[mi], acos(fmin(1, dot)) * 180 / PI);
            }
        }
        printf("normals in the blend band vs finite differences: exact %.3g deg, rigid %.3g deg\n", worst_mode[0], worst_mode[1]);
        CHECK(worst_mode[0] < 0.05, "exact normals off by %g degrees", worst_mode[0]);
        CHECK(worst_mode[1] > 1, "rigid normals should be visibly approximate in the band (%g degrees)", worst_mode[1]);
        sl_harness_destroy(h);
    }

    char moving[4096], rotated[4096], still[4096];
    /* the cube spans world y in [0.6, 1.6]; the pivot (the origin) is 0.6 below its bottom: all of it moves */
    const char *cube_tagged = "{\"name\": \"cube\", \"tags\": [\"nod\"], \"translate\": [0, 0.6, 0], \"children\": ["
                              "{\"name\": \"cube-mesh\", \"translate\": [0, 0.5, 0], \"mesh\": {\"primitive\": \"cube\", \"size\": 1}, \"material\": \"box\"}]}";
    /* the same cube rotated by the amplitude (25° about x) about the pivot (world (0, 0, 0)) by
     * the scene's transforms */
    const char *cube_rotated = "{\"name\": \"pivot\", \"rotate\": [25, 0, 0], \"children\": [{\"name\": \"cube\", \"translate\": [0, 0.6, 0], \"children\": ["
                               "{\"name\": \"cube-mesh\", \"translate\": [0, 0.5, 0], \"mesh\": {\"primitive\": \"cube\", \"size\": 1}, \"material\": \"box\"}]}]}";
    /* nod's pivot is in world space (rest pose): the origin */
    const char *settings[] = {"nod.amplitude=25", "nod.frequency=0.25", "nod.pivot=0,0,0", "nod.axis=1,0,0",
                              "nod.region=0,1,0", "nod.blend=0", NULL};
    /* ---- 1. rest: t = 0 equals no plugin ---- */
    cube_scene(moving, sizeof moving, cube_tagged, "", false);
    cube_scene(still, sizeof still, cube_tagged, "", false);
    {
        float *a = render(moving, settings, true, 0), *b = render(still, NULL, false, 0);
        sl_compare c;
        sl_harness_compare(a, b, W, H, 0, &c);
        printf("t = 0 vs no plugin: max |diff| = %g\n", c.max_abs);
        CHECK(c.max_abs == 0, "t = 0 must be the static frame exactly (max diff %g)", c.max_abs);
        free(a), free(b);
    }
    /* ---- 4, 5. quarter period (frame 60 at 1/60 s = 1 s = 1/(4 f)) vs rotated static ---- */
    for (int spot = 0; spot < 2; spot++) {
        cube_scene(moving, sizeof moving, cube_tagged, "", spot);
        cube_scene(rotated, sizeof rotated, cube_rotated, "", spot);
        float *a = render(moving, settings, true, 60), *r = render(rotated, NULL, false, 60), *z = render(moving, settings, true, 0);
        sl_compare c, cz;
        sl_harness_compare(a, r, W, H, 0.03, &c);
        sl_harness_compare(a, z, W, H, 0.03, &cz);
        printf("%s quarter period vs cube rotated by scene transform: %ld pixels over 0.03 (rmse %.3g); vs rest: %ld\n",
               spot ? "[spot, shadows]" : "[sun]", c.pixels_over, c.rmse, cz.pixels_over);
        CHECK(c.pixels_over <= W * H / 200, "quarter period differs from the rotated cube in %ld pixels", c.pixels_over);
        CHECK(cz.pixels_over > W * H / 40, "the cube did not move (%ld pixels differ from rest)", cz.pixels_over);
        CHECK(c.nonfinite == 0 && cz.nonfinite == 0, "non-finite pixels");
        if (spot) {
            /* floor pixels only (the box's own pixels excluded): the shadow moved with the cube */
            sl_harness *hb = make(rotated, NULL, false);
            free(render_at(hb, 0));
            sl_harness_destroy(hb);
            long floor_moved = 0, floor_bad = 0;
            for (int i = 0; i < W * H; i++) {
                /* the floor is grey (r = g = b in base colour); the box is blue: b > 1.3 r */
                bool boxish = a[i * 4 + 2] > 1.3f * a[i * 4] + 1e-3f || z[i * 4 + 2] > 1.3f * z[i * 4] + 1e-3f ||
                              r[i * 4 + 2] > 1.3f * r[i * 4] + 1e-3f;
                if (boxish) continue;
                floor_moved += fabsf(a[i * 4] - z[i * 4]) > 0.03f;
                floor_bad += fabsf(a[i * 4] - r[i * 4]) > 0.03f;
            }
            printf("  floor: %ld pixels changed from rest (the shadow moved), %ld differ from the rotated static frame\n",
                   floor_moved, floor_bad);
            CHECK(floor_moved > W * H / 100, "the shadow on the floor did not move (%ld pixels)", floor_moved);
            CHECK(floor_bad <= W * H / 400, "the moved shadow differs from the rotated cube's in %ld floor pixels", floor_bad);
        }
        free(a), free(r), free(z);
    }

    /* ---- 6. colour at pulse 1 (t = 1/(2 f_c) = 2 s = frame 120 at f_c = 0.25) ---- */
    {
        const char *sph = "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40}],"
                          " \"materials\": [{\"name\": \"m\", \"base_color\": [0.6, 0.5, 0.4]%s}],"
                          " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1}, \"material\": \"m\"}],"
                          " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 3}]}";
        char with[2048], without[2048];
        snprintf(with, sizeof with, sph, ", \"nod_color\": [0.1, 0.9, 0.2]");
        snprintf(without, sizeof without, sph, "");
        const char *cs[] = {"nod.color_strength=0.7", "nod.color_frequency=0.25", "nod.color_center=0,0,1",
                            "nod.color_radius=0.8", NULL};
        float *a = render(with, cs, true, 120), *b = render(without, NULL, false, 120);
        const double base[3] = {0.6, 0.5, 0.4}, col[3] = {0.1, 0.9, 0.2}, s = 0.7;
        /* centre pixel: object position (0, 0, 1) exactly at the region's centre (weight 1) */
        int cx = W / 2, cy = H / 2;
        double worst = 0;
        for (int dy = -2; dy <= 2; dy++)
            for (int dx = -2; dx <= 2; dx++)
                for (int k = 0; k < 3; k++) {
                    int i = ((cy + dy) * W + cx + dx) * 4 + k;
                    double want = b[i] * ((1 - s) * base[k] + s * col[k]) / base[k];
                    worst = fmax(worst, fabs(a[i] - want) / want);
                }
        /* a pixel far from the region (the sphere's rim, |p - c| > r) is unchanged */
        int ri = (cy * W + cx + (int)(0.45 * H)) * 4;
        printf("colour at pulse 1: worst relative error at the centre %.3g; rim %g vs %g\n", worst, a[ri], b[ri]);
        CHECK(worst < 0.01, "recoloured centre off by %g (relative)", worst);
        CHECK(fabsf(a[ri] - b[ri]) <= 1e-6f * b[ri] + 1e-6f, "outside the region the colour changed (%g vs %g)", a[ri], b[ri]);
        free(a), free(b);
    }

    /* ---- 7. costs nothing ---- */
    {
        const char *untagged = "{\"name\": \"cube\", \"translate\": [0, 0.5, 0], \"mesh\": {\"primitive\": \"cube\", \"size\": 1}, \"material\": \"box\"}";
        cube_scene(still, sizeof still, untagged, "", false);
        const char *off[] = {"nod.enabled=false", NULL};
        sl_harness_structure s0, s1, s2;
        sl_harness *h = make(still, NULL, false);
        free(render_at(h, 30)), sl_harness_structure_of(h, &s0), sl_harness_destroy(h);
        h = make(still, NULL, true);
        free(render_at(h, 30)), sl_harness_structure_of(h, &s1), sl_harness_destroy(h);
        cube_scene(moving, sizeof moving, cube_tagged, "", false);
        h = make(moving, off, true);
        free(render_at(h, 30)), sl_harness_structure_of(h, &s2);
        sl_harness_destroy(h);
        sl_harness *h0 = make(moving, NULL, false);
        sl_harness_structure s3;
        free(render_at(h0, 30)), sl_harness_structure_of(h0, &s3), sl_harness_destroy(h0);
        CHECK(sl_harness_structure_equal(&s0, &s1), "on, but no tagged node and no nod_color: programs or passes differ");
        CHECK(sl_harness_structure_equal(&s2, &s3), "switched off: programs or passes differ from not loaded");
    }

    /* ---- stability: extreme settings give finite, non-negative pixels ---- */
    {
        const char *extreme[][8] = {
            {"nod.pose_time=0.25", "nod.amplitude=90", "nod.frequency=1", "nod.blend=0", NULL},
            {"nod.pose_time=0.25", "nod.amplitude=-90", "nod.frequency=1", "nod.blend=0.01", "nod.pivot=0,1.1,0", NULL},
            {"nod.pose_time=0.25", "nod.amplitude=90", "nod.frequency=1", "nod.pivot=1000000,0,0", "nod.blend=10", NULL},
            {"nod.pose_time=3", "nod.axis=0,0,0", "nod.region=0,0,0", "nod.color_radius=0", NULL},
        };
        cube_scene(moving, sizeof moving, cube_tagged, ", \"nod_color\": [0.9, 0.1, 0.1]", true);
        for (int k = 0; k < 4; k++) {
            float *img = render(moving, extreme[k], true, 0);
            long bad = sl_harness_count_nonfinite(img, W, H) + sl_harness_count_negative(img, W, H);
            CHECK(bad == 0, "extreme settings %d: %ld non-finite or negative values", k, bad);
            free(img);
        }
    }

    /* ---- 8. live equals fresh ---- */
    {
        cube_scene(moving, sizeof moving, cube_tagged, ", \"nod_color\": [0.9, 0.1, 0.1]", true);
        sl_harness *h = make(moving, settings, true);
        free(render_at(h, 45));
        char err[512];
        bool ok = sl_harness_set(h, "nod.amplitude=-40", err, sizeof err) && sl_harness_set(h, "nod.normals=rigid", err, sizeof err) &&
                  sl_harness_set(h, "nod.blend=0.4", err, sizeof err);
        CHECK(ok, "set: %s", err);
        float *live = render_at(h, 45);
        sl_harness_destroy(h);
        const char *fresh_set[] = {"nod.amplitude=-40", "nod.frequency=0.25", "nod.pivot=0,0,0", "nod.axis=1,0,0",
                                   "nod.region=0,1,0", "nod.blend=0.4", "nod.normals=rigid", NULL};
        float *fresh = render(moving, fresh_set, true, 45);
        sl_compare c;
        sl_harness_compare(live, fresh, W, H, 0, &c);
        CHECK(c.max_abs == 0, "live change differs from a fresh start (max %g)", c.max_abs);
        free(live), free(fresh);
    }
    printf(failures ? "FAILED (%d)\n" : "all nod checks passed\n", failures);
    return failures ? 1 : 0;
}
