/* sl-imgdiff A B [--same TOL] [--differ MIN] [--region x0 y0 x1 y1]
 * Image comparison for the shell-driven tests (SDK install, GUI smoke): loads both files (PNG,
 * EXR, … through the core's OpenImageIO loader, values as stored) and compares RGB.
 *   --same TOL     pass when max |a-b| <= TOL (identical within the tolerance)
 *   --differ MIN   pass when mean |a-b| >= MIN (a visible change, not noise)
 *   --region …     compare only the pixels x0 <= x < x1, y0 <= y < y1 (row 0 = top)
 * Prints rmse, max and mean differences and the verdict; exit 0 = pass, 1 = fail, 2 = error. */
#include "image/image.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv) {
    if (argc < 5) {
        fprintf(stderr, "usage: %s A B --same TOL | --differ MIN [--region x0 y0 x1 y1]\n", argv[0]);
        return 2;
    }
    double same = -1, differ = -1;
    int rx0 = 0, ry0 = 0, rx1 = 1 << 30, ry1 = 1 << 30;
    for (int i = 3; i < argc; i++) {
        if (!strcmp(argv[i], "--same") && i + 1 < argc) same = atof(argv[++i]);
        else if (!strcmp(argv[i], "--differ") && i + 1 < argc) differ = atof(argv[++i]);
        else if (!strcmp(argv[i], "--region") && i + 4 < argc) {
            rx0 = atoi(argv[++i]); ry0 = atoi(argv[++i]); rx1 = atoi(argv[++i]); ry1 = atoi(argv[++i]);
        } else { fprintf(stderr, "unknown argument %s\n", argv[i]); return 2; }
    }
    sl_image a, b;
    char err[1024];
    if (!sl_image_load(&a, argv[1], err, sizeof err) || !sl_image_load(&b, argv[2], err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    if (a.width != b.width || a.height != b.height) {
        fprintf(stderr, "FAIL: sizes differ: %s is %dx%d, %s is %dx%d\n", argv[1], a.width, a.height, argv[2], b.width, b.height);
        return 1;
    }
    if (rx1 > a.width) rx1 = a.width;
    if (ry1 > a.height) ry1 = a.height;
    double sum = 0, sq = 0, mx = 0;
    long n = 0, nonfinite = 0;
    for (int y = ry0; y < ry1; y++)
        for (int x = rx0; x < rx1; x++)
            for (int c = 0; c < 3; c++) {
                size_t i = ((size_t)y * a.width + x) * 4 + c;
                double d = fabs((double)a.pixels[i] - b.pixels[i]);
                if (!isfinite(d)) { nonfinite++; continue; }
                sum += d; sq += d * d; n++;
                if (d > mx) mx = d;
            }
    double mean = n ? sum / n : 0, rmse = n ? sqrt(sq / n) : 0;
    bool ok = nonfinite == 0 && (same < 0 || mx <= same) && (differ < 0 || mean >= differ);
    printf("%s: %s vs %s [%d,%d)x[%d,%d): rmse %.6f  max %.6f  mean %.6f  non-finite %ld  (%s%g)\n", ok ? "PASS" : "FAIL",
           argv[1], argv[2], rx0, rx1, ry0, ry1, rmse, mx, mean, nonfinite, same >= 0 ? "same within max " : "differ by mean >= ",
           same >= 0 ? same : differ);
    sl_image_free(&a);
    sl_image_free(&b);
    return ok ? 0 : 1;
}
