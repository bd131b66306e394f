/* ABI 1.6: the vertex-hook node filter (sl_shader_chunk_desc.when_node_tag, the scene's node
 * "tags", inherited by children) and SlSurface.object_position, with the tp-tagged test plugin.
 *  - A hook gated on tag "lift" raising object-space y by 0.5 moves exactly the meshes under the
 *    tagged node: the frame equals a frame without the key whose tagged node is translated by
 *    +0.5 in y by its scene transform instead (an independent path: the node matrix), while an
 *    untagged node sharing the same material (same program) stays where it was.
 *  - object_position is the rest pose: on the lifted unit sphere |object_position| = 1 (the
 *    displaced position would be 0.5 off), checked on every covered pixel.
 *  - bad "tags" are refused naming the cause; when_node_tag on a SURFACE hook is refused
 *    (tp-tagged-bad registers one: the plugin is refused). */
#include <shadelab/harness.h>
#include "check.h"
#include <stdlib.h>

#define W 160
#define H 96

static const char *scene_fmt =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0.8, 7], \"target\": [0, 0.3, 0], \"fov_y\": 40}],"
    " \"materials\": [{\"name\": \"m\", \"base_color\": [0.8, 0.7, 0.6]%s}],"
    " \"nodes\": [{\"name\": \"a\", \"translate\": [-1.4, %s, 0]%s, \"children\": ["
    "              {\"name\": \"a-mesh\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1}, \"material\": \"m\"}]},"
    "            {\"name\": \"b\", \"translate\": [1.4, 0, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1}, \"material\": \"m\"}],"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.3, -1, -0.5], \"intensity\": 3}]}";

static sl_harness *make(const char *json, const char *view, char *err, size_t n) {
    const char *plugins[] = {TP_TAGGED_PATH, NULL};
    sl_harness_desc d = {.struct_size = sizeof d, .width = W, .height = H, .scene_json = json, .plugins = plugins,
                         .strict = true, .debug_view = view};
    return sl_harness_create(&d, err, n);
}

static float *render(const char *json, const char *view) {
    char err[4096];
    sl_harness *h = make(json, view, err, sizeof err);
    if (!h) { fprintf(stderr, "harness: %s\n", err); exit(1); }
    float *img = malloc(sizeof(float) * W * H * 4);
    if (!sl_harness_render(h, img)) { fprintf(stderr, "render failed\n"); exit(1); }
    sl_harness_destroy(h);
    return img;
}

int main(void) {
    char moved[4096], ref[4096], still[4096];
    snprintf(moved, sizeof moved, scene_fmt, ", \"tp_tag_lift\": 0.5", "0", ", \"tags\": [\"lift\"]");
    snprintf(ref, sizeof ref, scene_fmt, "", "0.5", "");
    snprintf(still, sizeof still, scene_fmt, "", "0", "");
    float *a = render(moved, NULL), *b = render(ref, NULL), *c = render(still, NULL);
    sl_compare cmp;
    sl_harness_compare(a, b, W, H, 0.02, &cmp);
    printf("hook on tagged node vs node translated: rmse %.3g, %ld pixels over 0.02\n", cmp.rmse, cmp.pixels_over);
    CHECK_MSG(cmp.pixels_over <= W * H / 200, "%ld pixels differ", cmp.pixels_over);
    CHECK(cmp.nonfinite == 0);
    sl_harness_compare(a, c, W, H, 0.02, &cmp);
    CHECK_MSG(cmp.pixels_over > W * H / 50, "the hook did not move the tagged node (%ld pixels differ)", cmp.pixels_over);
    /* the untagged node b (right half) is untouched: same program, mask bit clear */
    long diff_right = 0;
    for (int y = 0; y < H; y++)
        for (int x = W / 2 + 8; x < W; x++)
            for (int k = 0; k < 3; k++) diff_right += fabsf(a[(y * W + x) * 4 + k] - c[(y * W + x) * 4 + k]) > 0.02f;
    CHECK_MSG(diff_right == 0, "untagged node moved: %ld channel values differ", diff_right);
    free(a), free(b), free(c);

    /* object_position on the lifted sphere: the rest pose, |p| = radius 1 */
    float *p = render(moved, "tp-object-position");
    long covered = 0, bad = 0;
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W / 2 - 8; x++) {
            const float *q = &p[(y * W + x) * 4];
            double r = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2]);
            if (r < 0.3) continue; /* background (black) */
            covered++;
            double e = fabs(r - 1.0);
            worst = e > worst ? e : worst;
            bad += e > 0.02; /* the sphere's facets: chord sag of a 64-segment sphere is < 0.002 */
        }
    printf("object_position: %ld covered pixels, worst | |p| - 1 | = %.4g\n", covered, worst);
    CHECK_MSG(covered > 500, "only %ld pixels of the lifted sphere", covered);
    CHECK_MSG(bad == 0, "%ld pixels with | |object_position| - 1 | > 0.02 (worst %.3g)", bad, worst);
    free(p);

    /* bad tags name the cause */
    char err[4096], badscene[4096];
    snprintf(badscene, sizeof badscene, scene_fmt, "", "0", ", \"tags\": [\"Bad Tag\"]");
    sl_harness *h = make(badscene, NULL, err, sizeof err);
    CHECK(h == NULL);
    if (h) sl_harness_destroy(h);
    else CHECK_CONTAINS(err, "tag 'Bad Tag' must be");
    snprintf(badscene, sizeof badscene, scene_fmt, "", "0", ", \"tags\": \"lift\"");
    h = make(badscene, NULL, err, sizeof err);
    CHECK(h == NULL);
    if (h) sl_harness_destroy(h);
    else CHECK_CONTAINS(err, "\"tags\" must be an array");
    /* a SURFACE chunk with when_node_tag: refused, so the plugin does not load (strict) */
    const char *bad_plugin[] = {TP_TAGGED_BAD_PATH, NULL};
    sl_harness_desc bd = {.struct_size = sizeof bd, .width = 16, .height = 16, .plugins = bad_plugin, .strict = true};
    h = sl_harness_create(&bd, err, sizeof err);
    CHECK(h == NULL);
    if (h) sl_harness_destroy(h);
    else CHECK_CONTAINS(err, "registration was refused");
    return check_result();
}
