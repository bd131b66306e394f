// shadelab core GLSL library: constants, the records every hook sees, and the uniforms the
// core sets for every program. Conventions (sdk/docs/conventions.md): linear HDR radiance,
// right-handed world space, Y up; directional lights carry irradiance E, point lights
// intensity I (E = I/d²); Lambert BRDF = k_d/π.
const float SL_PI = 3.14159265358979323846;
const float SL_INV_PI = 0.31830988618379067154;

// The angular radius (radians) of the light whose l and E the shading model is evaluating: the
// core's directional light sets it from its angular_radius key, every other light leaves 0, and
// the light loop sets it back to 0 after each model evaluation. GGX's D is convolved with the
// light's reflected disk by it, blinn-gloss's lobe widens to it (ggx_brdf.glsl). Declared here and in ggx_brdf.glsl (which some
// programs include alone), once.
#ifndef SL_LIGHT_SPREAD_DECLARED
#define SL_LIGHT_SPREAD_DECLARED 1
float sl_light_spread = 0.0;
#endif
// ABI 1.23: the pixel's footprint of the surface's interpolated normal, for filtering a lobe over
// the pixel (sl:ggx_brdf.glsl filters D over it under a light's disk): the area of the
// parallelogram the normal's screen derivatives span, /π (a disk's r², in slopes). Fragment stage:
// sl_surface_from_varyings sets it, a pass that builds its surface otherwise (a deferred lighting
// pass) calls sl_set_normal_footprint(n); 0 where nothing did.
// ABI 1.28: the change of that normal from the fragment's (jittered) sample to its pixel's centre,
// sl_jitter.x·dFdx(n) + sl_jitter.y·dFdy(n), set with it: a lobe filtered over the footprint can
// centre its filter on the pixel in every frame of a TAA still.
#ifndef SL_NORMAL_FOOTPRINT_DECLARED
#define SL_NORMAL_FOOTPRINT_DECLARED 1
float sl_normal_footprint = 0.0;
vec3 sl_normal_to_centre = vec3(0.0);
#endif
// ABI 1.25: true while the light loop evaluates the model for one of its lights (one direction
// per pixel, which a lobe may filter over the pixel's footprint), false for the directions an
// integrator samples (they see the lobe itself, whose importance sampling they use). Declared
// here and in ggx_brdf.glsl, once.
#ifndef SL_LIGHT_IN_LOOP_DECLARED
#define SL_LIGHT_IN_LOOP_DECLARED 1
bool sl_light_in_loop = false;
#endif

// Object-space vertex, edited by VERTEX hooks.
struct SlVertex {
    vec3 position;
    vec3 normal;
    vec4 tangent;   // xyz + handedness w (±1)
    vec2 uv;
};

// World-space shading record, filled by the core and edited by SURFACE hooks.
struct SlSurface {
    vec3 position;
    vec3 normal;           // shading normal (unit, facing the viewer's side of the surface)
    vec3 geometric_normal; // unit triangle normal, same side as normal
    vec3 tangent;          // unit, orthogonal to normal
    vec3 bitangent;        // unit, handedness applied
    vec2 uv;
    vec3 view;             // unit, surface → camera
    vec3 base_color;       // linear; material base_color × base_color_map
    float alpha;           // GGX α (plugins fill it; 1 by default)
    float specular;        // specular scale k_s (1 by default)
    float ao;              // ambient occlusion (1 by default)
    float opacity;         // 1 by default
    float lod_bias;        // mip bias of lookups that follow the normal map's level (normal-map sets
                           // it; 0 by default): a model's gloss map filtered at the normal's level
    vec3 object_position;  // ABI 1.6: object-space position before VERTEX hooks (rest pose),
                           // interpolated: object-space regions stay on a moving surface
    float metallic;        // ABI 1.7: glTF metalness in [0, 1] (0 by default): metallicFactor ×
                           // the metallic-roughness texture's blue channel (ggx fills it)
    vec2 uv1;              // ABI 1.7: the mesh's second UV set (glTF TEXCOORD_1); uv where the
                           // material has no texture on it. Material textures are read at
                           // sl_uv_<key>(s): their UV set and KHR_texture_transform
    vec3 emission_weight;  // ABI 1.20: what the layers over the emission leave of it (1 by
                           // default; ggx's clear coat: 1 − w·F_c(n_c·v)); sl_emission(s) is
                           // the material's emission times it
};

// ABI 1.14, the lobe contract (sdk/docs/plugin-guide.md, "Lobes"): how a shading model's
// response looks to a light integrator (environment maps, area lights) that does not know the
// model. A MODEL_LOBES hook returns it; the generated sl_model_lobes(s) returns it for the
// material's model, or the fallback (a Lambert diffuse of s.base_color, no lobe) when the model
// gives none. Radiance from incident radiance L_i(l):
//   L_o ≈ ∫ L_i(l) [diffuse/π · w_d(l) + Σ_k weight_k · f_GGX(v, l; α_k, F_k)] (n·l) dl
// with f_GGX the microfacet GGX BRDF (Smith G) and F_k Schlick between f0 and f90, or the exact
// dielectric Fresnel with eta when eta > 0. w_d = 1, or 1 − F_0(l·h) with diffuse_coupled (glTF
// 2.0 appendix B: the diffuse under lobe 0's Fresnel). Lobes are isotropic.
// ABI 1.16, flags: SL_LOBES_MODEL_AT_DOMINANT_LIGHT says the model's response must not be
// integrated (a toon model's bands would blur): the integrator evaluates the model's own f
// (sl_shading_model) once per light, at the light's dominant direction d with the irradiance E_d
// it carries, and adds the diffuse albedo under the rest of the light:
//   L_o = f(s, d, E_d) + diffuse/π · max(E(n) − E_d max(0, n·d), 0)
// (envmap: d and E_d from the environment's order-1 irradiance; area lights: the polygon's vector
// irradiance, nothing left over). A Lambert f gives diffuse/π · E(n) exactly; the lobes are unused.
// ABI 1.19, lobe shapes: flag bit SL_LOBES_BLINN_PHONG << k says lobe k is normalised
// Blinn-Phong instead of GGX: its directional albedo is the GGX lobe's (weight × the environment
// BRDF at α with its Fresnel), spread over l as (n·h)^p (n·l), p = sl_lobe_blinn_power(α) (below).
// α stays the GGX lobe closest to it, which an integrator that does not know the shape uses.
// Flag bits rather than an SlLobe field: SlLobe(…) constructors of older plugins still compile.
const int SL_MAX_LOBES = 2;
const int SL_LOBES_MODEL_AT_DOMINANT_LIGHT = 1;
const int SL_LOBES_BLINN_PHONG = 256; // lobe k: SL_LOBES_BLINN_PHONG << k
struct SlLobe {
    vec3 f0;      // Fresnel at normal incidence of the microfacets (colour)
    vec3 f90;     // … at grazing incidence (1 for Schlick's usual form)
    float alpha;  // GGX α, the lobe's shape (≥ 0)
    float weight; // scale of the lobe (≥ 0; 0 switches it off)
    float eta;    // > 0: exact dielectric Fresnel with η = n₁/n₂ instead of Schlick (f0 kept as
                  // Schlick's F0 for integrators that tabulate Schlick)
};
struct SlLobes {
    vec3 diffuse;          // Lambert albedo (radiance = diffuse/π × irradiance)
    bool diffuse_coupled;  // the diffuse is weighted by 1 − F of lobe 0 (see above)
    int count;             // lobes in use, 0 … SL_MAX_LOBES
    SlLobe lobe[SL_MAX_LOBES];
    int flags;             // ABI 1.16: SL_LOBES_MODEL_AT_DOMINANT_LIGHT | (1.19) SL_LOBES_BLINN_PHONG << k
    vec3 normal[SL_MAX_LOBES]; // ABI 1.26: lobe k's own shading normal (a clear coat's normal
                               // texture), unit length; vec3(0): the surface's, s.normal
};
// Lobe shapes (ABI 1.19): whether lobe k is Blinn-Phong, and the power ↔ α of the contract. The
// α of power p has Blinn's median: half of each D's projected microfacet area lies within the same
// θ½ of n, 1 − cos^(p+2) θ½ = ½ = tan²θ½/(α² + tan²θ½), so α = √(2^(2/(p+2)) − 1) and
// p = 2/log2(1 + α²) − 2 (0.83–0.90 × Walter et al.'s √(2/(p+2)): GGX's longer tails).
bool sl_lobe_blinn_phong(SlLobes L, int k) { return (L.flags & (SL_LOBES_BLINN_PHONG << k)) != 0; }
float sl_lobe_blinn_alpha(float p) {
    float y = 0.69314718 * 2.0 / (max(p, 0.0) + 2.0); // 2^(2/(p+2)) − 1 = e^y − 1, by its series
    return sqrt(y < 0.01 ? y * (1.0 + y * (0.5 + y / 6.0)) : exp(y) - 1.0); // where exp − 1 cancels
}
float sl_lobe_blinn_power(float alpha) {
    float x = alpha * alpha; // log2(1 + x), by its series where 1 + x rounds (α ≲ 0.1)
    float l2 = x < 0.01 ? x * (1.0 - x * (0.5 - x / 3.0)) * 1.44269504 : log2(1.0 + x);
    return max(2.0 / max(l2, 1e-30) - 2.0, 0.0);
}
// An empty description: no diffuse, no lobe; a hook starts from it.
SlLobes sl_lobes_none() {
    SlLobe z = SlLobe(vec3(0.0), vec3(1.0), 1.0, 0.0, 0.0);
    return SlLobes(vec3(0.0), false, 0, SlLobe[SL_MAX_LOBES](z, z), 0, vec3[SL_MAX_LOBES](vec3(0.0), vec3(0.0)));
}
// The normal lobe k is integrated about (ABI 1.26): its own where the model set one, else s.normal.
vec3 sl_lobe_normal(SlLobes L, int k, SlSurface s) {
    return dot(L.normal[k], L.normal[k]) > 0.5 ? L.normal[k] : s.normal;
}

// One light as packed by the core (std430, 80 bytes).
struct SlLight {
    vec4 position;   // xyz world
    vec4 direction;  // xyz unit, the direction light travels
    vec4 color;      // rgb = colour × intensity
    vec4 params[2];  // light-type keys by light_slot (0..7)
};

uniform float sl_time;
uniform mat4 sl_view;
uniform mat4 sl_proj;
uniform mat4 sl_view_proj;
uniform vec3 sl_camera_pos;
uniform int sl_frame_index;
uniform int sl_sample_index, sl_sample_count; // ABI 1.9: sl_frame.sample_index/count
uniform vec2 sl_viewport_size;
uniform vec2 sl_jitter; // ABI 1.28: sl_frame.jitter, the frame's projection offset in pixels
uniform float sl_texture_lod_bias; // ABI 1.30: the mip bias the materials' textures have this frame (set_texture_lod_bias)
uniform mat4 sl_model;
uniform mat3 sl_normal_matrix;

float sl_saturate(float x) { return clamp(x, 0.0, 1.0); }
vec3 sl_saturate(vec3 x) { return clamp(x, 0.0, 1.0); }

// sRGB OETF (IEC 61966-2-1), per channel.
vec3 sl_srgb_encode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
