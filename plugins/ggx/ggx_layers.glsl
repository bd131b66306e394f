// The glTF material layers ggx renders (KHR_materials_*; README "Layers"), as material inputs of
// the ggx model. Everything here is compiled only for a material carrying the layer's key and
// while the layer's switch (ggx.layer_<name>) is on, so a material without it pays nothing.
// ggx_surface.glsl fills the per-fragment records below once (textures read once, not per light);
// ggx_model.glsl reads them.

#include "sl:ggx_brdf.glsl"

// Schlick's Fresnel with its own F90: F0 + (F90 − F0)(1 − c)⁵.
vec3 ggx_schlick_f90(float c, vec3 f0, vec3 f90) {
    float m = clamp(1.0 - abs(c), 0.0, 1.0);
    float m2 = m * m;
    return f0 + (f90 - f0) * (m2 * m2 * m);
}

#if defined(SL_MAT_HAS_CLEARCOAT) && GGX_LAYER_CLEARCOAT
#define GGX_HAS_CLEARCOAT 1
// KHR_materials_clearcoat: a second GGX lobe on top, IOR 1.5 (F0 = 0.04), with its own roughness
// and normal n_c, layered by the extension's fresnel_coat: coated = mix(base, coat_brdf,
// clearcoat·F_c(n_c·v)), the coat's D·G/(4|n·l||n·v|) without a Fresnel of its own. The Fresnel
// at the view, not at each light's half vector, is what keeps the sum ≤ 1 (the extension's
// "Discussion"; test_ggx_layers: with F_c(v·h) a white base under a coat gains up to 25 % at
// grazing views).
struct GgxClearcoat {
    float weight; // clearcoatFactor × clearcoatTexture.r (0: no coat)
    float alpha;  // (clearcoatRoughnessFactor × clearcoatRoughnessTexture.g)²
    vec3 normal;  // the coat's own normal: the interpolated one, or its normal texture's
};
GgxClearcoat ggx_coat = GgxClearcoat(0.0, 1.0, vec3(0.0));
const float GGX_COAT_F0 = 0.04; // ((1.5 − 1)/(1.5 + 1))²

float ggx_coat_fresnel(float c) { return ggx_schlick_f90(c, vec3(GGX_COAT_F0), vec3(1.0)).x; }
// The coat over the radiance `below` of the layers under it, lit with E from l, about the
// coat's normal n: below·(1 − w·F_c(n·v)) + w·F_c(n·v)·D·G/(4|n·l||n·v|)·E·(n·l).
vec3 ggx_coat_layer(vec3 below, vec3 E, float w, float alpha, vec3 n, vec3 v, vec3 l) {
    vec3 h;
    float dg = ggx_DG_over_4(n, l, v, alpha, h);
    float fc = w * ggx_coat_fresnel(clamp(dot(n, v), 0.0, 1.0));
    return mix(below, dg * max(dot(n, l), 0.0) * E, fc);
}
#endif
