/* Additivity: with 32 spot lights (two in three shadowed) and two directional lights (one
 * shadowed) the linear float image equals the sum of the 34 single-light images within 1e-3
 * (every light has its own map layer, table row and lookup; a light reading another light's map,
 * a layer overwritten, or a light lost or counted twice by the core's casters' and others'
 * loops — the casters are packed first, in ranges of their own — breaks the sum). Then a light's
 * shadow switched off and on again live gives the first image back. */
#include "shadow_test.h"

#define W 64
#define H 48
#define NL 32
#define ND 2 /* directional lights: d0 casts, d1 does not */
static float all[W * H * 4], one[W * H * 4], sum[W * H * 4];

int main(void) {
    char lights[NL * 400], json[NL * 400 + 2048];
    size_t u = 0;
    unsigned seed = 12345;
    for (int k = 0; k < NL; k++) {
        seed = seed * 1103515245u + 12345u;
        double a = 2 * M_PI * k / NL, r = 2.5 + 1.5 * ((seed >> 16) % 1000) / 1000.0, hgt = 2.5 + (k % 5) * 0.4;
        double px = r * cos(a), pz = r * sin(a);
        double tx = 0.8 * cos(3 * a), tz = 0.8 * sin(2 * a); /* aims spread over the spheres */
        double c[3] = {0.3 + 0.7 * ((k * 37) % 11) / 10.0, 0.3 + 0.7 * ((k * 17) % 7) / 6.0, 0.3 + 0.7 * ((k * 29) % 5) / 4.0};
        u += snprintf(lights + u, sizeof lights - u,
                      "%s{\"name\": \"s%d\", \"type\": \"spot\", \"position\": [%.4f, %.4f, %.4f], \"direction\": [%.4f, %.4f, %.4f], "
                      "\"color\": [%.3f, %.3f, %.3f], \"intensity\": 3, \"cone_angle\": %d, \"falloff\": \"%s\", "
                      "\"inner_cone_angle\": 10, \"radius\": 0.1, \"cast_shadows\": %s}\n",
                      k ? "," : "", k, px, hgt, pz, tx - px, -hgt, tz - pz, c[0], c[1], c[2], 20 + k % 20, k % 2 ? "gltf" : "linear",
                      k % 3 == 2 ? "false" : "true");
        if (k == 10 || k == 20) /* between the spots in the scene's order */
            u += snprintf(lights + u, sizeof lights - u,
                          ",{\"name\": \"d%d\", \"type\": \"directional\", \"direction\": [%.2f, -1, -0.4], "
                          "\"intensity\": 0.4, \"cast_shadows\": %s}\n",
                          k / 20, k == 10 ? 0.5 : -0.6, k == 10 ? "true" : "false");
    }
    snprintf(json, sizeof json,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 5, 6], \"target\": [0, 0.3, 0], \"fov_y\": 50}],\n"
             " \"materials\": [{\"name\": \"m\", \"base_color\": [0.7, 0.7, 0.7]}, {\"name\": \"r\", \"base_color\": [0.8, 0.3, 0.2]}],\n"
             " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 12}, \"material\": \"m\"},\n"
             "   {\"name\": \"a\", \"translate\": [-0.8, 0.6, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6}, \"material\": \"r\"},\n"
             "   {\"name\": \"b\", \"translate\": [0.9, 0.4, 0.5], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.4}, \"material\": \"m\"},\n"
             "   {\"name\": \"box\", \"translate\": [0.3, 0.3, -0.9], \"rotate\": [0, 25, 0], \"mesh\": {\"primitive\": \"cube\", \"size\": 0.6}, \"material\": \"r\"}],\n"
             " \"lights\": [%s]}", lights);
    for (int f = 0; f < 4; f++) {
        char fs[64];
        snprintf(fs, sizeof fs, "spotlight-shadow.filter=%s", ss_filters[f]);
        sl_harness *h = ss_make(W, H, json, (const char *[]){"spotlight-shadow.map_size=512", fs, NULL});
        CHECK(h != NULL);
        if (!h) return check_result();
        CHECK(sl_harness_render(h, all));
        memset(sum, 0, sizeof sum);
        for (int k = 0; k < NL + ND; k++) {
            for (int j = 0; j < NL + ND; j++)
                CHECK(ss_set(h, "light.%c%d.enabled=%s", j < NL ? 's' : 'd', j < NL ? j : j - NL, j == k ? "true" : "false"));
            CHECK(sl_harness_render(h, one));
            for (int i = 0; i < W * H * 4; i++) sum[i] += one[i];
        }
        sl_compare c;
        sl_harness_compare(all, sum, W, H, 1e-3, &c);
        double peak = 0;
        for (int i = 0; i < W * H * 4; i++)
            if (i % 4 != 3) peak = fmax(peak, all[i]);
        /* the shadows are there: all lights with shadows off differs */
        static float noshadow[W * H * 4];
        for (int j = 0; j < NL + ND; j++) CHECK(ss_set(h, "light.%c%d.enabled=true", j < NL ? 's' : 'd', j < NL ? j : j - NL));
        /* a light's shadow off and on again, live: the first image (the casters are repacked) */
        static float again[W * H * 4];
        sl_compare e, e_off;
        CHECK(ss_set(h, "light.s0.cast_shadows=false") && sl_harness_render(h, noshadow));
        sl_harness_compare(all, noshadow, W, H, 1e-6, &e_off);
        CHECK(ss_set(h, "light.s0.cast_shadows=true") && sl_harness_render(h, again));
        sl_harness_compare(all, again, W, H, 1e-6, &e);
        CHECK_MSG(e_off.pixels_over > 0, "light s0's shadow switched off changed nothing");
        CHECK_MSG(e.max_abs <= 1e-6, "s0's shadow off and on again: max difference %g from the first image", e.max_abs);
        CHECK(ss_set(h, "spotlight-shadow.shadows=false") && sl_harness_render(h, noshadow));
        sl_compare d;
        sl_harness_compare(all, noshadow, W, H, 1e-2, &d);
        printf("%-7s 32 spots and 2 directional lights (23 casting) vs the sum of 34 single-light images: max difference %.2e (peak radiance %.2f), "
               "%ld pixels over 1e-3; %ld pixels differ from the unshadowed image\n",
               ss_filters[f], c.max_abs, peak, c.pixels_over, d.pixels_over);
        CHECK_MSG(c.max_abs < 1e-3, "not additive: max difference %g", c.max_abs);
        CHECK(c.nonfinite == 0 && peak > 0.2);
        CHECK_MSG(d.pixels_over > 100, "no visible shadows (%ld pixels)", d.pixels_over);
        sl_harness_destroy(h);
    }
    return check_result();
}
