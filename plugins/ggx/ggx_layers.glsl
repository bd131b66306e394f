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

#if defined(SL_MAT_HAS_DIELECTRIC_SPECULAR) || defined(SL_MAT_HAS_DIELECTRIC_SPECULAR_MAP) || \
    defined(SL_MAT_HAS_DIELECTRIC_SPECULAR_COLOR) || defined(SL_MAT_HAS_DIELECTRIC_SPECULAR_COLOR_MAP)
#if GGX_LAYER_SPECULAR && SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
#define GGX_HAS_SPECULAR 1
#endif
#endif
#ifdef GGX_HAS_SPECULAR
// KHR_materials_specular: the strength and F0 colour of the dielectric's specular reflection
// (specularFactor × specularTexture.a, specularColorFactor × specularColorTexture.rgb), filled by
// the surface hooks.
float ggx_spec_strength = 1.0;
vec3 ggx_spec_color = vec3(1.0);
#endif

// The extension's dielectric BRDF (its fresnel_mix) times n·l, for a dielectric F0 of
// f0_ior (((ior − 1)/(ior + 1))², 0.04 by default):
//   F_d = Schlick(min(f0_ior·colour, 1)·strength, F90 = strength) at v·h,
//   f = F_d·D·G/(4|n·l||n·v|) + (1 − max(F_d))·base/π.
// Without the extension (strength 1, colour 1) it is glTF's dielectric BRDF (appendix B).
vec3 ggx_dielectric_fresnel(float v_dot_h, float f0_ior, vec3 colour, float strength) {
    return ggx_schlick_f90(v_dot_h, min(vec3(f0_ior) * colour, vec3(1.0)) * strength, vec3(strength));
}
vec3 ggx_dielectric_layer(vec3 base, float f0_ior, vec3 colour, float strength, float alpha, vec3 n, vec3 v, vec3 l) {
    vec3 h;
    float dg = ggx_DG_over_4(n, l, v, alpha, h);
    vec3 F = ggx_dielectric_fresnel(dot(v, h), f0_ior, colour, strength);
    return (F * dg + (1.0 - max(F.r, max(F.g, F.b))) * base * SL_INV_PI) * max(dot(n, l), 0.0);
}

// KHR_materials_sheen's BRDF (Conty Estevez & Kulla 2017, "Production Friendly Microfacet Sheen
// BRDF"): the "Charlie" distribution D = (2 + 1/α)·sin(θ_h)^(1/α)/(2π), α = roughness², and the
// paper's visibility V = 1/((1 + Λ(n·v) + Λ(n·l))·4·n·l·n·v), Λ from its fitted L(x) (the
// coefficients of the paper, interpolated in (1 − α)²). GGX_SHEEN_MIN_ALPHA keeps 1/α finite.
const float GGX_SHEEN_MIN_ALPHA = 0.07 * 0.07;
float ggx_sheen_D(float n_dot_h, float alpha) {
    float inv = 1.0 / max(alpha, GGX_SHEEN_MIN_ALPHA);
    float sin2 = max(1.0 - n_dot_h * n_dot_h, 0.0);
    return (2.0 + inv) * pow(sin2, 0.5 * inv) / (2.0 * SL_PI);
}
float ggx_sheen_L(float x, float alpha) {
    float t = (1.0 - alpha) * (1.0 - alpha);
    float a = mix(21.5473, 25.3245, t), b = mix(3.82987, 3.32435, t), c = mix(0.19823, 0.16801, t);
    float d = mix(-1.97760, -1.27393, t), e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}
float ggx_sheen_lambda(float c, float alpha) {
    return c < 0.5 ? exp(ggx_sheen_L(c, alpha)) : exp(2.0 * ggx_sheen_L(0.5, alpha) - ggx_sheen_L(1.0 - c, alpha));
}
// D·V·(n·l): the sheen BRDF times the cosine (0 below either horizon).
float ggx_sheen_brdf_cos(vec3 n, vec3 v, vec3 l, float alpha) {
    float nl = dot(n, l), nv = dot(n, v);
    if (nl <= 0.0 || nv <= 0.0) return 0.0;
    alpha = max(alpha, GGX_SHEEN_MIN_ALPHA);
    nl = min(nl, 1.0), nv = min(nv, 1.0);
    vec3 h = normalize(l + v);
    float vis = 1.0 / ((1.0 + ggx_sheen_lambda(nv, alpha) + ggx_sheen_lambda(nl, alpha)) * 4.0 * nv);
    return ggx_sheen_D(dot(n, h), alpha) * vis;
}

#if defined(SL_MAT_HAS_SHEEN_COLOR) && GGX_LAYER_SHEEN
#define GGX_HAS_SHEEN 1
// The sheen's directional albedo E(μ, roughness) = ∫ D·V·(n·l) dl, tabulated by ggx.c (the same
// formulas in C, 32 values of μ = n·v × 8 of the sheen roughness) and set by its bind callback.
uniform vec4 ggx_sheen_albedo[64];
float ggx_sheen_table(int i) { return ggx_sheen_albedo[i >> 2][i & 3]; }
float ggx_sheen_E(float mu, float roughness) {
    vec2 p = vec2(clamp(mu, 0.0, 1.0) * 31.0, clamp(roughness, 0.0, 1.0) * 7.0);
    ivec2 i = min(ivec2(p), ivec2(30, 6));
    vec2 f = p - vec2(i);
    float e00 = ggx_sheen_table(i.y * 32 + i.x), e10 = ggx_sheen_table(i.y * 32 + i.x + 1);
    float e01 = ggx_sheen_table((i.y + 1) * 32 + i.x), e11 = ggx_sheen_table((i.y + 1) * 32 + i.x + 1);
    return mix(mix(e00, e10, f.x), mix(e01, e11, f.x), f.y);
}
// The layer (the extension's albedo scaling, in its V·N form, which keeps a white furnace ≤ 1):
// colour·D·V·(n·l)·E_light + below·(1 − max(colour)·E(n·v)).
struct GgxSheen {
    vec3 colour;     // sheenColorFactor × sheenColorTexture.rgb
    float roughness; // sheenRoughnessFactor × sheenRoughnessTexture.a (α = roughness²)
    float scale;     // 1 − max(colour)·E(n·v): what the layers below keep
};
GgxSheen ggx_sheen = GgxSheen(vec3(0.0), 1.0, 1.0);
vec3 ggx_sheen_layer(vec3 below, vec3 E, vec3 colour, float roughness, float scale, vec3 n, vec3 v, vec3 l) {
    return colour * ggx_sheen_brdf_cos(n, v, l, roughness * roughness) * E + below * scale;
}
#endif

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

#if defined(SL_MAT_HAS_TRANSMISSION) && GGX_LAYER_TRANSMISSION
#define GGX_HAS_TRANSMISSION 1
// KHR_materials_transmission: of the light entering the surface (not reflected), the share
// `weight` passes through a thin wall instead of being diffused. The extension's
//   base = mix(diffuse_brdf(baseColor), specular_btdf(α)·baseColor, transmission)
// under the dielectric's Fresnel, the BTDF V_T·D_T with the transmission half vector
// H_T = normalize(V − 2(N·L)N + L): the specular lobe about the light mirrored through the wall.
// The opaque scene behind the wall is what lights it from there (the core's SCENE_BEHIND hook),
// looked up straight through a thin wall, blurred by a mip level that grows with the roughness.
// KHR_materials_volume (GGX_HAS_VOLUME): a thickness under the surface refracts that lookup by the
// IOR and absorbs along it by Beer–Lambert, T = attenuationColor^(distance/attenuationDistance).
struct GgxTransmission {
    float weight;   // transmissionFactor × transmissionTexture.r
    float distance; // world length of the path through the volume (0: a thin wall)
    vec3 exit;      // where that path leaves it: the point the scene behind is looked up at
};
GgxTransmission ggx_trans = GgxTransmission(0.0, 0.0, vec3(0.0));
#if defined(SL_MAT_HAS_THICKNESS) && GGX_LAYER_VOLUME
#define GGX_HAS_VOLUME 1
#endif

float ggx_ior() {
#ifdef SL_MAT_HAS_IOR
    return sl_mat_ior;
#else
    return 1.5;
#endif
}
// The microfacet "prisms" of the two faces of a thin wall blur what it transmits by an amount the
// IOR modulates (the extension, "Refraction"): none at IOR 1. As the Khronos sample viewer, the
// transmitted lobe's roughness is the surface's times clamp(2·ior − 2, 0, 1).
float ggx_transmission_roughness_scale() { return clamp(2.0 * ggx_ior() - 2.0, 0.0, 1.0); }

// Beer–Lambert through `distance` (world units, per colour channel) of the volume
// (KHR_materials_volume, "Attenuation"): T = c^(x/d) with c = attenuationColor, d =
// attenuationDistance; 1 without a distance (infinite).
vec3 ggx_volume_transmittance(vec3 distance) {
#if defined(GGX_HAS_VOLUME) && defined(SL_MAT_HAS_ATTENUATION_DISTANCE)
#ifdef SL_MAT_HAS_ATTENUATION_COLOR
    vec3 c = sl_mat_attenuation_color;
#else
    vec3 c = vec3(1.0);
#endif
    vec3 x = max(distance, vec3(0.0)) / max(sl_mat_attenuation_distance, 1e-6);
    vec3 T = pow(max(c, vec3(0.0)), x); // pow(0, 0) is undefined in GLSL: 1 where x = 0
    return vec3(x.r > 0.0 ? T.r : 1.0, x.g > 0.0 ? T.g : 1.0, x.b > 0.0 ? T.b : 1.0);
#else
    return vec3(1.0);
#endif
}

#if defined(GGX_HAS_VOLUME) && defined(SL_MAT_HAS_DISPERSION) && GGX_LAYER_DISPERSION
#define GGX_HAS_DISPERSION 1
// KHR_materials_dispersion: the volume's index of refraction per wavelength, the extension's
// Cauchy fit through the Abbe number V_d = 20/dispersion (λ in nm):
//   n(λ) = max(n_d + (n_d − 1)/V_d · (523655/λ² − 1.5168), 1),
// taken for red, green and blue at the Fraunhofer lines the Abbe number is defined by: C
// (656.27 nm), d (587.56 nm: n_d, the material's ior) and F (486.13 nm). Each channel's lookup of
// the scene behind follows its own refracted ray (ggx_surface_transmission).
vec3 ggx_dispersion_iors(float ior, float dispersion) {
    vec3 lambda = vec3(656.27, 587.56, 486.13);
    return max(ior + (ior - 1.0) * dispersion / 20.0 * (523655.0 / (lambda * lambda) - 1.5168), vec3(1.0));
}
// Where the red and blue paths leave the volume, and each channel's path length.
struct GgxDispersion {
    vec3 exit_red, exit_blue;
    vec3 distance; // world length of the red, green and blue paths through the volume
};
GgxDispersion ggx_disp = GgxDispersion(vec3(0.0), vec3(0.0), vec3(0.0));
#endif
// Each colour channel's path length through the volume (one length without dispersion).
vec3 ggx_volume_distances() {
#ifdef GGX_HAS_DISPERSION
    return ggx_disp.distance;
#else
    return vec3(ggx_trans.distance);
#endif
}
#endif

#if defined(SL_MAT_HAS_IRIDESCENCE) && GGX_LAYER_IRIDESCENCE && SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
#define GGX_HAS_IRIDESCENCE 1
// KHR_materials_iridescence: a thin film (index film_ior, thickness in nm) over the base's
// specular reflection, whose Fresnel becomes mix(F, F_film, weight). F_film is Belcour & Barla
// 2017 ("A Practical Extension to Microfacet Theory for the Modeling of Varying Iridescence") in
// the form the extension specifies: Schlick's Fresnel at both interfaces, the Airy reflectance
// written as a Fourier series in the film's optical path difference (orders 0..2), each order
// integrated over the spectrum against Gaussian fits of the XYZ colour matching functions, then
// converted to linear sRGB. Only (ggx_layers.glsl's) glTF metallic-roughness model carries it.
struct GgxIridescence {
    float weight;    // iridescenceFactor × iridescenceTexture.r (0 also for a film of thickness 0)
    float thickness; // nm: mix(minimum, maximum, iridescenceThicknessTexture.g), maximum without it
    float film_ior;  // iridescenceIor (1.3)
};
GgxIridescence ggx_irid = GgxIridescence(0.0, 0.0, 1.3);

// The spectral sensitivity of order m in Fourier space (the paper's eq. for the XYZ Gaussians,
// the extension's constants): for optical path difference opd (nm) and phase shift, the XYZ
// response ∑ a·√(2πσ)·cos(2π·μ·opd + shift)·exp(−(2π·opd)²σ), normalised by the Y integral,
// converted to linear sRGB by the XYZ → Rec. 709 matrix (D65).
vec3 ggx_film_sensitivity(float opd, vec3 shift) {
    float phase = 2.0 * SL_PI * opd * 1e-9;
    vec3 a = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13), mu = vec3(1.6810e6, 1.7953e6, 2.2084e6);
    vec3 sigma = vec3(4.3278e9, 9.3046e9, 6.6121e9);
    vec3 xyz = a * sqrt(2.0 * SL_PI * sigma) * cos(mu * phase + shift) * exp(-phase * phase * sigma);
    xyz.x += 9.7470e-14 * sqrt(2.0 * SL_PI * 4.5282e9) * cos(2.2399e6 * phase + shift.x) * exp(-4.5282e9 * phase * phase);
    xyz /= 1.0685e-7;
    return mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314, 0.0415560,
                1.0572252) * xyz;
}
float ggx_film_f0(float a, float b) { return ((a - b) / (a + b)) * ((a - b) / (a + b)); }
// The film's Fresnel at cosine c1 from air, over a base of normal-incidence reflectance f0 (its
// index η3 = (1 + √f0)/(1 − √f0) per channel):
//   R12 = Schlick(f0(η2, 1), c1), T = 1 − R12, R23 = Schlick(f0(η3, η2), c2), c2 by Snell's law;
//   phase shifts φ = φ21 + φ23 (π at a reflection on a denser medium), opd = 2·η2·d·c2;
//   R = R12 + Rs + ∑_{m=1,2} 2·(Rs − T)·√(R12 R23)^m · S(m·opd, m·φ), Rs = T²R23/(1 − R12 R23).
// Total internal reflection in the film (η2 < 1) reflects everything.
vec3 ggx_film_fresnel(float c1, vec3 f0, float eta2, float thickness) {
    float s2 = (1.0 - c1 * c1) / (eta2 * eta2);
    if (s2 >= 1.0) return vec3(1.0);
    float c2 = sqrt(1.0 - s2);
    float R12 = ggx_schlick_f90(c1, vec3(ggx_film_f0(eta2, 1.0)), vec3(1.0)).x, T = 1.0 - R12;
    float phi21 = eta2 < 1.0 ? 0.0 : SL_PI;
    vec3 sf0 = sqrt(clamp(f0, 0.0, 0.9999)), eta3 = (1.0 + sf0) / (1.0 - sf0);
    vec3 R23 = ggx_schlick_f90(c2, (eta3 - eta2) * (eta3 - eta2) / ((eta3 + eta2) * (eta3 + eta2)), vec3(1.0));
    vec3 phi = vec3(phi21) + mix(vec3(0.0), vec3(SL_PI), lessThan(eta3, vec3(eta2)));
    float opd = 2.0 * eta2 * thickness * c2;
    vec3 R123 = min(R12 * R23, vec3(0.9999)), r123 = sqrt(R123);
    vec3 Rs = T * T * R23 / (1.0 - R123);
    vec3 R = R12 + Rs, Cm = Rs - T;
    for (int m = 1; m <= 2; m++) {
        Cm *= r123;
        R += Cm * 2.0 * ggx_film_sensitivity(float(m) * opd, float(m) * phi);
    }
    return max(R, vec3(0.0));
}
#endif

#if defined(SL_MAT_HAS_ANISOTROPY) && GGX_LAYER_ANISOTROPY
#define GGX_HAS_ANISOTROPY 1
// KHR_materials_anisotropy: the base's specular lobe stretched along a direction t of the surface
// (the tangent rotated by anisotropyRotation, or the anisotropy texture's direction rotated by
// it), b = n × t across it: α_t = mix(α, 1, strength²), α_b = α (the extension's formula), and
// Burley's anisotropic GGX distribution (the extension's D):
//   D(h) = 1 / (π α_t α_b ((h·t)²/α_t² + (h·b)²/α_b² + (h·n)²)²),
// with the Smith masking of that distribution (Heitz 2014, "Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs", §5.3: Λ with α² tan²θ replaced by
// (α_t²(x·t)² + α_b²(x·b)²)/(x·n)²), separable as ggx's isotropic G: at strength 0 both are
// ggx_DG_over_4's terms exactly (up to rounding). The extension's sample code uses the
// height-correlated form instead, the same choice ggx makes differently for the isotropic lobe.
struct GgxAnisotropy {
    float strength; // anisotropyStrength × anisotropyTexture.b
    vec3 t;         // unit direction of the stretch, orthogonal to the shading normal
    vec3 b;         // n × t
};
GgxAnisotropy ggx_aniso = GgxAnisotropy(0.0, vec3(1.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0));

// α_t, α_b of a lobe of GGX α `alpha` at anisotropy `strength` (both ≥ GGX_MIN_ALPHA).
vec2 ggx_aniso_alphas(float alpha, float strength) {
    float a = max(alpha, GGX_MIN_ALPHA);
    return vec2(mix(a, 1.0, strength * strength), a);
}
float ggx_aniso_D(vec3 n, vec3 t, vec3 b, vec3 h, vec2 a) {
    float hn = dot(h, n);
    if (hn <= 0.0) return 0.0;
    float ht = dot(h, t) / a.x, hb = dot(h, b) / a.y, k = ht * ht + hb * hb + hn * hn;
    return 1.0 / (SL_PI * a.x * a.y * k * k);
}
// D of the anisotropic lobe seen through the light's disk, as ggx_D_disk: in slopes scaled by
// 1/α_t, 1/α_b the lobe is the isotropic one of α = 1, and the squeezed disk of radius s becomes an
// ellipse, taken as the disk of the same area (s²/(α_t α_b)); ggx_D_disk's where α_t = α_b.
float ggx_aniso_D_disk(vec3 n, vec3 t, vec3 b, vec3 h, vec3 l, vec3 v, vec2 a) {
    float c = max(dot(h, n), 1e-4), c2 = c * c, ab = a.x * a.y, s2;
    vec3 m = (h - n * c) / c;
    float k = ggx_disk_squeeze(l, v, h, ggx_disk_light(c, m), ab, m, s2);
    vec2 q = vec2(dot(m, t), dot(m, b)) / a;
    return k * ggx_slope_disk(dot(q, q), s2 / ab, 1.0) / (ab * c2 * c2);
}
// D·G/(4|n·l||n·v|) of the anisotropic lobe, written as ggx_DG_over_4 with the divisions cancelled:
// G₁(x) = 2c/(c + √(c² + α_t²(x·t)² + α_b²(x·b)²)), c = n·x. 0 below either horizon.
float ggx_aniso_DG_over_4(vec3 n, vec3 t, vec3 b, vec3 l, vec3 v, vec2 a, out vec3 h) {
    float n_dot_l = dot(n, l), n_dot_v = dot(n, v);
    vec3 hv = l + v;
    float len2 = dot(hv, hv);
    h = len2 > 1e-16 ? hv * inversesqrt(len2) : n;
    if (n_dot_l <= 0.0 || n_dot_v <= 0.0) return 0.0;
    float D; // as ggx_DG_over_4
    // a light without a disk squeezes nothing: the footprint alone (ggx_D_footprint's case)
    if (ggx_D_disk_filtered() || ggx_D_footprint_filtered())
        D = ggx_aniso_D_disk(ggx_footprint_normal(n, a.x * a.y), t, b, h, l, v, a);
    else D = ggx_aniso_D(n, t, b, h, a);
    float cl = min(n_dot_l, 1.0), cv = min(n_dot_v, 1.0);
    vec2 pl = a * vec2(dot(l, t), dot(l, b)), pv = a * vec2(dot(v, t), dot(v, b));
    return D / ((cl + sqrt(cl * cl + dot(pl, pl))) * (cv + sqrt(cv * cv + dot(pv, pv))));
}
// Smith's G = G₁(v)·G₁(l) of the anisotropic lobe (the ggx-g debug view).
float ggx_aniso_G(vec3 n, vec3 t, vec3 b, vec3 l, vec3 v, vec2 a) {
    float cl = dot(n, l), cv = dot(n, v);
    if (cl <= 0.0 || cv <= 0.0) return 0.0;
    vec2 pl = a * vec2(dot(l, t), dot(l, b)), pv = a * vec2(dot(v, t), dot(v, b));
    return 4.0 * cl * cv / ((cl + sqrt(cl * cl + dot(pl, pl))) * (cv + sqrt(cv * cv + dot(pv, pv))));
}
#endif
