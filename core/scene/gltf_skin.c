/* glTF skins (glTF 2.0 §3.7.3) as scene skins: for each skin a deformed mesh of the file uses, its
 * joints (scene nodes of the scene shown, each listed once) and inverse bind matrices (MAT4 float,
 * at least one per joint, finite; absent: identities). The meshes' sl_mesh_deform.skin, the glTF
 * skin while the nodes were made, becomes the scene skin's index. */
#include "scene/gltf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* glTF skin `gs` as scene skin *out (appended); false after gltf_fail. */
static bool make_skin(gltf_import *im, int gs, int *out) {
    gltf_doc *d = &im->doc;
    char at[48];
    snprintf(at, sizeof at, "/skins/%d", gs);
    const cJSON *skin = gltf_item(d, "skins", gs), *joints, *j;
    int ibm = -1;
    if (!gltf_get_array(d, skin, at, "joints", &joints) ||
        !gltf_get_index(d, skin, at, "inverseBindMatrices", "accessors", false, &ibm))
        return false;
    int n = cJSON_GetArraySize(joints), nodes = gltf_count(d, "nodes"), k = 0;
    sl_skin sk = {.joint_count = n, .joints = malloc(sizeof(int) * (size_t)n), .inverse_bind = NULL};
    if (!sk.joints) return gltf_fail(d, at, "out of memory");
    cJSON_ArrayForEach(j, joints) {
        char p[80];
        snprintf(p, sizeof p, "%s/joints/%d", at, k);
        double v = cJSON_IsNumber(j) ? j->valuedouble : -1;
        bool ok = v >= 0 && v < nodes && v == floor(v);
        if (!ok || im->nodes[(int)v] < 0) {
            free(sk.joints);
            return ok ? gltf_fail(d, p, "node %d is not in the scene shown (a skin's joints are)", (int)v)
                      : gltf_fail(d, p, "not an index of /nodes (%d elements)", nodes);
        }
        sk.joints[k] = im->nodes[(int)v];
        for (int e = 0; e < k; e++)
            if (sk.joints[e] == sk.joints[k]) {
                free(sk.joints);
                return gltf_fail(d, p, "node %d is listed twice (joints are unique)", (int)v);
            }
        k++;
    }
    int count = n;
    if (ibm >= 0) {
        char p[96];
        snprintf(p, sizeof p, "%s/inverseBindMatrices", at);
        if (!(sk.inverse_bind = gltf_read_floats(d, ibm, "MAT4", GLTF_F32, p, &count))) return free(sk.joints), false;
        if (count < n) {
            free(sk.joints), free(sk.inverse_bind);
            return gltf_fail(d, p, "%d matrices for %d joints (at least one per joint, §3.7.3.1)", count, n);
        }
        for (int i = 0; i < 16 * n; i++)
            if (!isfinite(sk.inverse_bind[i]) || fabsf(sk.inverse_bind[i]) > SL_SCENE_MAX_EXTENT) {
                gltf_fail(d, p, "matrix %d's element %d (%g) is not finite within ±%g", i / 16, i % 16, sk.inverse_bind[i],
                          SL_SCENE_MAX_EXTENT);
                return free(sk.joints), free(sk.inverse_bind), false;
            }
    } else if ((sk.inverse_bind = calloc((size_t)n * 16, sizeof(float)))) {
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 4; c++) sk.inverse_bind[16 * i + 5 * c] = 1;
    }
    sl_scene *s = im->scene;
    sl_skin *grown = sk.inverse_bind ? realloc(s->skins, sizeof *grown * (size_t)(s->skin_count + 1)) : NULL;
    if (!grown) return free(sk.joints), free(sk.inverse_bind), gltf_fail(d, at, "out of memory");
    s->skins = grown;
    s->skins[s->skin_count] = sk;
    *out = s->skin_count++;
    return true;
}

bool gltf_import_skins(gltf_import *im, int first_mesh) {
    int n = gltf_count(&im->doc, "skins");
    if (!n) return true;
    int *made = malloc(sizeof(int) * (size_t)n); /* glTF skin → scene skin (−1: not made) */
    if (!made) return gltf_fail(&im->doc, NULL, "out of memory");
    for (int i = 0; i < n; i++) made[i] = -1;
    bool ok = true;
    for (int m = first_mesh; ok && m < im->scene->mesh_count; m++) {
        sl_mesh_deform *d = im->scene->meshes[m].deform;
        if (!d || d->skin < 0) continue;
        if (made[d->skin] < 0) ok = make_skin(im, d->skin, &made[d->skin]);
        if (ok) d->skin = made[d->skin];
    }
    free(made);
    return ok;
}
