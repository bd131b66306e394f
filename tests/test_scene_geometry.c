/* Procedural primitives, the Utah teapot and tangent generation (core/scene/primitives.c,
 * teapot.c, tangents.c): counts, bounds, the lat-long UV convention, unit normals, tangent
 * frames (orthogonal, |w| = 1, handedness), winding, and no NaN on degenerate input. */
#include "check.h"
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double dot3(const float *a, const float *b) { return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]; }
static double len3(const float *a) { return sqrt(dot3(a, a)); }
static void cross3(const float *a, const float *b, float *o) {
    o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Every vertex: finite, unit normal, unit tangent ⟂ normal, w = ±1. Returns failures. */
static int check_frames(const char *what, const sl_mesh_data *m) {
    int bad = 0;
    for (int i = 0; i < m->vertex_count; i++) {
        const float *p = m->positions + 3 * i, *n = m->normals + 3 * i, *t = m->tangents + 4 * i,
                    *uv = m->uvs + 2 * i;
        bool finite = isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) && isfinite(n[0]) && isfinite(n[1]) &&
                      isfinite(n[2]) && isfinite(t[0]) && isfinite(t[1]) && isfinite(t[2]) && isfinite(t[3]) &&
                      isfinite(uv[0]) && isfinite(uv[1]);
        bool ok = finite && fabs(len3(n) - 1) < 1e-5 && fabs(len3(t) - 1) < 1e-5 && fabs(dot3(n, t)) < 1e-4 &&
                  fabs(fabs(t[3]) - 1) == 0;
        if (!ok && bad++ < 5)
            fprintf(stderr, "%s: vertex %d: n = (%g %g %g) t = (%g %g %g %g)\n", what, i, n[0], n[1], n[2],
                    t[0], t[1], t[2], t[3]);
    }
    return bad;
}

/* Triangles whose geometric normal (CCW) disagrees with the mean of their vertex normals. */
static int count_flipped(const sl_mesh_data *m, int *degenerate) {
    int flipped = 0;
    *degenerate = 0;
    for (int t = 0; t < m->index_count / 3; t++) {
        const uint32_t *ix = m->indices + 3 * t;
        const float *a = m->positions + 3 * ix[0], *b = m->positions + 3 * ix[1], *c = m->positions + 3 * ix[2];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, g[3];
        cross3(e1, e2, g);
        float n[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int c2 = 0; c2 < 3; c2++) n[c2] += m->normals[3 * ix[k] + c2];
        if (len3(g) < 1e-12) {
            (*degenerate)++;
            continue;
        }
        flipped += dot3(g, n) <= 0;
    }
    return flipped;
}

static bool indices_in_range(const sl_mesh_data *m) {
    for (int i = 0; i < m->index_count; i++)
        if (m->indices[i] >= (uint32_t)m->vertex_count) return false;
    return m->index_count % 3 == 0;
}

static void test_sphere(void) {
    sl_mesh_data m;
    const int seg = 48, rings = 24;
    const float r = 2.5f;
    CHECK(sl_mesh_sphere(&m, r, seg, rings));
    CHECK(m.vertex_count == (seg + 1) * (rings + 1));
    CHECK(m.index_count == 3 * 2 * seg * (rings - 1)); /* one triangle per quad at the poles */
    CHECK(indices_in_range(&m));
    CHECK(check_frames("sphere", &m) == 0);
    int degenerate, flipped = count_flipped(&m, &degenerate);
    CHECK(flipped == 0 && degenerate == 0);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(m.bounds_min[c], -r, 1e-5);
        CHECK_NEAR(m.bounds_max[c], r, 1e-5);
    }
    double worst_n = 0, worst_u = 0, worst_v = 0;
    int wrong_w = 0;
    for (int i = 0; i < m.vertex_count; i++) {
        const float *p = m.positions + 3 * i, *n = m.normals + 3 * i, *uv = m.uvs + 2 * i;
        /* normal = normalised position */
        for (int c = 0; c < 3; c++) worst_n = fmax(worst_n, fabs(n[c] - p[c] / len3(p)));
        /* lat-long: v = θ/π with θ from +Y; u = φ/2π, φ = atan2(x, z) (undefined at the poles) */
        double theta = acos(fmax(-1.0, fmin(1.0, n[1])));
        worst_v = fmax(worst_v, fabs(uv[1] - theta / M_PI));
        if (sin(theta) > 1e-3) {
            double phi = atan2(n[0], n[2]);
            if (phi < 0) phi += 2 * M_PI;
            double du = fabs(uv[0] - phi / (2 * M_PI));
            du = fmin(du, fabs(du - 1)); /* the seam column has u = 1 */
            worst_u = fmax(worst_u, du);
        }
        wrong_w += m.tangents[4 * i + 3] != 1.0f;
    }
    CHECK_NEAR(worst_n, 0, 1e-6);
    CHECK_NEAR(worst_u, 0, 1e-6);
    CHECK_NEAR(worst_v, 0, 1e-6);
    CHECK(wrong_w == 0);
    /* known directions: (u, v) = (0, 0.5) faces +Z, (0.25, 0.5) +X, (0.5, 0.5) −Z, v = 0 is +Y */
    struct { int k, r; float d[3]; } known[] = {
        {0, rings / 2, {0, 0, 1}}, {seg / 4, rings / 2, {1, 0, 0}}, {seg / 2, rings / 2, {0, 0, -1}},
        {3 * seg / 4, rings / 2, {-1, 0, 0}}, {5, 0, {0, 1, 0}}, {7, rings, {0, -1, 0}}};
    for (int i = 0; i < 6; i++) {
        int v = known[i].r * (seg + 1) + known[i].k;
        for (int c = 0; c < 3; c++) CHECK_NEAR(m.normals[3 * v + c], known[i].d[c], 1e-6);
    }
    /* the tangent points toward increasing u: at +Z that is +X; at +X it is −Z */
    int front = (rings / 2) * (seg + 1), right = front + seg / 4;
    CHECK_NEAR(m.tangents[4 * front + 0], 1, 1e-6);
    CHECK_NEAR(m.tangents[4 * right + 2], -1, 1e-6);

    /* The analytic frames agree with the generator (same convention) away from the poles. At
     * the seam columns the generator sees triangles on one side only, so its tangent is the
     * chord direction, off by half a segment (3.75° at 48 segments): hence 0.995. */
    sl_mesh_data g = m;
    g.tangents = malloc(sizeof(float) * 4 * (size_t)m.vertex_count);
    memset(g.tangents, 0, sizeof(float) * 4 * (size_t)m.vertex_count);
    sl_mesh_generate_tangents(&g);
    int disagree = 0;
    for (int i = 0; i < m.vertex_count; i++) {
        int row = i / (seg + 1);
        if (row == 0 || row == rings) continue;
        if (dot3(g.tangents + 4 * i, m.tangents + 4 * i) < 0.995 || g.tangents[4 * i + 3] != m.tangents[4 * i + 3])
            disagree++;
    }
    CHECK(disagree == 0);
    CHECK(check_frames("sphere (generated)", &g) == 0);
    free(g.tangents);
    sl_mesh_free(&m);
    CHECK(m.positions == NULL && m.vertex_count == 0);
}

static void test_plane_cube_torus(void) {
    sl_mesh_data m;
    CHECK(sl_mesh_plane(&m, 4, 2, 3));
    CHECK(m.vertex_count == 16 && m.index_count == 3 * 18 && indices_in_range(&m));
    CHECK(check_frames("plane", &m) == 0);
    int degenerate;
    CHECK(count_flipped(&m, &degenerate) == 0 && degenerate == 0);
    CHECK(m.bounds_min[0] == -2 && m.bounds_max[0] == 2 && m.bounds_min[2] == -1 && m.bounds_max[2] == 1);
    CHECK(m.bounds_min[1] == 0 && m.bounds_max[1] == 0);
    for (int i = 0; i < m.vertex_count; i++) {
        CHECK(m.normals[3 * i + 1] == 1 && m.tangents[4 * i] == 1 && m.tangents[4 * i + 3] == 1);
        /* UVs tile 0..1: u follows +X, v follows +Z (image top at the far, −Z edge) */
        CHECK_NEAR(m.uvs[2 * i], m.positions[3 * i] / 4 + 0.5, 1e-6);
        CHECK_NEAR(m.uvs[2 * i + 1], m.positions[3 * i + 2] / 2 + 0.5, 1e-6);
    }
    /* the generator reproduces the plane's frames */
    memset(m.tangents, 0, sizeof(float) * 4 * (size_t)m.vertex_count);
    sl_mesh_generate_tangents(&m);
    for (int i = 0; i < m.vertex_count; i++) CHECK(m.tangents[4 * i] == 1 && m.tangents[4 * i + 3] == 1);
    sl_mesh_free(&m);

    CHECK(sl_mesh_cube(&m, 3));
    CHECK(m.vertex_count == 24 && m.index_count == 36 && indices_in_range(&m));
    CHECK(check_frames("cube", &m) == 0);
    CHECK(count_flipped(&m, &degenerate) == 0 && degenerate == 0);
    for (int c = 0; c < 3; c++) CHECK(m.bounds_min[c] == -1.5f && m.bounds_max[c] == 1.5f);
    for (int i = 0; i < m.vertex_count; i++) {
        CHECK_NEAR(dot3(m.normals + 3 * i, m.positions + 3 * i), 1.5, 1e-6); /* on its face */
        CHECK(m.uvs[2 * i] >= 0 && m.uvs[2 * i] <= 1 && m.uvs[2 * i + 1] >= 0 && m.uvs[2 * i + 1] <= 1);
    }
    /* per-face frames match the generator: every face is unmirrored */
    float saved[96];
    memcpy(saved, m.tangents, sizeof saved);
    sl_mesh_generate_tangents(&m);
    for (int i = 0; i < 24; i++) {
        CHECK(dot3(saved + 4 * i, m.tangents + 4 * i) > 0.9999);
        CHECK(m.tangents[4 * i + 3] == 1);
    }
    sl_mesh_free(&m);

    const float R = 2, r = 0.5f;
    CHECK(sl_mesh_torus(&m, R, r, 40, 20));
    CHECK(m.vertex_count == 41 * 21 && m.index_count == 3 * 2 * 40 * 20 && indices_in_range(&m));
    CHECK(check_frames("torus", &m) == 0);
    CHECK(count_flipped(&m, &degenerate) == 0 && degenerate == 0);
    CHECK_NEAR(m.bounds_max[0], R + r, 1e-5);
    CHECK_NEAR(m.bounds_min[2], -(R + r), 1e-5);
    CHECK_NEAR(m.bounds_max[1], r, 1e-3);
    CHECK_NEAR(m.bounds_min[1], -r, 1e-3);
    double worst = 0;
    for (int i = 0; i < m.vertex_count; i++) {
        const float *p = m.positions + 3 * i, *n = m.normals + 3 * i;
        double rho = sqrt((double)p[0] * p[0] + (double)p[2] * p[2]);
        float centre[3] = {(float)(R * p[0] / rho), 0, (float)(R * p[2] / rho)};
        float d[3] = {p[0] - centre[0], p[1], p[2] - centre[2]};
        worst = fmax(worst, fabs(len3(d) - r));                  /* on the tube */
        worst = fmax(worst, fabs(dot3(d, n) / len3(d) - 1));       /* normal points away from its centre */
    }
    CHECK_NEAR(worst, 0, 1e-5);
    float *analytic = malloc(sizeof(float) * 4 * (size_t)m.vertex_count);
    memcpy(analytic, m.tangents, sizeof(float) * 4 * (size_t)m.vertex_count);
    sl_mesh_generate_tangents(&m);
    int disagree = 0;
    for (int i = 0; i < m.vertex_count; i++)
        disagree += dot3(analytic + 4 * i, m.tangents + 4 * i) < 0.99 || analytic[4 * i + 3] != m.tangents[4 * i + 3];
    CHECK(disagree == 0);
    free(analytic);
    sl_mesh_free(&m);

    /* refused, without crashing or leaking, and the mesh stays zeroed */
    CHECK(!sl_mesh_sphere(&m, -1, 8, 8) && m.positions == NULL);
    CHECK(!sl_mesh_sphere(&m, NAN, 8, 8));
    CHECK(!sl_mesh_sphere(&m, 1, 2, 8));
    CHECK(!sl_mesh_sphere(&m, 1, 8, 1));
    CHECK(!sl_mesh_plane(&m, INFINITY, 1, 1));
    CHECK(!sl_mesh_plane(&m, 1, 1, 0));
    CHECK(!sl_mesh_cube(&m, 0));
    CHECK(!sl_mesh_torus(&m, 1, 0, 8, 8));
    CHECK(!sl_mesh_teapot(&m, 1, 0));
    CHECK(!sl_mesh_teapot(&m, -1, 4));
}

/* Largest x of the spout tip from the published control points: the patch row x-values
 * (3.3, 3.525, 3.45, 3.2) as a cubic Bézier, maximised by dense sampling. */
static double spout_tip_x(void) {
    double best = 0;
    for (int i = 0; i <= 100000; i++) {
        double t = i / 100000.0, s = 1 - t;
        double x = 3.3 * s * s * s + 3 * 3.525 * t * s * s + 3 * 3.45 * t * t * s + 3.2 * t * t * t;
        best = fmax(best, x);
    }
    return best;
}

static void test_teapot(void) {
    sl_mesh_data m;
    const int t = 12;
    const float size = 2.0f;
    CHECK(sl_mesh_teapot(&m, size, t));
    /* 32 patches of (t+1)² vertices; 2t² triangles each, minus t at each of the 8 patches
     * whose first row collapses to a point (lid knob top ×4, bottom centre ×4) */
    CHECK(m.vertex_count == 32 * (t + 1) * (t + 1));
    CHECK(m.index_count == 3 * (32 * 2 * t * t - 8 * t));
    CHECK(indices_in_range(&m));
    CHECK(check_frames("teapot", &m) == 0);
    int degenerate, flipped = count_flipped(&m, &degenerate);
    CHECK_MSG(flipped == 0 && degenerate == 0, "%d flipped, %d degenerate triangles", flipped, degenerate);
    /* extent of the published teapot (Z up: x −3..3.434, y −2..2, z 0..3.15), Y up, scaled to
     * height `size`: the corners that lie on the surface are exact, the spout tip is sampled */
    double s = size / 3.15;
    CHECK_NEAR(m.bounds_min[1], 0, 1e-6);
    CHECK_NEAR(m.bounds_max[1], 3.15 * s, 1e-5);
    CHECK_NEAR(m.bounds_min[0], -3.0 * s, 1e-5);
    CHECK_NEAR(m.bounds_min[2], -2.0 * s, 1e-5);
    CHECK_NEAR(m.bounds_max[2], 2.0 * s, 1e-5);
    double tip = spout_tip_x() * s;
    CHECK(m.bounds_max[0] <= tip + 1e-5);
    CHECK_NEAR(m.bounds_max[0], tip, 2e-3 * s); /* the tessellation can miss the exact maximum */
    /* every patch is laid out unmirrored */
    int mirrored = 0;
    for (int i = 0; i < m.vertex_count; i++) mirrored += m.tangents[4 * i + 3] != 1.0f;
    CHECK(mirrored == 0);
    /* outward normals: body patches (4..11) point away from the axis; the knob's tip up, the
     * bottom's centre down (both poles are degenerate in the patch data) */
    int side = t + 1, inward = 0;
    for (int p = 4; p < 12; p++)
        for (int k = 0; k < side * side; k++) {
            int v = p * side * side + k;
            float radial[3] = {m.positions[3 * v], 0, m.positions[3 * v + 2]};
            inward += dot3(radial, m.normals + 3 * v) <= 0;
        }
    CHECK(inward == 0);
    int knob = 20 * side * side, bottom = 28 * side * side;
    CHECK_NEAR(m.normals[3 * knob + 1], 1, 1e-3);
    CHECK_NEAR(m.positions[3 * knob + 1], 3.15 * s, 1e-5);
    CHECK_NEAR(m.normals[3 * bottom + 1], -1, 1e-3);
    CHECK_NEAR(m.positions[3 * bottom + 1], 0, 1e-6);
    sl_mesh_free(&m);

    CHECK(sl_mesh_teapot(&m, 1, 1)); /* coarsest: still valid */
    CHECK(check_frames("teapot t=1", &m) == 0 && indices_in_range(&m));
    sl_mesh_free(&m);
}

/* A quad facing +Z with UVs laid out as given, two triangles. */
static void make_quad(sl_mesh_data *m, const float uv[8]) {
    static const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    static const uint32_t ix[6] = {0, 1, 2, 0, 2, 3};
    sl_mesh_alloc(m, 4, 6);
    memcpy(m->positions, pos, sizeof pos);
    memcpy(m->uvs, uv, sizeof(float) * 8);
    memcpy(m->indices, ix, sizeof ix);
    for (int i = 0; i < 4; i++) m->normals[3 * i + 2] = 1;
}

static void test_tangent_generation(void) {
    sl_mesh_data m;
    /* upright image: u right (+X), v = 0 at the top (+Y): tangent +X, w = +1 */
    make_quad(&m, (const float[]){0, 1, 1, 1, 1, 0, 0, 0});
    sl_mesh_generate_tangents(&m);
    for (int i = 0; i < 4; i++) {
        CHECK_NEAR(m.tangents[4 * i], 1, 1e-6);
        CHECK_NEAR(m.tangents[4 * i + 1], 0, 1e-6);
        CHECK(m.tangents[4 * i + 3] == 1);
    }
    /* bitangent = w·cross(n, t) = +Y: up in the image (toward v = 0) */
    float b[3];
    cross3(m.normals, m.tangents, b);
    CHECK_NEAR(b[1] * m.tangents[3], 1, 1e-6);
    sl_mesh_free(&m);

    /* mirrored in u: tangent −X, w = −1 */
    make_quad(&m, (const float[]){1, 1, 0, 1, 0, 0, 1, 0});
    sl_mesh_generate_tangents(&m);
    for (int i = 0; i < 4; i++) {
        CHECK_NEAR(m.tangents[4 * i], -1, 1e-6);
        CHECK(m.tangents[4 * i + 3] == -1);
    }
    sl_mesh_free(&m);

    /* mirrored in v (v = 0 at the bottom, OpenGL style): tangent +X, w = −1 */
    make_quad(&m, (const float[]){0, 0, 1, 0, 1, 1, 0, 1});
    sl_mesh_generate_tangents(&m);
    for (int i = 0; i < 4; i++) CHECK(m.tangents[4 * i] > 0.999f && m.tangents[4 * i + 3] == -1);
    sl_mesh_free(&m);

    /* rotated layout: u runs along +Y → tangent +Y */
    make_quad(&m, (const float[]){0, 0, 0, 1, 1, 1, 1, 0});
    sl_mesh_generate_tangents(&m);
    for (int i = 0; i < 4; i++) CHECK_NEAR(m.tangents[4 * i + 1], 1, 1e-6);
    CHECK(check_frames("rotated quad", &m) == 0);
    sl_mesh_free(&m);

    /* all UVs equal (degenerate mapping): finite, orthogonal fallback */
    make_quad(&m, (const float[]){0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
    sl_mesh_generate_tangents(&m);
    CHECK(check_frames("degenerate UVs", &m) == 0);
    sl_mesh_free(&m);

    /* UVs on a line (zero UV area, non-zero positions) */
    make_quad(&m, (const float[]){0, 0, 0.5f, 0.5f, 1, 1, 0.25f, 0.25f});
    sl_mesh_generate_tangents(&m);
    CHECK(check_frames("collinear UVs", &m) == 0);
    sl_mesh_free(&m);

    /* zero-area triangles (all corners at one point) next to a good one; NaN UVs; a vertex
     * used by no triangle; out-of-range indices are ignored */
    sl_mesh_alloc(&m, 7, 12);
    float pos[21] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5};
    float uv[14] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, NAN, NAN};
    uint32_t ix[12] = {0, 1, 2, 3, 4, 5, 0, 4, 6, 1, 2, 99};
    memcpy(m.positions, pos, sizeof pos);
    memcpy(m.uvs, uv, sizeof uv);
    memcpy(m.indices, ix, sizeof ix);
    for (int i = 0; i < 7; i++) m.normals[3 * i + 2] = 1;
    m.normals[3 * 6] = NAN; /* a broken normal is repaired too */
    sl_mesh_generate_tangents(&m);
    m.uvs[12] = m.uvs[13] = 0; /* the NaN UVs were input: not the generator's to fix */
    CHECK(check_frames("zero-area", &m) == 0);
    CHECK_NEAR(m.tangents[4 * 3], 1, 1e-6); /* the good triangle: u along +X */
    sl_mesh_free(&m);

    /* sl_mesh_repair_frames: NaN and parallel tangents, zero normals, w = 0 */
    sl_mesh_alloc(&m, 3, 3);
    float p3[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    memcpy(m.positions, p3, sizeof p3);
    m.indices[0] = 0, m.indices[1] = 1, m.indices[2] = 2;
    m.normals[2] = 1, m.normals[5] = 2, m.normals[8] = 0; /* unit, too long, zero */
    float t3[12] = {NAN, 0, 0, 1, 0, 0, 5, -1, 1, 1, 0, 0};
    memcpy(m.tangents, t3, sizeof t3);
    int repaired = sl_mesh_repair_frames(&m);
    CHECK(repaired >= 3);
    CHECK(check_frames("repaired", &m) == 0);
    CHECK_NEAR(m.normals[8], 1, 1e-6); /* the zero normal became the face normal */
    CHECK(m.tangents[4 * 2 + 3] == 1); /* w = 0 → +1 */
    sl_mesh_free(&m);

    /* empty mesh: nothing to do, no crash */
    memset(&m, 0, sizeof m);
    sl_mesh_generate_tangents(&m);
    CHECK(sl_mesh_repair_frames(&m) == 0);
    sl_mesh_compute_bounds(&m);
}

int main(void) {
    test_sphere();
    test_plane_cube_torus();
    test_teapot();
    test_tangent_generation();
    return check_result();
}
