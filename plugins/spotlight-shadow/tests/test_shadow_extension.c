/* The shadelab.shadow-maps/1 extension, used from another plugin (tests/shadow_consumer.c):
 * every map's texels, turned back into world points with the published view_proj and depth
 * convention, lie on the scene's surfaces (plane or sphere) for spot, directional and point
 * lights; the documented linear-depth formula and texel_world agree with the matrices; find()
 * agrees with get(); with shadows off there are no maps; a disabled provider gives NULL. */
#include "shadow_test.h"
#include "shadow_consumer.h"
#include <dlfcn.h>

int main(void) {
    const char *json =
        "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 4, 5], \"target\": [0, 0, 0], \"fov_y\": 50}],\n"
        " \"materials\": [{\"name\": \"m\", \"base_color\": [0.6, 0.6, 0.6]}],\n"
        " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 10}, \"material\": \"m\"},\n"
        "           {\"name\": \"ball\", \"translate\": [0, 1, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6, \"segments\": 128, \"rings\": 64}, \"material\": \"m\"}],\n"
        " \"lights\": [{\"name\": \"spot\", \"type\": \"spot\", \"position\": [1, 4, 0.5], \"direction\": [-0.25, -1, -0.12], \"intensity\": 30, \"cone_angle\": 35, \"cast_shadows\": true},\n"
        "  {\"name\": \"unshadowed\", \"type\": \"point\", \"position\": [3, 3, 3], \"intensity\": 5},\n"
        "  {\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0.3, -1, 0.2], \"intensity\": 2, \"cast_shadows\": true},\n"
        "  {\"name\": \"bulb\", \"type\": \"point\", \"position\": [-0.5, 2.4, 0.3], \"intensity\": 20, \"cast_shadows\": true}]}";
    char err[4096];
    const char *consumer = SS_CONSUMER_PATH;
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 64, .height = 48,
                                                         .scene_json = json, .strict = true,
                                                         .plugins = (const char *[]){"spotlight-shadow", consumer, NULL},
                                                         .settings = (const char *[]){"spotlight-shadow.map_size=512", NULL}},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();
    void *dl = dlopen(consumer, RTLD_NOW | RTLD_NOLOAD);
    const consumer_results *(*get)(void) = dl ? (const consumer_results *(*)(void))dlsym(dl, "shadow_consumer_results") : NULL;
    CHECK_MSG(get != NULL, "consumer plugin not loaded: %s", dlerror());
    if (!get) return check_result();
    static float img[64 * 48 * 4];
    CHECK(sl_harness_render(h, img));
    const consumer_results *r = get();
    CHECK(r->had_extension);
    /* spot 1 map, sun 1, bulb 6 faces; the unshadowed point light none */
    CHECK_MSG(r->count == 8, "%d maps", r->count);
    int on_sphere[3] = {0}, on_plane[3] = {0};
    double worst_off = 0, worst_depth = 0, worst_texel = 0;
    for (int i = 0; i < r->count; i++) {
        const consumer_map *c = &r->maps[i];
        int which = c->m.light == 0 ? 0 : c->m.light == 2 ? 1 : 2;
        CHECK(c->m.light == 0 || c->m.light == 2 || c->m.light == 3);
        CHECK(c->m.projection == (which == 1 ? SL_SHADOW_ORTHOGRAPHIC : SL_SHADOW_PERSPECTIVE));
        CHECK(c->m.size == 512 && c->m.texture != 0 && c->find_agrees);
        CHECK(which == 2 ? c->m.face == i - 2 : c->m.face == 0);
        worst_depth = fmax(worst_depth, c->depth_formula_error);
        worst_texel = fmax(worst_texel, c->texel_world_error);
        for (int k = 0; k < c->points; k++) {
            const float *p = c->p[k];
            double to_light = c->m.projection == SL_SHADOW_ORTHOGRAPHIC ? 1
                            : sqrt(pow(p[0] - c->m.position[0], 2) + pow(p[1] - c->m.position[1], 2) + pow(p[2] - c->m.position[2], 2));
            double tol = 4 * c->m.texel_world * to_light + 2e-3; /* depth quantisation, tessellation */
            double dp = fabs(p[1]), ds = fabs(sqrt(p[0] * p[0] + pow(p[1] - 1, 2) + p[2] * p[2]) - 0.6);
            if (dp < tol) on_plane[which]++;
            else if (ds < tol) on_sphere[which]++;
            else worst_off = fmax(worst_off, fmin(dp, ds));
        }
    }
    printf("extension: %d maps; points on the plane spot/sun/bulb %d/%d/%d, on the sphere %d/%d/%d; worst point off the "
           "surfaces %.2e m; linear-depth formula %.1e; texel_world %.1e (relative)\n",
           r->count, on_plane[0], on_plane[1], on_plane[2], on_sphere[0], on_sphere[1], on_sphere[2], worst_off, worst_depth,
           worst_texel);
    CHECK_MSG(worst_off == 0, "a map texel does not lie on the scene (%.3g m off)", worst_off);
    for (int k = 0; k < 3; k++) CHECK(on_plane[k] > 10 && on_sphere[k] > 2);
    CHECK(worst_depth < 1e-3 && worst_texel < 1e-5);

    /* maps re-rendered → version changes; shadows off → no maps; provider disabled → NULL */
    uint64_t v0 = r->version;
    CHECK(sl_harness_set(h, "light.spot.position=1,4,0.4", err, sizeof err) && sl_harness_render(h, NULL));
    CHECK(r->version != v0);
    CHECK(sl_harness_set(h, "spotlight-shadow.shadows=false", err, sizeof err) && sl_harness_render(h, NULL));
    CHECK_MSG(r->had_extension && r->count == 0, "shadows off still lists %d maps", r->count);
    CHECK(sl_harness_set(h, "spotlight-shadow.enabled=false", err, sizeof err) && sl_harness_render(h, NULL));
    CHECK_MSG(!r->had_extension, "a disabled provider still answers");
    sl_harness_destroy(h);
    return check_result();
}
