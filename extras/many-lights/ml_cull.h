/* many-lights: light ranges and the culling grids (CPU), shared by the plugin's passes.
 *
 * Range (README "Range"): a point or spot light of intensity I (colour × intensity, largest
 * channel) gives irradiance E = I/d²; it is cut off where E falls below ε·E_ref, E_ref = 1
 * (unit irradiance), so its range is r = sqrt(I / ε). Inside r the light is exact; beyond it
 * contributes nothing (the discontinuity is at most ε·E_ref per light).
 *
 * Cells. View space is the camera's (x right, y up, looking down -z); d = -z is the distance
 * along the view axis. A pixel column x (gl_FragCoord) maps to NDC 2x/W - 1 and, at distance d,
 * to view x = d·(ndc + P[2][0]) / P[0][0] (P the projection, column-major, jitter included).
 *   tiles     T×T pixels; the depth bounds [dmin, dmax] of the tile's pixels (tiled deferred)
 *   froxels   T×T pixel tiles × S slices exponential in d between near and far (Olsson, Billeter,
 *             Assarsson 2012, "Clustered deferred and forward shading", HPG): slice
 *             k = floor(log(d/near) · S / log(far/near)), clamped to [0, S-1]; slice 0 reaches
 *             down to d = 0 and slice S-1 out to d = far (scene bounds: nothing lies beyond).
 * A light belongs to a cell when its range sphere meets the cell's view-space bounding box (the
 * box of the cell's 8 frustum corners, in (x, y, d)): conservative, never misses a light. */
#ifndef ML_CULL_H
#define ML_CULL_H
#include <math.h>
#include <stdbool.h>

typedef struct ml_view {
    float view[16], proj[16]; /* column-major */
    int width, height;
} ml_view;

static inline float ml_range(const float color[3], float epsilon) {
    float I = fmaxf(color[0], fmaxf(color[1], color[2]));
    return I > 0 && epsilon > 0 ? sqrtf(I / epsilon) : 0;
}

/* Half-angle (radians) beyond which a spot's fall-off is exactly 0 (sdk/docs/conventions.md,
 * "Spot lights"): `linear` reaches 1.1·cone_angle, `gltf` the outer cone; 1° more for the
 * shader's float angle. cone_deg = cone_angle in degrees, mode 0 linear / 1 gltf. */
static inline float ml_spot_reach(float cone_deg, float mode) {
    float a = (mode > 0.5f ? cone_deg : 1.1f * cone_deg) + 1.0f;
    return a * 3.14159265f / 180;
}

/* Bounding sphere of a spot's lit region: its range sphere (apex p, radius r) cut by the cone of
 * half-angle a about the unit axis (B. Wronski 2017, "Cull that cone!"). The sector is convex for
 * a < 90°, so the farthest points from a centre on the axis are the apex and the cap's rim:
 *   a ≤ 45°: centre p + axis·r/(2 cos a), radius r/(2 cos a) (apex and rim equidistant);
 *   a > 45°: centre p + axis·r cos a, radius r sin a (the rim's circle; it holds the apex).
 * False for a ≥ 90° (the range sphere is as tight). */
static inline bool ml_spot_sphere(const float p[3], const float axis[3], float r, float a, float c[3], float *R) {
    if (!(a < 1.5707f) || !(r > 0)) return false;
    float l = sqrtf(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(l > 0)) return false;
    float t = a <= 0.7853982f ? r / (2 * cosf(a)) : r * cosf(a);
    *R = (a <= 0.7853982f ? t : r * sinf(a)) * 1.0001f + 1e-5f;
    for (int i = 0; i < 3; i++) c[i] = p[i] + axis[i] / l * t;
    return *R < r;
}

/* world → view (x, y, d = -z) */
static inline void ml_to_view(const ml_view *v, const float p[3], float out[3]) {
    const float *m = v->view;
    out[0] = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12];
    out[1] = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
    out[2] = -(m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]);
}

/* view-space bounding box (x, y, d) of the pixel rectangle [x0,x1]×[y0,y1] between d0 and d1 */
static inline void ml_cell_box(const ml_view *v, float x0, float x1, float y0, float y1, float d0, float d1,
                               float lo[3], float hi[3]) {
    const float *P = v->proj;
    float ax[2] = {(2 * x0 / v->width - 1 + P[8]) / P[0], (2 * x1 / v->width - 1 + P[8]) / P[0]};
    float ay[2] = {(2 * y0 / v->height - 1 + P[9]) / P[5], (2 * y1 / v->height - 1 + P[9]) / P[5]};
    float d[2] = {d0, d1};
    lo[0] = lo[1] = INFINITY, hi[0] = hi[1] = -INFINITY;
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) {
            lo[0] = fminf(lo[0], d[k] * ax[i]), hi[0] = fmaxf(hi[0], d[k] * ax[i]);
            lo[1] = fminf(lo[1], d[k] * ay[i]), hi[1] = fmaxf(hi[1], d[k] * ay[i]);
        }
    lo[2] = d0, hi[2] = d1;
}

static inline bool ml_sphere_box(const float c[3], float r, const float lo[3], const float hi[3]) {
    float s = 0;
    for (int i = 0; i < 3; i++) {
        float e = c[i] < lo[i] ? lo[i] - c[i] : c[i] > hi[i] ? c[i] - hi[i] : 0;
        s += e * e;
    }
    return s <= r * r;
}

/* Conservative pixel rectangle of a sphere (view-space centre c, radius r); false when the
 * sphere reaches behind the near distance dn (then it may cover the whole screen). */
static inline bool ml_sphere_rect(const ml_view *v, const float c[3], float r, float dn, float *x0, float *x1, float *y0,
                                  float *y1) {
    if (c[2] - r <= dn) return false;
    const float *P = v->proj;
    float nx0 = INFINITY, nx1 = -INFINITY, ny0 = INFINITY, ny1 = -INFINITY;
    for (int sx = -1; sx <= 1; sx += 2)
        for (int sd = -1; sd <= 1; sd += 2) {
            float d = c[2] + sd * r;
            float nx = P[0] * (c[0] + sx * r) / d - P[8], ny = P[5] * (c[1] + sx * r) / d - P[9];
            nx0 = fminf(nx0, nx), nx1 = fmaxf(nx1, nx), ny0 = fminf(ny0, ny), ny1 = fmaxf(ny1, ny);
        }
    *x0 = (nx0 + 1) * 0.5f * v->width, *x1 = (nx1 + 1) * 0.5f * v->width;
    *y0 = (ny0 + 1) * 0.5f * v->height, *y1 = (ny1 + 1) * 0.5f * v->height;
    return true;
}

/* Distance along the view axis of a depth-buffer value (GL conventions, [0,1]). */
static inline float ml_depth_to_d(const ml_view *v, float depth) {
    /* ndc_z = (P22·z + P32) / -z  →  d = -z = P32 / (ndc_z + P22) */
    return v->proj[14] / (2 * depth - 1 + v->proj[10]);
}
#endif
