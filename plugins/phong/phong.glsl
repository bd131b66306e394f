// phong: the shading models "phong" and "blinn-gloss", their ambient terms, the property-map
// SURFACE hook (gloss → s.alpha, AO → s.ao, with Toksvig specular antialiasing) and the
// "effective-gloss" debug view. Uniforms from the composer:
//   phong_color, phong_gloss_map, phong_ao (bool: keys 1, 3, 4), PHONG_SPECULAR_AA (define),
//   sl_mat_gloss, sl_mat_shininess (float), sl_mat_specular_color (vec3),
//   sl_mat_property_map (sampler2D, R gloss, B AO; only when the material carries one).
// The plugin's own: phong_toksvig (sampler2D on a reserved unit, bound by phong.c per material):
//   RG, explicit mips: R = gloss with the level's normal variance baked in, G = |N̄|.
#include "phong_brdf.glsl"
#include "sl:ggx_brdf.glsl" // ggx_disk_alpha: a light's disk widens the lobe (the core's angular_radius)

#if defined(SL_MAT_HAS_PROPERTY_MAP) && PHONG_SPECULAR_AA && defined(SL_MAT_HAS_NORMAL_MAP)
#define PHONG_TOKSVIG 1
uniform sampler2D phong_toksvig;
#endif

// How much the current texel's lobe was widened by Toksvig (1 − ft), set by phong_surface and
// read by the blinn-gloss model in the same invocation; 0 without specular antialiasing.
float phong_filter_w = 0.0;

// Key 1: the colour map, or grey albedo 0.5 to judge the lighting alone.
vec3 phong_albedo(SlSurface s) { return phong_color ? s.base_color : vec3(0.5); }

// The blinn-gloss specular power, always from s.alpha (Walter 2007: SpecPower = 2/α² − 2), so
// that whoever sets the surface's gloss is honoured: phong_surface_gloss (the material's gloss,
// first), the property map, or another plugin's surface hook (procedural tiles, ggx's alpha key).
float phong_power(SlSurface s) { return phong_power_from_alpha(s.alpha); }

// The material's gloss as s.alpha for blinn-gloss materials only (when_model; 0.5 → SpecPower
// 64); runs before every other surface hook (order -100), so any of them may override it.
void phong_surface_gloss(inout SlSurface s) { s.alpha = phong_alpha_from_power(phong_power_from_gloss(sl_mat_gloss)); }

// Lit by a light of angular radius r (sl_light_spread), the lobe about reflect(−l, n) widens to the
// disk's reflection (reflected directions within r of the light's): the half maximum of
// max(0, r·v)^s, at θ² ≈ 2 ln 2/s, grows in quadrature, θ'² = θ² + r², so s' = 1/(1/s + r²/2 ln 2),
// and k_s scales by (s' + 1)/(s + 1), which keeps the lobe's integral 2π/(s + 1): the classic
// model's k_s is not normalised, and the light it reflects stays the same.
vec3 phong_model_classic(SlSurface s, vec3 l, vec3 E) {
    float p = max(sl_mat_shininess, 0.0), k = 1.0;
    if (sl_light_spread > 0.0) {
        float q = 1.0 / (1.0 / max(p, 1e-6) + sl_light_spread * sl_light_spread / 1.3862944);
        k = (q + 1.0) / (p + 1.0);
        p = q;
    }
    return phong_classic(s.normal, s.view, l, phong_albedo(s), sl_mat_specular_color * s.specular * k, p, E);
}
vec3 phong_model_classic_ambient(SlSurface s, vec3 Ea) { return phong_classic_ambient(phong_albedo(s), s.ao, Ea); }

// Lit by a light of angular radius r (sl_light_spread, set per light by the core), the lobe is
// widened to the disk's reflection (half vectors within r/2) as GGX's is (ggx_disk_alpha),
// through the power's α (Walter's mapping, whose lobe has its half maximum at 0.8326 α where
// GGX's is at 0.6436 α: ρ = r/2 × 0.773), so a polished surface shows the sun's disk, not a dot.
vec3 phong_model_blinn_gloss(SlSurface s, vec3 l, vec3 E) {
    float a = sl_light_spread > 0.0 ? ggx_disk_alpha(s.alpha, 0.3865 * sl_light_spread) : s.alpha;
    float p = phong_power_from_alpha(a);
#if defined(PHONG_TOKSVIG)
    return phong_blinn_gloss_filtered(s.normal, s.view, l, phong_albedo(s), p, s.specular, E, phong_filter_w);
#else
    return phong_blinn_gloss(s.normal, s.view, l, phong_albedo(s), p, s.specular, E);
#endif
}
// blinn-gloss's lobes (ABI 1.14): the diffuse (1 − F(n·v))·albedo exactly (F depends on n·v
// only), and one lobe, Blinn-Phong shaped (ABI 1.19) of the power s.alpha carries (its α,
// sl_lobe_blinn_alpha, is the GGX lobe with Blinn's median for integrators that read GGX only),
// constant Fresnel f0 = f90 = F(n·v)·k_s, and the weight that gives the model's specular albedo
// (phong_lobe_weight): a uniform environment is lit as the model says. Toksvig's widening is in
// the power; its Fresnel/cosine blend (phong_filter_w) is not described.
SlLobes phong_blinn_gloss_lobes(SlSurface s) {
    SlLobes L = sl_lobes_none();
    float mu = dot(s.normal, s.view);
    float F = phong_schlick(mu);
    L.diffuse = (1.0 - F) * phong_albedo(s);
    L.count = 1;
    L.lobe[0].alpha = sl_lobe_blinn_alpha(phong_power(s));
    L.lobe[0].f0 = L.lobe[0].f90 = vec3(F * s.specular);
    L.lobe[0].weight = phong_lobe_weight(mu, L.lobe[0].alpha);
    L.flags = SL_LOBES_BLINN_PHONG; // lobe 0 is Blinn-Phong
    return L;
}
vec3 phong_model_blinn_gloss_ambient(SlSurface s, vec3 Ea) {
    return phong_blinn_gloss_ambient(s.normal, s.view, phong_albedo(s), s.ao, Ea);
}

#if defined(SL_MAT_HAS_PROPERTY_MAP)
// Property map: R = gloss, B = ambient occlusion (G unused). Key 3 off: the material's gloss;
// key 4 off: no AO. With specular antialiasing and a normal map, gloss comes from the
// Toksvig texture instead (same UVs, same size as the normal map, so the same mip level).
void phong_surface(inout SlSurface s) {
    float bias = s.lod_bias; // gloss follows the normal map's mip level (set by normal-map; SDK contract)
    vec4 prop = texture(sl_mat_property_map, sl_uv_property_map(s), bias);
#if defined(PHONG_TOKSVIG)
    vec2 t = texture(phong_toksvig, s.uv, bias).rg;
    float p0 = phong_power_from_gloss(phong_gloss_map ? prop.r : sl_mat_gloss);
    float p = phong_gloss_map ? phong_power_from_gloss(t.r) : phong_toksvig_power(p0, t.g);
    phong_filter_w = clamp(1.0 - p / p0, 0.0, 1.0);
    // Not in a TAA still's jittered frames (sl_texture_lod_bias < 0, ABI 1.30): they read the maps
    // at their share of the pixel and their mean resolves the bumps (as ggx_surface_specular_aa).
    if (sl_texture_lod_bias < 0.0) p = p0, phong_filter_w = 0.0;
    // Never taken (sl_frame_index ≥ 0), but keeps both material samplers active wherever the
    // Toksvig texture is (e.g. the effective-gloss view, which uses neither map otherwise):
    // phong.c finds the core's textures through these uniforms to build the Toksvig texture.
    if (sl_frame_index < 0) p += texture(sl_mat_normal_map, sl_uv_normal_map(s)).r + prop.g;
#else
    float p = phong_power_from_gloss(phong_gloss_map ? prop.r : sl_mat_gloss);
#endif
    if (phong_ao) s.ao *= prop.b;
    s.alpha = phong_alpha_from_power(p);
}
#endif

// "effective-gloss": log2(SpecPower)/12 written as linear grey: the gloss blinn-gloss uses,
// after the gloss-map toggle and Toksvig (far, bumpy regions turn darker with antialiasing).
vec3 phong_debug_gloss(SlSurface s) { return vec3(phong_gloss_from_power(phong_power(s))); }
