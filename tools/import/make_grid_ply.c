/* A binary little-endian PLY (or, for OUT.obj, a Wavefront OBJ) of an N×N vertex grid (2(N−1)²
 * triangles, gently rippled), for tools/import/bench_import.sh.
 *   usage: make_grid_ply N OUT.ply|OUT.obj */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv) {
    if (argc != 3) { fprintf(stderr, "usage: %s N OUT.ply\n", argv[0]); return 2; }
    int n = atoi(argv[1]);
    if (n < 2 || n > 20000) { fprintf(stderr, "N must be 2..20000\n"); return 2; }
    FILE *f = fopen(argv[2], "wb");
    if (!f) { perror(argv[2]); return 1; }
    long nv = (long)n * n, nf = 2L * (n - 1) * (n - 1);
    size_t len = strlen(argv[2]);
    if (len > 4 && !strcmp(argv[2] + len - 4, ".obj")) { /* text: v lines, then f lines (1-based) */
        fprintf(f, "# %ld vertices, %ld triangles\n", nv, nf);
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++)
                fprintf(f, "v %.6f %.6f %.6f\n", i / (float)(n - 1) * 2 - 1, 0.05f * sinf(i * 0.01f) * cosf(j * 0.013f),
                        j / (float)(n - 1) * 2 - 1);
        for (int j = 0; j < n - 1; j++)
            for (int i = 0; i < n - 1; i++) {
                long a = (long)j * n + i + 1, b = a + 1, c = a + n, d = c + 1;
                fprintf(f, "f %ld %ld %ld\nf %ld %ld %ld\n", a, c, b, b, c, d);
            }
        return fclose(f) == 0 ? 0 : 1;
    }
    fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %ld\nproperty float x\nproperty float y\n"
               "property float z\nelement face %ld\nproperty list uchar int vertex_indices\nend_header\n", nv, nf);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            float p[3] = {i / (float)(n - 1) * 2 - 1, 0.05f * sinf(i * 0.01f) * cosf(j * 0.013f), j / (float)(n - 1) * 2 - 1};
            fwrite(p, 4, 3, f);
        }
    for (int j = 0; j < n - 1; j++)
        for (int i = 0; i < n - 1; i++) {
            int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            unsigned char k = 3;
            int t1[3] = {a, c, b}, t2[3] = {b, c, d};
            fwrite(&k, 1, 1, f), fwrite(t1, 4, 3, f), fwrite(&k, 1, 1, f), fwrite(t2, 4, 3, f);
        }
    return fclose(f) == 0 ? 0 : 1;
}
