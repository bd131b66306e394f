/* A light's disk in a polished sphere (the core's angular_radius, sl_light_spread), for the shading
 * models' tests (ggx, phong): a sphere of radius R = 1 with the material `material_keys` (the
 * model and its keys, as JSON members) lit along the view by a directional light (E = 3) of angular
 * radius r_deg, seen from 40 m (nearly parallel rays) through a field of view of fov_deg, aa off.
 * On paper a mirror shows the disk where the normal is within r/2 of the view: a spot of radius
 * R sin(r/2). Gives the highlight's flux Σ L·(pixel area) and the half-maximum spot's radius
 * (from its area), red channel. */
#ifndef SL_TEST_DISK_HIGHLIGHT_H
#define SL_TEST_DISK_HIGHLIGHT_H
#include "check.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>

/* Renders scene `json` at w × h with `settings` (NULL-terminated) and writes the last of `frames`
 * frames (a TAA still) to px (RGBA floats); false, with a failed check, when it cannot. */
static inline bool sl_test_render_frames(const char *json, const char *const *settings, int w, int h, int frames,
                                         float *px) {
    char err[4096];
    sl_harness *hn = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w, .height = h,
                                                           .scene_json = json, .settings = settings, .float32 = true,
                                                           .strict = true}, err, sizeof err);
    CHECK_MSG(hn != NULL, "%s", err);
    if (!hn) return false;
    bool ok = true;
    for (int f = 1; f < frames; f++) ok = ok && sl_harness_render(hn, NULL);
    ok = ok && sl_harness_render(hn, px);
    CHECK(ok);
    sl_harness_destroy(hn);
    return ok;
}

/* As sl_test_disk_highlight, with the harness's settings (NULL-terminated; NULL: aa off), the
 * sphere moved by (dx, dy) m across the view, and the image the last of `frames` (a TAA still). */
static inline void sl_test_disk_highlight_at(const char *plugin, const char *material_keys, double r_deg, double fov_deg,
                                             const char *const *settings, int frames, double dx, double dy,
                                             double *flux, double *radius) {
    enum { DW = 96, DH = 96 };
    static float px[DW * DH * 4];
    char json[2048];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"%s\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 40], \"target\": [0, 0, 0], \"fov_y\": %g}],\n"
             " \"materials\": [{\"name\": \"m\", %s}],\n"
             " \"nodes\": [{\"name\": \"s\", \"translate\": [%g, %g, 0],"
             "   \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 256, \"rings\": 128},"
             "   \"material\": \"m\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 3,"
             "   \"angular_radius\": %g}]}", plugin, fov_deg, material_keys, dx, dy, r_deg);
    static const char *const aa_off[] = {"aa.enabled=false", NULL};
    if (!settings) settings = aa_off;
    *flux = *radius = 0;
    if (!sl_test_render_frames(json, settings, DW, DH, frames, px)) return;
    double pixel = 2 * 40 * tan(fov_deg / 2 * M_PI / 180) / DH, peak = 0, sum = 0, above = 0;
    for (int i = 0; i < DW * DH; i++) peak = fmax(peak, px[i * 4]);
    for (int i = 0; i < DW * DH; i++) sum += px[i * 4], above += px[i * 4] >= 0.5 * peak;
    *flux = sum * pixel * pixel;
    *radius = sqrt(above / M_PI) * pixel;
}
static inline void sl_test_disk_highlight(const char *plugin, const char *material_keys, double r_deg, double fov_deg,
                                          double *flux, double *radius) {
    sl_test_disk_highlight_at(plugin, material_keys, r_deg, fov_deg, NULL, 1, 0, 0, flux, radius);
}

/* The half-maximum spot's radius under a disk of r_deg, against R sin(r/2) within 15 %. */
static inline void sl_test_disk_radius(const char *plugin, const char *what, const char *material_keys, double r_deg,
                                       double fov_deg) {
    double flux, radius, expect = sin(r_deg / 2 * M_PI / 180);
    sl_test_disk_highlight(plugin, material_keys, r_deg, fov_deg, &flux, &radius);
    printf("%s, disk of %g deg: half-maximum radius %.5f, on paper R sin(r/2) = %.5f\n", what, r_deg, radius, expect);
    CHECK_MSG(fabs(radius / expect - 1) < 0.15, "%s: the highlight's radius %.5f is not R sin(r/2) = %.5f", what, radius,
              expect);
}

/* A disk keeps the highlight's energy: its flux under a disk of r_deg within 1 % of a point's. */
static inline void sl_test_disk_flux(const char *plugin, const char *what, const char *material_keys, double r_deg,
                                     double fov_deg) {
    double f0, f, r0, r;
    sl_test_disk_highlight(plugin, material_keys, 0, fov_deg, &f0, &r0);
    sl_test_disk_highlight(plugin, material_keys, r_deg, fov_deg, &f, &r);
    printf("%s: highlight flux %.5f for a point, %.5f for a disk of %g deg (ratio %.4f)\n", what, f0, f, r_deg, f / f0);
    CHECK_MSG(fabs(f / f0 - 1) < 0.01, "%s: the disk changed the highlight's flux by %.2f %%", what, 100 * (f / f0 - 1));
}
#endif
