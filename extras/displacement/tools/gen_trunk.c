/* gen_trunk: the demo's tree trunk as OBJ meshes (extras/displacement/README.md).
 *   gen_trunk OUT_DIR
 * writes OUT_DIR/trunk_side_low.obj, trunk_cap_low.obj (a 16-sided cylinder, 4 rings; the cap a polar
 * grid of 3 rings: what the GPU displaces) and trunk_side_high.obj, trunk_cap_high.obj (the same surfaces
 * finely tessellated and displaced here on the CPU with the heights of tests/height.h: bark
 * grooves on the side, growth rings on the cap; the reference). Radius 0.35 m, height 1.6 m,
 * standing on y = 0. Normals of the displaced meshes: cross product of the displaced surface's
 * partial derivatives (central differences). */
#include "../tests/height.h"
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#define R 0.35
#define HEIGHT 1.6
#define BARK_F 14.0
#define BARK_SCALE 0.03
#define RING_F 8.0
#define RING_SCALE 0.012
static const double PI = 3.14159265358979323846;

/* side: u around (φ = 2πu), v along the height (v = 0 at the top) */
static void side(double u, double v, bool displaced, double p[3]) {
    double phi = 2 * PI * u, h = displaced ? hf_h(HF_BARK, BARK_F, BARK_SCALE, u, v) : 0;
    p[0] = (R + h) * cos(phi), p[1] = HEIGHT * (1 - v), p[2] = -(R + h) * sin(phi);
}
/* cap: planar UVs, u along +X, v along +Z, centre (0.5, 0.5), rim at distance 0.5 */
static void cap(double u, double v, bool displaced, double p[3]) {
    double h = displaced ? hf_h(HF_RINGS, RING_F, RING_SCALE, u, v) : 0;
    p[0] = (u - 0.5) * 2 * R, p[1] = HEIGHT + h, p[2] = (v - 0.5) * 2 * R;
}

typedef void (*surface_fn)(double, double, bool, double[3]);

static void vertex(FILE *f, surface_fn s, double u, double v, bool displaced, double sign) {
    double p[3], a[3], b[3], c[3], d[3], e = 1e-5;
    s(u, v, displaced, p);
    s(u + e, v, displaced, a), s(u - e, v, displaced, b), s(u, v + e, displaced, c), s(u, v - e, displaced, d);
    double pu[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]}, pv[3] = {c[0] - d[0], c[1] - d[1], c[2] - d[2]};
    double n[3] = {pu[1] * pv[2] - pu[2] * pv[1], pu[2] * pv[0] - pu[0] * pv[2], pu[0] * pv[1] - pu[1] * pv[0]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len < 1e-30) n[0] = 0, n[1] = -1, n[2] = 0, len = 1; /* the cap's centre of a polar grid */
    /* OBJ texture rows run bottom-up: vt = (u, 1 − v) */
    fprintf(f, "v %.6f %.6f %.6f\nvn %.6f %.6f %.6f\nvt %.6f %.6f\n", p[0], p[1], p[2], sign * n[0] / len,
            sign * n[1] / len, sign * n[2] / len, u, 1 - v);
}

/* a (nu+1)×(nv+1) grid over the side's UV square */
static bool write_side(const char *path, int nu, int nv, bool displaced) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) vertex(f, side, (double)i / nu, (double)j / nv, displaced, -1);
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            int a = j * (nu + 1) + i + 1, b = a + 1, c = a + nu + 1, d = c + 1;
            fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\nf %d/%d/%d %d/%d/%d %d/%d/%d\n", a, a, a, c, c, c, b, b, b, b, b, b,
                    c, c, c, d, d, d);
        }
    return fclose(f) == 0;
}

/* a polar grid: `rings` circles of `segs` vertices around the centre vertex */
static bool write_cap(const char *path, int segs, int rings, bool displaced) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    vertex(f, cap, 0.5, 0.5, displaced, -1);
    for (int r = 1; r <= rings; r++)
        for (int s = 0; s < segs; s++) {
            double phi = 2 * PI * s / segs, rad = 0.5 * r / rings;
            vertex(f, cap, 0.5 + rad * cos(phi), 0.5 - rad * sin(phi), displaced, -1);
        }
    for (int r = 1; r <= rings; r++)
        for (int s = 0; s < segs; s++) {
            int s1 = (s + 1) % segs;
            int a = 2 + (r - 1) * segs + s, b = 2 + (r - 1) * segs + s1;
            if (r == 1) { fprintf(f, "f 1/1/1 %d/%d/%d %d/%d/%d\n", a, a, a, b, b, b); continue; }
            int c = a - segs, d = b - segs;
            fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\nf %d/%d/%d %d/%d/%d %d/%d/%d\n", c, c, c, a, a, a, b, b, b, c, c, c,
                    b, b, b, d, d, d);
        }
    return fclose(f) == 0;
}

int main(int argc, char **argv) {
    if (argc != 2) { fprintf(stderr, "usage: gen_trunk OUT_DIR\n"); return 2; }
    char p[4][1024];
    const char *names[4] = {"trunk_side_low.obj", "trunk_cap_low.obj", "trunk_side_high.obj", "trunk_cap_high.obj"};
    for (int i = 0; i < 4; i++) snprintf(p[i], sizeof p[i], "%s/%s", argv[1], names[i]);
    bool ok = write_side(p[0], 16, 4, false) && write_cap(p[1], 16, 3, false) && write_side(p[2], 384, 192, true) &&
              write_cap(p[3], 384, 96, true);
    if (!ok) { fprintf(stderr, "gen_trunk: cannot write into %s\n", argv[1]); return 1; }
    return 0;
}
