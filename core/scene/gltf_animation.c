/* glTF animations (glTF 2.0 §3.11): one animation's node TRS channels as scene channels
 * (sl_anim_channel; the renderer samples them per appendix C). Checked per channel: a sampler and
 * a target path, key times finite, non-negative and strictly increasing, one output per key (three
 * for CUBICSPLINE; weights: one per morph target of the node's mesh per key), every value finite.
 * A channel that fails is not played and named; so are channels without a target node
 * (KHR_animation_pointer's), on nodes outside the scene, TRS on nodes given by a matrix, and
 * weights on nodes without morph targets. */
#include "scene/gltf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The node's rest translation, rotation and scale (the defaults where absent). */
static void rest_pose(gltf_import *im, int gn, sl_anim_node *rest) {
    const cJSON *node = gltf_item(&im->doc, "nodes", gn);
    gltf_get_numbers(&im->doc, node, "", "translation", 3, rest->t, NULL); /* checked by the node's import */
    gltf_get_numbers(&im->doc, node, "", "rotation", 4, rest->r, NULL);
    gltf_get_numbers(&im->doc, node, "", "scale", 3, rest->s, NULL);
    double len = sqrt((double)rest->r[0] * rest->r[0] + (double)rest->r[1] * rest->r[1] + (double)rest->r[2] * rest->r[2] +
                      (double)rest->r[3] * rest->r[3]);
    if (len < 1e-6) rest->r[0] = rest->r[1] = rest->r[2] = 0, rest->r[3] = 1, len = 1;
    for (int c = 0; c < 4; c++) rest->r[c] = (float)(rest->r[c] / len);
}

static bool add_channel(gltf_import *im, const sl_anim_channel *ch, int gn) {
    sl_scene *s = im->scene;
    sl_anim_channel *grown = realloc(s->anim_channels, sizeof *grown * (size_t)(s->anim_channel_count + 1));
    if (!grown) return gltf_fail(&im->doc, NULL, "out of memory");
    s->anim_channels = grown;
    s->anim_channels[s->anim_channel_count++] = *ch;
    if (ch->times[ch->key_count - 1] > s->anim_duration) s->anim_duration = ch->times[ch->key_count - 1];
    if (ch->path == SL_ANIM_WEIGHTS) return true; /* no rest pose: weights go to the node's meshes */
    for (int a = 0; a < s->anim_node_count; a++)
        if (s->anim_nodes[a].node == ch->node) return true;
    sl_anim_node *an = realloc(s->anim_nodes, sizeof *an * (size_t)(s->anim_node_count + 1));
    if (!an) return gltf_fail(&im->doc, NULL, "out of memory");
    s->anim_nodes = an;
    sl_anim_node rest = {.node = ch->node, .r = {0, 0, 0, 1}, .s = {1, 1, 1}};
    rest_pose(im, gn, &rest);
    s->anim_nodes[s->anim_node_count++] = rest;
    return true;
}

/* The morph target count of the deformed meshes scene node n draws (their primitives have one
 * count, §3.7.2.2), or 0. */
static int morph_targets_of(gltf_import *im, int n) {
    const sl_node *node = &im->scene->nodes[n];
    for (int k = 0; k < node->mesh_count; k++) {
        const sl_mesh_deform *d = im->scene->meshes[node->meshes[k]].deform;
        if (d && d->target_count) return d->target_count;
    }
    return 0;
}

/* Key times (input) and values (output) of a sampler, checked: 1 usable, 0 not (noted), −1 after
 * gltf_fail. */
static int read_keys(gltf_import *im, const cJSON *smp, const char *sp, int path, int interp, sl_anim_channel *ch) {
    gltf_doc *d = &im->doc;
    int in = -1, out = -1, nt = 0, nv = 0, comps = path == SL_ANIM_WEIGHTS ? ch->components : path == SL_ANIM_ROTATION ? 4 : 3;
    char ip[128], op[128];
    snprintf(ip, sizeof ip, "%s/input", sp);
    snprintf(op, sizeof op, "%s/output", sp);
    if (!gltf_get_index(d, smp, sp, "input", "accessors", true, &in) || !gltf_get_index(d, smp, sp, "output", "accessors", true, &out))
        return -1;
    /* §3.11: rotations and weights may be normalized integers */
    unsigned formats = GLTF_F32 | (path == SL_ANIM_ROTATION || path == SL_ANIM_WEIGHTS ? GLTF_NORMALIZED : 0) |
                       (gltf_uses_extension(d, "KHR_mesh_quantization") ? GLTF_NORMALIZED | GLTF_INTEGERS : 0);
    const char *type = path == SL_ANIM_WEIGHTS ? "SCALAR" : comps == 4 ? "VEC4" : "VEC3";
    if (!(ch->times = gltf_read_floats(d, in, "SCALAR", GLTF_F32, ip, &nt)) ||
        !(ch->values = gltf_read_floats(d, out, type, formats, op, &nv)))
        return -1;
    if (path == SL_ANIM_WEIGHTS) { /* one value per target per key */
        if (nv % comps) {
            gltf_note(d, op, "%d values are not a whole number of keys of %d weights: channel not played", nv, comps);
            return 0;
        }
        nv /= comps;
    }
    ch->key_count = nt;
    if ((im->keys += nt) > GLTF_MAX_KEYS)
        return gltf_fail(d, ip, "%lld animation keys in all, over the %d shadelab reads", im->keys, GLTF_MAX_KEYS), -1;
    for (int k = 0; k < nt; k++)
        if (!isfinite(ch->times[k]) || ch->times[k] < 0 || (k && !(ch->times[k] > ch->times[k - 1]))) {
            gltf_note(d, ip, "key %d's time %g is not finite, non-negative and after the previous one: channel not played",
                      k, ch->times[k]);
            return 0;
        }
    if (nv != nt * (interp == SL_ANIM_CUBICSPLINE ? 3 : 1)) {
        gltf_note(d, op, "%d values for %d keys%s: channel not played", nv, nt, interp == SL_ANIM_CUBICSPLINE ? " (CUBICSPLINE: 3 per key)" : "");
        return 0;
    }
    for (int i = 0; i < nv * comps; i++)
        if (!isfinite(ch->values[i])) {
            gltf_note(d, op, "value %d is not finite: channel not played", i / comps);
            return 0;
        }
    return 1;
}

/* Channel k of the animation at `at`; false after gltf_fail (a channel not played is a note). */
static bool channel(gltf_import *im, const cJSON *ch, const cJSON *samplers, const char *at, int k) {
    gltf_doc *d = &im->doc;
    char cp[96], tp[128], sp[96];
    snprintf(cp, sizeof cp, "%s/channels/%d", at, k);
    snprintf(tp, sizeof tp, "%s/target", cp);
    const cJSON *target;
    long long sampler = -1, gn = -1;
    const char *path = "", *is = "LINEAR";
    if (!cJSON_IsObject(ch)) return gltf_fail(d, cp, "must be an object");
    if (!gltf_get_int(d, ch, cp, "sampler", 0, cJSON_GetArraySize(samplers) - 1, &sampler) ||
        !gltf_get_object(d, ch, cp, "target", &target) || !gltf_get_int(d, target, tp, "node", 0, gltf_count(d, "nodes") - 1, &gn) ||
        !gltf_get_string(d, target, tp, "path", &path))
        return false;
    if (sampler < 0 || !target) return gltf_fail(d, cp, "sampler and target are required");
    int kind = !strcmp(path, "translation") ? SL_ANIM_TRANSLATION : !strcmp(path, "rotation") ? SL_ANIM_ROTATION
             : !strcmp(path, "scale") ? SL_ANIM_SCALE : !strcmp(path, "weights") ? SL_ANIM_WEIGHTS : -1;
    if (kind < 0 || gn < 0) return gltf_note(d, tp, "path \"%.40s\"%s: channel not played", path, gn < 0 ? " without a node" : ""), true;
    if (im->nodes[gn] < 0) return gltf_note(d, tp, "node %lld is not in the scene shown: channel not played", gn), true;
    int targets = kind == SL_ANIM_WEIGHTS ? morph_targets_of(im, im->nodes[gn]) : 0;
    if (kind == SL_ANIM_WEIGHTS && targets <= 0)
        return gltf_note(d, tp, "node %lld draws no mesh with morph targets: channel not played", gn), true;
    if (kind != SL_ANIM_WEIGHTS && cJSON_GetObjectItemCaseSensitive(gltf_item(d, "nodes", (int)gn), "matrix"))
        return gltf_note(d, tp, "node %lld is given by a matrix, which animations may not target: channel not played", gn), true;
    snprintf(sp, sizeof sp, "%s/samplers/%lld", at, sampler);
    const cJSON *smp = cJSON_GetArrayItem(samplers, (int)sampler);
    if (!cJSON_IsObject(smp)) return gltf_fail(d, sp, "must be an object");
    if (!gltf_get_string(d, smp, sp, "interpolation", &is)) return false;
    int interp = !strcmp(is, "STEP") ? SL_ANIM_STEP : !strcmp(is, "CUBICSPLINE") ? SL_ANIM_CUBICSPLINE
               : !strcmp(is, "LINEAR") ? SL_ANIM_LINEAR : -1;
    if (interp < 0) return gltf_fail(d, sp, "interpolation \"%.20s\" is not LINEAR, STEP or CUBICSPLINE", is);
    sl_anim_channel c = {.node = im->nodes[gn], .path = kind, .interpolation = interp, .components = targets};
    int usable = read_keys(im, smp, sp, kind, interp, &c);
    if (usable > 0 && add_channel(im, &c, (int)gn)) return true;
    free(c.times), free(c.values);
    return usable == 0;
}

bool gltf_import_animation(gltf_import *im, int which) {
    gltf_doc *d = &im->doc;
    int count = gltf_count(d, "animations");
    if (which < 0 && count > 1) gltf_note(d, "/animations", "%d animations: the first is played (--animation picks another)", count);
    if (which < 0) which = 0;
    if (which >= count) return true;
    char at[48];
    snprintf(at, sizeof at, "/animations/%d", which);
    const cJSON *anim = gltf_item(d, "animations", which), *channels, *samplers, *ch;
    if (!cJSON_IsObject(anim)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_array(d, anim, at, "channels", &channels) || !gltf_get_array(d, anim, at, "samplers", &samplers)) return false;
    if (!channels || !samplers) return gltf_fail(d, at, "channels and samplers are required");
    int k = 0;
    cJSON_ArrayForEach(ch, channels) if (!channel(im, ch, samplers, at, k++)) return false;
    return true;
}
