/* cascades: cascaded shadow maps for directional lights (issue 23). See README.md.
 *
 * The camera's view frustum, from its near plane to `max_distance` (or its far plane), is cut
 * into `count` slices at the practical split scheme of Zhang et al. 2006 ("Parallel-split
 * shadow maps for large-scale virtual environments", VRCIA; eq. for C_i^practical):
 *     s_i = λ · n (f/n)^(i/N) + (1 − λ) · (n + (f − n) i/N),   i = 0..N
 * (λ = 1 logarithmic, λ = 0 uniform). Each slice gets an orthographic map of the light
 * (Dimitrov 2007, "Cascaded Shadow Maps", NVIDIA), rendered and filtered by spotlight-shadow:
 * this plugin only supplies the views through the SDK extension "shadelab.shadow-maps/2"
 * (set_view_provider), and spotlight-shadow's SHADOW hook picks the map by camera depth and
 * fades into the next one over the last `blend` fraction of a slice.
 *
 * Stabilisation (Valient 2008, "Stable Rendering of Cascaded Shadow Maps", ShaderX6): each map
 * covers the slice's bounding sphere, whose radius depends only on the slice bounds and the lens
 * (not on where the camera is or where it looks), so the texel size never changes; the sphere's
 * centre, in light space, is snapped to whole texels, so the texel grid stays fixed in the world
 * and a moving camera re-rasterises the casters at exactly the same texel positions (no shimmer).
 * Off (`stabilize=false`): each map is the tight square around the slice's corners in light
 * space, as a fitted map is — sharper, but the grid slides and scales with the camera.
 *
 * Maps depend on the camera: spotlight-shadow's shadow pass hashes the views this plugin returns,
 * so it re-renders when a (snapped) view moves and is skipped when none did. */
#include <shadelab/shadelab.h>
#include <shadelab/ext/shadow_maps.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ID "cascades"
#define MARGIN_TEXELS 8.0f /* map border kept for filter kernels and the snap (≤ 1 texel) */

typedef struct cascades {
    const sl_host *host;
    const sl_ext_shadow_maps *sm;
    bool installed, install_failed;
} cascades;

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "count", .type = SL_PARAM_INT, .default_value = {.i = 4}, .min = 1, .max = 4, .step = 1,
      .flags = SL_PARAM_QUALITY_KNOB, .group = "cascades",
      .description = "Number of cascades (maps) per shadowed directional light, each spotlight-shadow.map_size square."),
    P(.id = "lambda", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.8f}}, .min = 0, .max = 1, .step = 0.05f,
      .flags = SL_PARAM_QUALITY_KNOB, .group = "cascades",
      .description = "Split scheme (Zhang et al.): 1 = logarithmic splits, 0 = uniform, between = the practical blend."),
    P(.id = "blend", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.1f}}, .min = 0, .max = 0.5f, .step = 0.01f,
      .group = "cascades",
      .description = "Fraction of each slice, before its far split, over which its shadow fades into the next cascade's."),
    P(.id = "stabilize", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "cascades",
      .description = "Bounding spheres + texel snapping: shadow edges stay put while the camera moves (off: tight fits)."),
    P(.id = "max_distance", .type = SL_PARAM_FLOAT, .default_value = {.f = {0}}, .min = 0, .max = 100000, .step = 1,
      .unit = "m", .group = "cascades", .zero_label = "far plane",
      .description = "Shadows end at this camera depth; 0 = the camera's far plane."),
};

static const sl_shader_chunk_desc debug_chunk = {
    .struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "cascades_debug.glsl",
    .function = "cascades_debug", .name = "cascades",
    .description = "cascade of each pixel: red, green, blue, yellow (mixed across the blend bands), grey beyond"};

static const sl_key_desc keys[] = {
    {.struct_size = sizeof(sl_key_desc), .key = "K", .param = "stabilize", .description = "cascades: stabilisation on/off"},
};

static sl_value param(const cascades *c, const char *id) {
    char full[64];
    snprintf(full, sizeof full, ID ".%s", id);
    return c->host->get_param(c->host, full);
}

/* Practical split distance i of n (Zhang et al. 2006). */
static double split_at(int i, int n, double znear, double zfar, double lambda) {
    double x = (double)i / n;
    return lambda * znear * pow(zfar / znear, x) + (1 - lambda) * (znear + (zfar - znear) * x);
}

static void cross3(const double a[3], const double b[3], double o[3]) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void normalize3(double a[3]) {
    double l = sqrt(dot3(a, a));
    if (l > 0) for (int i = 0; i < 3; i++) a[i] /= l;
}

/* Column-major orthographic projection (glOrtho). */
static void ortho(float m[16], double l, double r, double b, double t, double n, double f) {
    memset(m, 0, 16 * sizeof *m);
    m[0] = (float)(2 / (r - l));
    m[5] = (float)(2 / (t - b));
    m[10] = (float)(-2 / (f - n));
    m[12] = (float)(-(r + l) / (r - l));
    m[13] = (float)(-(t + b) / (t - b));
    m[14] = (float)(-(f + n) / (f - n));
    m[15] = 1;
}

static int views(void *user, const sl_frame *f, int light, int map_size, sl_shadow_view *out, int max) {
    cascades *c = user;
    if (!param(c, "enabled").b) return 0; /* switched off: spotlight-shadow's own fitted map */
    int nl = 0;
    const sl_light_info *lights = c->host->lights(c->host, &nl);
    if (light < 0 || light >= nl || f->proj[15] != 0 || f->proj[11] != -1) return 0; /* perspective cameras only */
    const sl_light_info *L = &lights[light];
    int n = param(c, "count").i;
    n = n < 1 ? 1 : n > 4 ? 4 : n > max ? max : n;
    double lambda = fmin(fmax(param(c, "lambda").f[0], 0), 1), blend = fmin(fmax(param(c, "blend").f[0], 0), 0.5);
    bool stable = param(c, "stabilize").b;
    /* camera: near/far and the lens from the projection (jitter only moves proj[8], proj[9]) */
    double m22 = f->proj[10], m32 = f->proj[14];
    double znear = m32 / (m22 - 1), zfar = m32 / (m22 + 1);
    double maxd = param(c, "max_distance").f[0];
    if (maxd > 0) zfar = fmin(zfar, maxd);
    if (!(znear > 0) || !(zfar > znear * 1.0001) || !isfinite(zfar)) return 0;
    double tx = 1.0 / f->proj[0], ty = 1.0 / f->proj[5], k2 = tx * tx + ty * ty;
    const float *V = f->view; /* rows of the camera's rotation: right, up, backwards */
    double R[3] = {V[0], V[4], V[8]}, U[3] = {V[1], V[5], V[9]}, F[3] = {-V[2], -V[6], -V[10]};
    double E[3] = {f->camera_pos[0], f->camera_pos[1], f->camera_pos[2]};

    /* light frame, fixed in the world (only the light and the scene box move it) */
    double d[3] = {L->direction[0], L->direction[1], L->direction[2]};
    normalize3(d);
    if (!(dot3(d, d) > 0.5)) return 0;
    double up[3] = {0, 1, 0}, t1[3], t2[3];
    if (fabs(d[1]) > 0.99) up[0] = 1, up[1] = 0;
    cross3(d, up, t1);
    normalize3(t1);
    cross3(t1, d, t2);
    double center[3], ext[3];
    for (int i = 0; i < 3; i++) {
        center[i] = 0.5 * (f->scene_min[i] + f->scene_max[i]);
        ext[i] = 0.5 * (f->scene_max[i] - f->scene_min[i]);
    }
    double box_r = sqrt(dot3(ext, ext)) + 1e-3, eye[3];
    for (int i = 0; i < 3; i++) eye[i] = center[i] - d[i] * (box_r + 1);
    /* light view: x = t1, y = t2, z = −d (looks along d), origin at eye */
    float lv[16] = {0};
    for (int i = 0; i < 3; i++) {
        lv[i * 4 + 0] = (float)t1[i];
        lv[i * 4 + 1] = (float)t2[i];
        lv[i * 4 + 2] = (float)-d[i];
    }
    lv[12] = (float)-dot3(t1, eye);
    lv[13] = (float)-dot3(t2, eye);
    lv[14] = (float)dot3(d, eye);
    lv[15] = 1;
    /* depth range: every caster in the scene box, whatever the slice */
    double zlo = INFINITY, zhi = -INFINITY;
    for (int k = 0; k < 8; k++) {
        double p[3] = {k & 1 ? f->scene_max[0] : f->scene_min[0], k & 2 ? f->scene_max[1] : f->scene_min[1],
                       k & 4 ? f->scene_max[2] : f->scene_min[2]}, q[3];
        for (int i = 0; i < 3; i++) q[i] = p[i] - eye[i];
        double z = dot3(q, d);
        zlo = fmin(zlo, z);
        zhi = fmax(zhi, z);
    }
    double near_plane = fmax(zlo - 0.01 * box_r, 1e-3), far_plane = zhi + 0.01 * box_r;
    if (far_plane <= near_plane) far_plane = near_plane + 1;

    double S = map_size > 2 * MARGIN_TEXELS + 1 ? map_size : 2 * MARGIN_TEXELS + 2;
    double prev_blend = 0;
    for (int k = 0; k < n; k++) {
        double s0 = split_at(k, n, znear, zfar, lambda), s1 = split_at(k + 1, n, znear, zfar, lambda);
        double b = k + 1 < n ? blend * (s1 - s0) : 0;
        double a = s0 - prev_blend; /* the previous cascade fades into this one from here */
        prev_blend = b;
        double cx, cy, half;
        if (stable) {
            /* the slice's bounding sphere: centre on the axis at depth cz, equidistant from the
             * near and far corner circles (radii a·k, s1·k), or at s1 when that is closer */
            double cz = fmin(0.5 * (a + s1) * (1 + k2), s1);
            double r = fmax(sqrt((cz - a) * (cz - a) + a * a * k2), sqrt((s1 - cz) * (s1 - cz) + s1 * s1 * k2));
            half = r * S / (S - 2 * MARGIN_TEXELS);
            double p[3];
            for (int i = 0; i < 3; i++) p[i] = E[i] + F[i] * cz - eye[i];
            double texel = 2 * half / S;
            cx = floor(dot3(p, t1) / texel + 0.5) * texel; /* snap to whole texels */
            cy = floor(dot3(p, t2) / texel + 0.5) * texel;
        } else {
            double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
            for (int q = 0; q < 8; q++) {
                double z = q & 4 ? s1 : a, sx = q & 1 ? 1 : -1, sy = q & 2 ? 1 : -1, p[3];
                for (int i = 0; i < 3; i++) p[i] = E[i] + F[i] * z + R[i] * sx * z * tx + U[i] * sy * z * ty - eye[i];
                double x = dot3(p, t1), y = dot3(p, t2);
                lo[0] = fmin(lo[0], x), hi[0] = fmax(hi[0], x);
                lo[1] = fmin(lo[1], y), hi[1] = fmax(hi[1], y);
            }
            half = 0.5 * fmax(hi[0] - lo[0], hi[1] - lo[1]) * S / (S - 2 * MARGIN_TEXELS);
            cx = 0.5 * (lo[0] + hi[0]);
            cy = 0.5 * (lo[1] + hi[1]);
        }
        sl_shadow_view *o = &out[k];
        memcpy(o->view, lv, sizeof lv);
        ortho(o->proj, cx - half, cx + half, cy - half, cy + half, near_plane, far_plane);
        o->near_plane = (float)near_plane;
        o->far_plane = (float)far_plane;
        o->texel_world = (float)(2 * half / S);
        o->split_near = (float)s0;
        o->split_far = (float)s1;
        o->blend = (float)b;
    }
    return n;
}

/* Installs the view provider into spotlight-shadow; false (logged) when it cannot. */
static bool install(cascades *c) {
    c->sm = c->host->get_extension(c->host, SL_EXT_SHADOW_MAPS_2);
    if (!c->sm || c->sm->struct_size < offsetof(sl_ext_shadow_maps, set_view_provider) + sizeof c->sm->set_view_provider) {
        c->host->log(c->host, SL_LOG_ERROR, "cascades: spotlight-shadow does not provide %s (too old?)", SL_EXT_SHADOW_MAPS_2);
        return false;
    }
    const sl_shadow_view_provider p = {.struct_size = sizeof p, .user = c, .views = views};
    if (!c->sm->set_view_provider(c->sm->ctx, &p)) {
        c->host->log(c->host, SL_LOG_ERROR, "cascades: another plugin already supplies the directional shadow views");
        return false;
    }
    c->installed = true;
    return true;
}

/* A spotlight-shadow switched off at start offers no extension (host.h: enabled plugins only);
 * cascades is off with it (a dependency) and installs at its first frame once it is switched on,
 * as a start with it on would have at activate. */
static sl_status cs_activate(void *user) {
    cascades *c = user;
    if (!c->host->plugin_enabled(c->host, "spotlight-shadow")) return SL_OK;
    return install(c) ? SL_OK : SL_ERR_FAILED;
}

static void cs_begin_frame(void *user, const sl_frame *frame) {
    cascades *c = user;
    if (!c->installed && !c->install_failed) c->install_failed = !install(c);
}

static void cs_deactivate(void *user) {
    cascades *c = user;
    if (c->installed && c->sm) c->sm->set_view_provider(c->sm->ctx, NULL);
    c->installed = false;
}

static sl_status cs_create(const sl_host *host, void **user) {
    cascades *c = calloc(1, sizeof *c);
    if (!c) return SL_ERR_FAILED;
    *user = c;
    c->host = host;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    if (host->add_shader_chunk(host, &debug_chunk) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    static const sl_reference_desc reference = {
        .struct_size = sizeof reference, .settings = "cascades.enabled=false spotlight-shadow.map_size=8192",
        .accumulate_frames = 1,
        .description = "One 8192² map per directional light fitted to the whole scene (spotlight-shadow without "
                       "cascades), same filter and biases."};
    host->set_reference(host, &reference);
    return SL_OK;
}

static void cs_destroy(void *user) { free(user); }

static const sl_plugin_desc cs_desc = {
    SL_PLUGIN_HEADER,
    .id = ID,
    .version = "1.0",
    .description = "Cascaded shadow maps for directional lights (practical splits, stabilised, blended), rendered by "
                   "spotlight-shadow through shadelab.shadow-maps/2.",
    .dependencies = (const char *const[]){"spotlight-shadow", NULL},
    .create = cs_create,
    .activate = cs_activate,
    .begin_frame = cs_begin_frame,
    .deactivate = cs_deactivate,
    .destroy = cs_destroy,
};

SL_DEFINE_PLUGIN(cs_desc)
