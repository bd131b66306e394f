// sss: the "skin" shading model (GGX specular layer + a subsurface diffuse term chosen by
// sss.method), the override models the prepasses draw with ("sss-irradiance", "sss-stretch"),
// the SURFACE hook that fetches per-pixel inputs, and the debug views. See README.md.
//
// Strength k = sss_strength ∈ [0, 1] blends the unscattered diffuse (Lambert k_d/π, exactly the
// ggx model's) with the method's scattered one. Every method is written as
//     ggx term + k·(scattered − Lambert)
// arranged so that k = 0 is bit-identical to the ggx model on the same material.
#include "sss_lib.glsl"
#include "sl:ggx_brdf.glsl"

#ifndef SSS_METHOD
#define SSS_METHOD 0
#endif
#ifndef SSS_ALBEDO
#define SSS_ALBEDO 0
#endif

// Textures on units the plugin reserved (bound by its bind callback).
uniform sampler2D sss_tex_diffuse;      // texture space: Σ wᵢ·blurᵢ; screen space: blurred diffuse
uniform sampler2D sss_tex_lut;          // pre-integrated skin LUT (sss_profile.h)
uniform sampler2DArray sss_tex_shadow;  // shadow maps (extension shadelab.shadow-maps/1)
uniform vec3 sss_lut_info;              // (width, height, κ_max mm⁻¹)

// Translucency: the shadow maps of lights with cast_shadows (one entry per map).
#define SSS_MAX_MAPS 8
uniform int sss_tl_count;
uniform mat4 sss_tl_view_proj[SSS_MAX_MAPS];
uniform vec4 sss_tl_map[SSS_MAX_MAPS];   // layer, near, far, 1 = perspective / 0 = orthographic
uniform vec4 sss_tl_pos[SSS_MAX_MAPS];   // light position as rendered, cube face (−1: none)
uniform vec4 sss_tl_dir[SSS_MAX_MAPS];   // map axis (unit), light type 0 directional / 1 point / 2 spot
uniform int sss_tl_light[SSS_MAX_MAPS];  // index in sl_lights[]

// Per-pixel inputs the SURFACE hook fetches once (uniform control flow: derivatives are valid
// there, and each light of the loop reuses them). Initialised for materials without the hook
// (no sss_radius): nothing scattered, pure Lambert + specular.
float sss_g_mix = 0.0;           // k × coverage of the scattered buffer at this pixel
vec3 sss_g_scattered = vec3(0.0); // the scattered buffer (unpremultiplied)
float sss_g_curvature = 0.0;     // mm⁻¹ (pre-integrated)

float sss_strength() { return clamp(sl_mat_sss_strength, 0.0, 1.0); }

// Skin's index of refraction 1.4 (F0 ≈ 0.028, as d'Eon & Luebke use) unless the material gives
// `eta` (a key shared with ggx).
float sss_eta() {
#if defined(SL_MAT_HAS_ETA)
    return sl_mat_eta;
#else
    return 1.0 / 1.4;
#endif
}

// Albedo before and after scattering (d'Eon & Luebke's pre-/post-scatter texturing): their product is base_color.
vec3 sss_albedo_pre(vec3 base) {
#if SSS_ALBEDO == SSS_ALBEDO_PRE_SCATTER
    return base;
#elif SSS_ALBEDO == SSS_ALBEDO_MIXED
    return sqrt(max(base, vec3(0.0)));
#else
    return vec3(1.0);
#endif
}
vec3 sss_albedo_post(vec3 base) {
#if SSS_ALBEDO == SSS_ALBEDO_PRE_SCATTER
    return vec3(1.0);
#elif SSS_ALBEDO == SSS_ALBEDO_MIXED
    return sqrt(max(base, vec3(0.0)));
#else
    return base;
#endif
}

// ---- SURFACE hook (materials carrying sss_radius) ------------------------------------------
void sss_surface(inout SlSurface s) {
#if defined(SL_MODEL_SKIN)
#if SSS_METHOD == SSS_METHOD_TEXTURE_SPACE || SSS_METHOD == SSS_METHOD_SCREEN_SPACE
#if SSS_METHOD == SSS_METHOD_TEXTURE_SPACE
    vec2 uv = s.uv;
#else
    vec4 c = sl_view_proj * vec4(s.position, 1.0);
    vec2 uv = c.w > 0.0 ? c.xy / c.w * 0.5 + 0.5 : vec2(-1.0);
#endif
    vec4 t = texture(sss_tex_diffuse, uv);
    sss_g_scattered = sss_unpremultiply(t);
    sss_g_mix = sss_strength() * sss_coverage_weight(t.a);
#elif SSS_METHOD == SSS_METHOD_PRE_INTEGRATED
    // Penner 2011: curvature from screen-space derivatives of the interpolated (vertex) normal
    // and position, before any normal map edits the normal (this hook runs first).
    float dp = length(fwidth(s.position));
    float kappa = dp > 0.0 ? length(fwidth(s.normal)) / dp : 0.0;
    sss_g_curvature = kappa * max(sl_mat_sss_radius, 0.0);
#endif
#endif
}

// ---- translucency (GPU Gems 1 ch. 16, second method) ---------------------------------------

// Conventions (sdk/docs/conventions.md): spot fall-off `linear` (0) or `gltf` (1).
float sss_spot_falloff(vec3 to_point, vec3 axis, float cone, float inner, float mode) {
    float c = dot(to_point, axis);
    if (mode > 0.5) {
        float scale = 1.0 / max(0.001, cos(inner) - cos(cone));
        float a = clamp(c * scale - cos(cone) * scale, 0.0, 1.0);
        return a * a;
    }
    float theta = atan(length(cross(to_point, axis)), c);
    return clamp((1.1 * cone - theta) / max(0.2 * cone, 1e-6), 0.0, 1.0);
}

// Irradiance E (at normal incidence, unshadowed) and direction l of map t's light at p; false
// when p is outside the map (or another cube face covers it) or the light does not reach it.
bool sss_tl_light_at(int t, vec3 p, out vec3 l, out vec3 E) {
    l = vec3(0.0);
    E = vec3(0.0);
    SlLight L = sl_lights[sss_tl_light[t]];
    float type = sss_tl_dir[t].w;
    if (type < 0.5) {
        l = -sss_tl_dir[t].xyz;
        E = L.color.rgb;
        return true;
    }
    vec3 d = sss_tl_pos[t].xyz - p;
    float face = sss_tl_pos[t].w;
    if (face >= 0.0) { // cube face: covers p when its axis is p's dominant direction
        vec3 q = -d;
        int a = int(face) / 2;
        float along = (int(face) % 2 == 0 ? 1.0 : -1.0) * q[a];
        if (along < abs(q[(a + 1) % 3]) || along < abs(q[(a + 2) % 3])) return false;
    }
    float d2 = max(dot(d, d), 1e-8);
    l = d * inversesqrt(d2);
    float f = type > 1.5 ? sss_spot_falloff(-l, sss_tl_dir[t].xyz, radians(L.params[0].x), radians(L.params[0].y),
                                             L.params[0].z)
                         : 1.0;
    E = L.color.rgb * (f / d2);
    return f > 0.0;
}

// Distance (world units) light travels inside the object to reach p: p's distance from the light
// minus that of the first surface the map saw along the same ray; −1 outside the map.
float sss_tl_thickness(int t, vec3 p) {
    vec4 c = sss_tl_view_proj[t] * vec4(p, 1.0);
    if (c.w <= 0.0) return -1.0;
    vec3 q = c.xyz / c.w * 0.5 + 0.5;
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return -1.0;
    float first = texture(sss_tex_shadow, vec3(q.xy, sss_tl_map[t].x)).r;
    bool persp = sss_tl_map[t].w > 0.5;
    float z_first = sss_map_linear_depth(first, sss_tl_map[t].y, sss_tl_map[t].z, persp);
    float z_p = sss_map_linear_depth(clamp(q.z, 0.0, 1.0), sss_tl_map[t].y, sss_tl_map[t].z, persp);
    float along = z_p - z_first; // metres along the map's axis
    if (persp) { // along the ray from the light: scale by |p − pos| / ((p − pos)·axis)
        vec3 r = p - sss_tl_pos[t].xyz;
        along *= length(r) / max(dot(r, sss_tl_dir[t].xyz), 1e-6);
    }
    return max(along, 0.0);
}

// Σ over the maps: T(thickness in mm)·E·max(0, −n·l) — light entering the far side (whose normal
// is about −n on thin parts) and diffusing through.
vec3 sss_translucent_irradiance(SlSurface s) {
    vec3 sum = vec3(0.0);
    float mm = max(sl_mat_sss_radius, 1e-12);
    // a do-while (llvmpipe ran a for loop's body once more, every lane masked, at full cost);
    // with no map its one run adds nothing
    int n = min(sss_tl_count, SSS_MAX_MAPS), t = 0;
    do {
        vec3 l, E;
        if (t >= n || !sss_tl_light_at(t, s.position, l, E)) continue;
        float back = max(0.0, -dot(s.normal, l));
        if (back <= 0.0) continue;
        float thick = sss_tl_thickness(t, s.position);
        if (thick < 0.0) continue;
        sum += sss_slab_transmittance(thick / mm) * E * back;
    } while (++t < n);
    return sum;
}

// ---- the "skin" shading model ---------------------------------------------------------------
vec3 sss_skin(SlSurface s, vec3 l, vec3 E) {
    vec3 n = s.normal, v = s.view;
    float n_dot_l = max(dot(n, l), 0.0);
    vec3 h;
    float dg = ggx_DG_over_4(n, l, v, s.alpha, h);
    vec3 F = vec3(ggx_fresnel_exact(dot(l, h), sss_eta()));
    vec3 spec = s.specular * F * dg;
#if SSS_METHOD == SSS_METHOD_WRAP
    float k = sss_strength();
    vec2 f = sss_wrap_factors(dot(n, l), sss_wrap, sss_scatter_width);
    vec3 wrapped = (s.base_color * f.x + sl_mat_sss_color * f.y) * SL_INV_PI * E;
    return (s.base_color * SL_INV_PI * (1.0 - k) + spec) * E * n_dot_l + k * wrapped;
#elif SSS_METHOD == SSS_METHOD_PRE_INTEGRATED
    float k = sss_strength();
    float u = (clamp(dot(n, l), -1.0, 1.0) * 0.5 + 0.5) * (sss_lut_info.x - 1.0) + 0.5;
    float w = clamp(sss_g_curvature / max(sss_lut_info.z, 1e-6), 0.0, 1.0) * (sss_lut_info.y - 1.0) + 0.5;
    vec3 D = texture(sss_tex_lut, vec2(u / sss_lut_info.x, w / sss_lut_info.y)).rgb;
    return (s.base_color * SL_INV_PI * (1.0 - k) + spec) * E * n_dot_l + k * s.base_color * SL_INV_PI * E * D;
#elif SSS_METHOD == SSS_METHOD_TEXTURE_SPACE || SSS_METHOD == SSS_METHOD_SCREEN_SPACE
    // the scattered diffuse of every light arrives once, in the ambient term below
    return (s.base_color * SL_INV_PI * (1.0 - sss_g_mix) + spec) * E * n_dot_l;
#else // none, translucency (its transmitted term is in the ambient term)
    return (s.base_color * SL_INV_PI + spec) * E * n_dot_l;
#endif
}

// Once per pixel, outside the light loop: the ambient Lambert term (the core's own expression)
// plus the method's once-per-pixel part.
vec3 sss_skin_ambient(SlSurface s, vec3 ambient_irradiance) {
    vec3 lambert = s.base_color * SL_INV_PI * ambient_irradiance * s.ao;
#if SSS_METHOD == SSS_METHOD_TEXTURE_SPACE || SSS_METHOD == SSS_METHOD_SCREEN_SPACE
    vec3 scattered = sss_albedo_post(s.base_color) * sss_g_scattered;
    return lambert + sss_g_mix * (scattered - lambert);
#elif SSS_METHOD == SSS_METHOD_TRANSLUCENCY
    return lambert + sss_strength() * s.base_color * SL_INV_PI * sss_translucent_irradiance(s);
#else
    return lambert;
#endif
}

// ---- override models for the prepasses ------------------------------------------------------
// "sss-irradiance": the light a scattering surface takes in, as outgoing radiance of a white
// Lambert surface times the pre-scatter albedo (texture space: rasterised in UV space; screen
// space: the separate diffuse buffer).
vec3 sss_irradiance(SlSurface s, vec3 l, vec3 E) {
    return sss_albedo_pre(s.base_color) * SL_INV_PI * E * max(0.0, dot(s.normal, l));
}
vec3 sss_irradiance_ambient(SlSurface s, vec3 ambient_irradiance) {
    return sss_albedo_pre(s.base_color) * SL_INV_PI * ambient_irradiance * s.ao;
}

// Its lobes: a Lambert of the pre-scatter albedo, as sss_irradiance_ambient gives the ambient
SlLobes sss_irradiance_lobes(SlSurface s) {
    SlLobes L = sl_lobes_none();
    L.diffuse = sss_albedo_pre(s.base_color);
    return L;
}

// "sss-stretch" (d'Eon & Luebke's stretch correction): drawn in UV space, the length of
// one texel on the surface along u and v, in millimetres of the profile (world length divided
// by sss_radius, the world length of 1 mm).
vec3 sss_stretch(SlSurface s, vec3 l, vec3 E) { return vec3(0.0); }
vec3 sss_stretch_ambient(SlSurface s, vec3 ambient_irradiance) {
    float mm = max(sl_mat_sss_radius, 1e-12);
    return vec3(length(dFdx(s.position)) / mm, length(dFdy(s.position)) / mm, 0.0);
}
// no lobes: an environment or area light adds nothing to the stretch
SlLobes sss_stretch_lobes(SlSurface s) { return sl_lobes_none(); }

// ---- debug views -----------------------------------------------------------------------------
// The scattered diffuse radiance the skin model uses (texture/screen space), without specular.
vec3 sss_view_scattered(SlSurface s) { return sss_albedo_post(s.base_color) * sss_g_scattered; }
// Translucency: thickness (mm) seen by the first shadow map, divided by 10 (white = 1 cm).
vec3 sss_view_thickness(SlSurface s) {
    if (sss_tl_count < 1) return vec3(0.0);
    float t = sss_tl_thickness(0, s.position);
    return t < 0.0 ? vec3(0.0, 0.0, 1.0) : vec3(t / max(sl_mat_sss_radius, 1e-12) / 10.0);
}
// Pre-integrated: curvature κ / κ_max (white = the LUT's last row).
vec3 sss_view_curvature(SlSurface s) { return vec3(sss_g_curvature / max(sss_lut_info.z, 1e-6)); }
