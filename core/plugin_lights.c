/* Lights that plugins add to the scene (plugin_lights.h). */
#include "plugin_lights.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

static bool valid_name(const char *s) {
    if (!s || !*s) return false;
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '-')) return false;
    return true;
}

int sl_plugin_light_add(sl_app *app, int plugin, const sl_plugin_light_desc *d, char *err, size_t n) {
    sl_plugin_light_desc desc = {0};
    memcpy(&desc, d, d->struct_size < sizeof desc ? d->struct_size : sizeof desc);
    const char *id = app->plugins.items[plugin]->id;
    if (app->light_params) {
        snprintf(err, n, "add_light: only in create()");
        return -1;
    }
    if (!valid_name(desc.name) || !desc.type) {
        snprintf(err, n, "add_light: the name \"%s\" is not [a-z0-9-]+ (or no type)", desc.name ? desc.name : "");
        return -1;
    }
    char full[256];
    snprintf(full, sizeof full, "%s.%s", id, desc.name);
    sl_scene *s = &app->scene;
    for (int i = 0; i < s->light_count; i++)
        if (!strcmp(s->lights[i].name, full)) {
            snprintf(err, n, "add_light: the scene has a light named \"%s\" already", full);
            return -1;
        }
    int li = sl_scene_add_light(s, full, desc.type);
    if (li < 0) {
        snprintf(err, n, "add_light: out of memory");
        return -1;
    }
    sl_light *L = &s->lights[li];
    L->plugin = plugin + 1;
    L->plugin_on = false; /* until set_light; L->enabled is the user's switch (light.NAME.enabled) */
    L->cast_shadows = desc.cast_shadows;
    for (int k = 0; desc.keys && desc.keys[k] && desc.keys[k + 1]; k += 2)
        if (!sl_prop_set_string(&L->props, desc.keys[k], desc.keys[k + 1], 0)) {
            snprintf(err, n, "add_light: out of memory");
            return -1;
        }
    return li;
}

static bool set_vec(float *to, const float *from, int count) {
    bool changed = memcmp(to, from, count * sizeof *to) != 0;
    memcpy(to, from, count * sizeof *to);
    return changed;
}

bool sl_plugin_light_set(sl_app *app, int plugin, int light, const sl_plugin_light_state *in) {
    if (light < 0 || light >= app->scene.light_count || app->scene.lights[light].plugin != plugin + 1) return false;
    sl_plugin_light_state st = {0};
    memcpy(&st, in, in->struct_size < sizeof st ? in->struct_size : sizeof st);
    sl_light *L = &app->scene.lights[light];
    float len = sqrtf(st.direction[0] * st.direction[0] + st.direction[1] * st.direction[1] +
                      st.direction[2] * st.direction[2]);
    float dir[3] = {0, -1, 0};
    if (len > 0 && isfinite(len))
        for (int c = 0; c < 3; c++) dir[c] = st.direction[c] / len;
    /* the ranges a scene's lights obey (colour <= 65504, intensity <= 1e10): finite in the shaders */
    float color[3], intensity = isfinite(st.intensity) && st.intensity > 0 ? fminf(st.intensity, 1e10f) : 0;
    for (int c = 0; c < 3; c++) color[c] = isfinite(st.color[c]) && st.color[c] > 0 ? fminf(st.color[c], 65504) : 0;
    bool changed = L->plugin_on != st.enabled;
    L->plugin_on = st.enabled;
    changed |= set_vec(L->position, st.position, 3);
    changed |= set_vec(L->direction, dir, 3);
    changed |= set_vec(L->color, color, 3);
    changed |= set_vec(&L->intensity, &intensity, 1);
    if (changed) app->plugin_lights_moved = true;
    return true;
}

static bool plugin_light_on(const sl_app *app, const sl_light *L) {
    return L->enabled && L->plugin_on && sl_plugin_enabled(&app->plugins, L->plugin - 1);
}

/* A plugin's shadow-casting directional light shines (a sun of its own: envmap's sky sun). */
static bool plugin_sun_on(const sl_app *app) {
    for (int i = 0; i < app->scene.light_count; i++) {
        const sl_light *L = &app->scene.lights[i];
        if (L->plugin && L->cast_shadows && !strcmp(L->type, "directional") && plugin_light_on(app, L)) return true;
    }
    return false;
}

bool sl_light_on(const sl_app *app, const sl_light *L) {
    if (L->plugin) return plugin_light_on(app, L);
    return L->enabled && !(L->stand_in && plugin_sun_on(app));
}

uint64_t sl_plugin_lights_owners_on(const sl_app *app) {
    uint64_t bits = 0;
    for (int i = 0; i < app->scene.light_count; i++) {
        int p = app->scene.lights[i].plugin - 1;
        if (p >= 0 && sl_plugin_enabled(&app->plugins, p)) bits |= 1ull << (p & 63);
    }
    return bits;
}
