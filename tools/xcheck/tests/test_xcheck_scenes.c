/* shadelab against Cycles on the default scene and the IBL spheres (issue 40 item 4): each
 * object's distance from the reference may not grow beyond today's. Bounds are today's figures
 * (160×90, 256 Cycles samples, 8 bounces, the reference cached) with a margin for the shadelab
 * side's run-to-run spread: relative RMS ≤ 1.15 × today + 0.02 and |1 − mean ratio| ≤ today's +
 * 0.03, FLIP ≤ 1.15 × today + 0.02 (it sees structure the means do not: a reflection's pattern).
 * Better is always allowed; a regression fails and names the object. Blender missing:
 * exit 77 (skipped). 256 samples, not 32: the sun's reflection in the mirror sphere is a
 * sub-pixel spot that 32 samples resolve poorly (a 15 × 15 window round it sums 125 at 32
 * samples, 186 at 1024), so a bound at 32 bounded the reference's noise, not shadelab. The IBL
 * spheres' smooth spheres reflect the floor and each other (envmap.reflections=screen in the
 * scene), the sky's sun casts shadows (spotlight-shadow) and the sky's ground is the lit floor's
 * radiance: with the sky alone in the reflections sg0's and smirror's FLIP fail (0.282, 0.272),
 * with the sky's default dark ground every rough sphere's and the white one's ratio (0.81-0.83).
 * The sun's glint on the polished spheres (rough_10, gold, sg0) is smaller than a pixel: ggx
 * filters D over each pixel's footprint of normals, so the still holds its energy: rough_10's
 * glint sums 8.2 over its 5 × 5 pixels, as Cycles'; gold's glint, about a pixel wide, is
 * filtered at the pixel's centre (ABI 1.28): its relative RMS 0.107 (0.145 with the footprint
 * where the jitter put it, 0.398 with point samples of D), sg0's 0.444 (its glint sums 28.9 over
 * 3 pixels, Cycles' 31.2 at 2048 samples). The still's jitter averages to the pixel's centre
 * (aa): the mirror sphere 0.174 -> 0.127, rough_10 0.206 -> 0.161.
 * And with --eevee, the report's per-object EEVEE figures against their definition; with --noise,
 * each object's noise: 0 where every sample is the same frame, above 0 where the samples differ,
 * -1 (not measured) without it. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "test_tmp.h"
#include "toolkit.h"

#define SKIP 77

typedef struct bound { const char *object; double rel_rms, ratio, flip; } bound;

/* today's figures (shadelab-xcheck --size 160x90 --samples 256: the converged still) */
static const bound default_scene[] = {
    {"floor", 0.155, 1.029, 0.126}, {"teapot", 0.196, 0.907, 0.139}, {"rough_95", 0.131, 0.964, 0.213},
    {"rough_65", 0.113, 1.000, 0.175}, {"rough_35", 0.102, 1.008, 0.145}, {"rough_10", 0.161, 1.103, 0.205},
    {"gold", 0.107, 0.996, 0.301}, {NULL, 0, 0, 0}};
static const bound ibl_spheres[] = {
    {"floor", 0.216, 0.995, 0.098}, {"sd0", 0.587, 0.845, 0.165}, {"sd1", 0.094, 0.941, 0.116},
    {"sd2", 0.084, 0.948, 0.125}, {"sd3", 0.061, 0.953, 0.104}, {"sg0", 0.444, 0.878, 0.242},
    {"sg1", 0.237, 0.897, 0.247}, {"sg2", 0.551, 0.929, 0.242}, {"sg3", 0.107, 1.071, 0.172},
    {"smirror", 0.127, 0.953, 0.209}, {"swhite", 0.042, 0.984, 0.110}, {NULL, 0, 0, 0}};

static char *read_text(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = malloc((size_t)n + 1);
    if (t && fread(t, 1, (size_t)n, f) == (size_t)n) t[n] = 0;
    else { free(t); t = NULL; }
    fclose(f);
    return t;
}

static void check_scene(const char *scene, const bound *bounds) {
    char out[4096], cmd[9000], report[4200];
    const char *base = strrchr(scene, '/') + 1;
    snprintf(out, sizeof out, "%s/%.*s", sl_test_dir(), (int)(strlen(base) - 5), base);
    snprintf(cmd, sizeof cmd, "'%s' --size 160x90 --samples 256 --out '%s' '%s/%s'", SL_XCHECK_EXE, out, SL_SOURCE_DIR, scene);
    int status = system(cmd);
    if (WIFEXITED(status) && WEXITSTATUS(status) == SKIP) {
        fprintf(stderr, "SKIPPED: Blender is not installed (tools/install-deps.sh --with-tests installs it)\n");
        exit(SKIP);
    }
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s: shadelab-xcheck failed (%d)", scene, status);
    snprintf(report, sizeof report, "%s/report.json", out);
    char *text = read_text(report);
    cJSON *doc = text ? cJSON_Parse(text) : NULL;
    free(text);
    CHECK_MSG(doc, "%s: no readable %s", scene, report);
    const cJSON *objects = cJSON_GetObjectItemCaseSensitive(doc, "objects");
    for (const bound *b = bounds; b->object; b++) {
        const cJSON *o = NULL, *it;
        cJSON_ArrayForEach(it, objects) {
            const cJSON *name = cJSON_GetObjectItemCaseSensitive(it, "name");
            if (cJSON_IsString(name) && !strcmp(name->valuestring, b->object)) o = it;
        }
        CHECK_MSG(o, "%s: object %s missing from the report", scene, b->object);
        if (!o) continue;
        double rr = cJSON_GetObjectItemCaseSensitive(o, "rel_rms")->valuedouble;
        double ratio = cJSON_GetObjectItemCaseSensitive(o, "mean_ratio")->valuedouble;
        double flip = cJSON_GetObjectItemCaseSensitive(o, "flip")->valuedouble;
        const cJSON *noise = cJSON_GetObjectItemCaseSensitive(o, "noise");
        CHECK_MSG(cJSON_IsNumber(noise) && noise->valuedouble == -1, "%s: %s: noise not -1 without --noise", scene, b->object);
        double rr_max = 1.15 * b->rel_rms + 0.02, off_max = fabs(1 - b->ratio) + 0.03, flip_max = 1.15 * b->flip + 0.02;
        printf("%-22s %-9s rel-RMS %.3f (bound %.3f)  mean ratio %.3f (|1 - r| bound %.3f)  FLIP %.3f (bound %.3f)\n",
               scene, b->object, rr, rr_max, ratio, off_max, flip, flip_max);
        CHECK_MSG(flip >= 0 && flip <= flip_max, "%s: %s: FLIP %.4f above %.4f", scene, b->object, flip, flip_max);
        CHECK_MSG(rr >= 0 && rr <= rr_max, "%s: %s: relative RMS %.4f above %.4f", scene, b->object, rr, rr_max);
        CHECK_MSG(fabs(1 - ratio) <= off_max, "%s: %s: mean ratio %.4f, more than %.3f from 1", scene, b->object, ratio,
                  off_max);
    }
    cJSON_Delete(doc);
}

/* EEVEE per object (--eevee 1, on scenes/aa_edges.json at 96×54, 32 samples): the report lists
 * EEVEE's figures for every object the report's own table lists, in its order, and each relative
 * RMS is the definition's, recomputed here from the written images: sqrt(Σ(e − c)²/Σc²) over
 * R, G, B of the object's interior (its pixels whose four neighbours are it too). */
static void check_eevee_objects(void) {
    char out[4096], cmd[9000], path[4200], err[512];
    snprintf(out, sizeof out, "%s/eevee", sl_test_dir());
    snprintf(cmd, sizeof cmd, "'%s' --size 96x54 --samples 32 --eevee 1 --out '%s' '%s/scenes/aa_edges.json' > /dev/null",
             SL_XCHECK_EXE, out, SL_SOURCE_DIR);
    int status = system(cmd);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "aa_edges with --eevee 1: shadelab-xcheck failed (%d)", status);
    snprintf(path, sizeof path, "%s/report.json", out);
    char *text = read_text(path);
    cJSON *doc = text ? cJSON_Parse(text) : NULL;
    free(text);
    CHECK_MSG(doc, "no readable %s", path);
    if (!doc) return;
    sl_image ee = {0}, cy = {0}, ix = {0};
    bool ok = true;
    const char *names[3] = {"eevee-1.exr", "cycles.exr", "index.exr"};
    sl_image *imgs[3] = {&ee, &cy, &ix};
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/%s", out, names[i]);
        ok = ok && sl_image_load(imgs[i], path, err, sizeof err);
    }
    CHECK_MSG(ok, "%s", err);
    const cJSON *objects = cJSON_GetObjectItemCaseSensitive(doc, "objects");
    const cJSON *eevee = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(doc, "eevee"), 0);
    const cJSON *eo = cJSON_GetObjectItemCaseSensitive(eevee, "objects");
    CHECK_MSG(cJSON_GetArraySize(eo) == cJSON_GetArraySize(objects) && cJSON_GetArraySize(objects) == 2,
              "EEVEE lists %d objects, the report %d", cJSON_GetArraySize(eo), cJSON_GetArraySize(objects));
    int w = cy.width, h = cy.height;
    for (int i = 0; ok && i < cJSON_GetArraySize(objects) && i < cJSON_GetArraySize(eo); i++) {
        const cJSON *a = cJSON_GetArrayItem(objects, i), *b = cJSON_GetArrayItem(eo, i);
        const char *an = cJSON_GetObjectItemCaseSensitive(a, "name")->valuestring;
        const char *bn = cJSON_GetObjectItemCaseSensitive(b, "name")->valuestring;
        CHECK_MSG(!strcmp(an, bn), "EEVEE's object %d is %s, the report's %s", i, bn, an);
        double d2 = 0, c2 = 0;
#define IDX(x, y) ((int)lroundf(ix.pixels[((size_t)(y) * w + (x)) * 4]))
        for (int y = 1; y < h - 1; y++)
            for (int x = 1; x < w - 1; x++) {
                int k = i + 1;
                if (IDX(x, y) != k || IDX(x - 1, y) != k || IDX(x + 1, y) != k || IDX(x, y - 1) != k || IDX(x, y + 1) != k)
                    continue;
                for (int c = 0; c < 3; c++) {
                    size_t p = ((size_t)y * w + x) * 4 + c;
                    d2 += (ee.pixels[p] - cy.pixels[p]) * (ee.pixels[p] - cy.pixels[p]), c2 += cy.pixels[p] * cy.pixels[p];
                }
            }
#undef IDX
        double want = sqrt(d2 / c2), got = cJSON_GetObjectItemCaseSensitive(b, "rel_rms")->valuedouble;
        printf("EEVEE 1 on aa_edges: %-8s relative RMS %.5f (recomputed %.5f)\n", bn, got, want);
        CHECK_MSG(fabs(got - want) <= 1e-4 * want + 1e-6, "%s: EEVEE's relative RMS %.6f, recomputed %.6f", bn, got, want);
    }
    for (int i = 0; i < 3; i++) sl_image_free(imgs[i]);
    cJSON_Delete(doc);
}

/* The noise (--noise 4, on scenes/ibl_spheres.json at 96×54, 32 Cycles samples, aa off, one
 * frame): with specular=dominant every sample is the same frame, so every object's noise is 0
 * exactly; with specular=filtered sample k reads the set turned by R2(k), so a glossy sphere's
 * interior scatters (noise above 0). A small prefiltered cube (32², 64 samples): what is measured
 * is the noise, not the cube's accuracy; the default one cost 3 of the check's 12 s. */
static void noise_of(const char *specular, cJSON **doc) {
    char out[4096], cmd[9000], path[4200];
    snprintf(out, sizeof out, "%s/noise-%s", sl_test_dir(), specular);
    snprintf(cmd, sizeof cmd, "'%s' --size 96x54 --samples 32 --frames 1 --noise 4 --set aa.enabled=false "
             "--set envmap.specular=%s --set envmap.cube_size=32 --set envmap.samples=64 "
             "--out '%s' '%s/scenes/ibl_spheres.json' > /dev/null",
             SL_XCHECK_EXE, specular, out, SL_SOURCE_DIR);
    int status = system(cmd);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "ibl_spheres, %s, --noise 4: shadelab-xcheck failed (%d)",
              specular, status);
    snprintf(path, sizeof path, "%s/report.json", out);
    char *text = read_text(path);
    *doc = text ? cJSON_Parse(text) : NULL;
    free(text);
    CHECK_MSG(*doc, "no readable %s", path);
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(*doc, "noise_samples");
    CHECK_MSG(cJSON_IsNumber(n) && n->valueint == 4, "%s: noise_samples is not 4", path);
}

static double object_noise(const cJSON *o) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, "noise");
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static void check_noise(void) {
    cJSON *dominant = NULL, *filtered = NULL;
    noise_of("dominant", &dominant);
    noise_of("filtered", &filtered);
    if (!dominant || !filtered) { cJSON_Delete(dominant); cJSON_Delete(filtered); return; }
    const cJSON *it;
    int count = 0;
    cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(dominant, "objects")) {
        const char *name = cJSON_GetObjectItemCaseSensitive(it, "name")->valuestring;
        double v = object_noise(it);
        CHECK_MSG(v == 0, "ibl_spheres, dominant: %s's noise %g, expected 0 (one frame whatever the sample)", name, v);
        count++;
    }
    CHECK_MSG(count == 11, "ibl_spheres, dominant: %d objects in the report, expected 11", count);
    cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(filtered, "objects")) {
        const char *name = cJSON_GetObjectItemCaseSensitive(it, "name")->valuestring;
        double v = object_noise(it);
        printf("ibl_spheres, filtered, --noise 4: %-8s noise %.6f\n", name, v);
        if (!strcmp(name, "sg1")) CHECK_MSG(v > 0, "ibl_spheres, filtered: sg1's noise %g, expected above 0", v);
    }
    cJSON_Delete(dominant);
    cJSON_Delete(filtered);
}

int main(void) {
    check_scene("scenes/default.json", default_scene);
    check_eevee_objects();
    check_noise();
    check_scene("scenes/ibl_spheres.json", ibl_spheres);
    return check_result();
}
