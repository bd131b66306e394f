/* shadelab against Cycles on the default scene and the IBL spheres (issue 40 item 4): each
 * object's distance from the reference may not grow beyond today's. Bounds are today's figures
 * (160×90, 256 Cycles samples, 8 bounces, the reference cached) with a margin for the shadelab
 * side's run-to-run spread: relative RMS ≤ 1.15 × today + 0.02 and |1 − mean ratio| ≤ today's +
 * 0.03. Better is always allowed; a regression fails and names the object. Blender missing:
 * exit 77 (skipped). 256 samples, not 32: the sun's reflection in the mirror sphere is a
 * sub-pixel spot that 32 samples resolve poorly (a 15 × 15 window round it sums 125 at 32
 * samples, 186 at 1024), so a bound at 32 bounded the reference's noise, not shadelab. The IBL
 * spheres' smooth spheres reflect the floor and each other (envmap.reflections=screen in the
 * scene) and the sky's sun casts shadows (spotlight-shadow): with the sky alone in the
 * reflections the bounds fail on sg0, sg1 and smirror. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "test_tmp.h"

#define SKIP 77

typedef struct bound { const char *object; double rel_rms, ratio; } bound;

/* today's figures (shadelab-xcheck --size 160x90 --samples 256: the converged still) */
static const bound default_scene[] = {
    {"floor", 0.160, 1.037}, {"teapot", 0.190, 0.919}, {"rough_95", 0.127, 0.968}, {"rough_65", 0.109, 1.005},
    {"rough_35", 0.097, 1.010}, {"rough_10", 0.311, 1.033}, {"gold", 0.398, 0.946}, {NULL, 0, 0}};
static const bound ibl_spheres[] = {
    {"floor", 0.206, 0.996}, {"sd0", 0.586, 0.775}, {"sd1", 0.193, 0.833}, {"sd2", 0.186, 0.822},
    {"sd3", 0.192, 0.811}, {"sg0", 0.301, 0.800}, {"sg1", 0.282, 0.870}, {"sg2", 0.567, 0.800},
    {"sg3", 0.117, 0.921}, {"smirror", 0.241, 1.030}, {"swhite", 0.178, 0.831}, {NULL, 0, 0}};

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
        double rr_max = 1.15 * b->rel_rms + 0.02, off_max = fabs(1 - b->ratio) + 0.03;
        printf("%-22s %-9s rel-RMS %.3f (bound %.3f)  mean ratio %.3f (|1 - r| bound %.3f)\n", scene, b->object, rr,
               rr_max, ratio, off_max);
        CHECK_MSG(rr >= 0 && rr <= rr_max, "%s: %s: relative RMS %.4f above %.4f", scene, b->object, rr, rr_max);
        CHECK_MSG(fabs(1 - ratio) <= off_max, "%s: %s: mean ratio %.4f, more than %.3f from 1", scene, b->object, ratio,
                  off_max);
    }
    cJSON_Delete(doc);
}

int main(void) {
    check_scene("scenes/default.json", default_scene);
    check_scene("scenes/ibl_spheres.json", ibl_spheres);
    return check_result();
}
