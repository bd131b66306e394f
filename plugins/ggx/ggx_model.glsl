// The "ggx" shading model: L_o = (k_d/π + k_s f_s) E max(0, n·l) with f_s = F D G/(4|n·l||n·v|)
// (the core's convention), or the glTF metallic-roughness combination when
// fresnel = metallic-roughness: f = (1 − F)(1 − metallic) base/π + F D G/(4|n·l||n·v|),
// F0 = mix(0.04, base, metallic).
#include "sl:ggx_brdf.glsl"
#include "ggx_layers.glsl"

// Vectors in the space the lighting is evaluated in (world by default; camera space as a
// check: a rotation, so both agree up to rounding).
void ggx_to_space(inout vec3 n, inout vec3 l, inout vec3 v) {
#if GGX_SPACE == GGX_SPACE_CAMERA
    mat3 r = mat3(sl_view);
    n = r * n;
    l = r * l;
    v = r * v;
#endif
}

#ifdef GGX_HAS_ANISOTROPY
// The anisotropy's frame (ggx_aniso.t, .b) in the space the lighting is evaluated in.
void ggx_aniso_frame(out vec3 t, out vec3 b) {
    t = ggx_aniso.t, b = ggx_aniso.b;
#if GGX_SPACE == GGX_SPACE_CAMERA
    t = mat3(sl_view) * t;
    b = mat3(sl_view) * b;
#endif
}
#endif
// D·G/(4|n·l||n·v|) of the base's specular lobe: anisotropic where KHR_materials_anisotropy is
// carried (always with θ_x measured from n there, whatever ggx.g1_angle says).
float ggx_base_DG_over_4(SlSurface s, vec3 n, vec3 l, vec3 v, out vec3 h) {
#ifdef GGX_HAS_ANISOTROPY
    vec3 t, b;
    ggx_aniso_frame(t, b);
    return ggx_aniso_DG_over_4(n, t, b, l, v, ggx_aniso_alphas(s.alpha, ggx_aniso.strength), h);
#else
    return ggx_DG_over_4(n, l, v, s.alpha, h);
#endif
}

vec3 ggx_fresnel_base(float l_dot_h, SlSurface s);
#ifdef GGX_HAS_IRIDESCENCE
// The dielectric's F0: glTF's from the ior, with KHR_materials_specular's colour and strength.
vec3 ggx_dielectric_f0_colour() {
#ifdef GGX_HAS_SPECULAR
    return min(vec3(ggx_gltf_dielectric_f0()) * ggx_spec_color, vec3(1.0)) * ggx_spec_strength;
#else
    return vec3(ggx_gltf_dielectric_f0());
#endif
}
// The film's Fresnel at cosine c over the base: mix(film over the dielectric, film over the metal
// (F0 the base colour), metallic), as the extension's dielectric and metal BRDFs each take it.
vec3 ggx_film(float c, SlSurface s) {
    vec3 d = ggx_film_fresnel(c, ggx_dielectric_f0_colour(), ggx_irid.film_ior, ggx_irid.thickness);
    if (s.metallic <= 0.0) return d;
    return mix(d, ggx_film_fresnel(c, s.base_color, ggx_irid.film_ior, ggx_irid.thickness), s.metallic);
}
#endif

vec3 ggx_fresnel(float l_dot_h, SlSurface s) {
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS && defined(GGX_HAS_IRIDESCENCE)
    // KHR_materials_iridescence: the base's Fresnel (below, without the film) mixed with the film's
    return mix(ggx_fresnel_base(l_dot_h, s), ggx_film(abs(l_dot_h), s), ggx_irid.weight);
#else
    return ggx_fresnel_base(l_dot_h, s);
#endif
}

vec3 ggx_fresnel_base(float l_dot_h, SlSurface s) {
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_SCHLICK
    return ggx_fresnel_schlick(l_dot_h, vec3(ggx_f0_from_eta(sl_mat_eta)));
#elif SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS && defined(GGX_HAS_SPECULAR)
    // KHR_materials_specular: mix(dielectric, metal) Fresnel (the metal's F0 the base colour, F90 1)
    return mix(ggx_dielectric_fresnel(l_dot_h, ggx_gltf_dielectric_f0(), ggx_spec_color, ggx_spec_strength),
               ggx_fresnel_schlick(l_dot_h, s.base_color), s.metallic);
#elif SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    return ggx_fresnel_schlick(l_dot_h, mix(vec3(ggx_gltf_dielectric_f0()), s.base_color, s.metallic));
#else
    return vec3(ggx_fresnel_exact(l_dot_h, sl_mat_eta));
#endif
}

#ifdef GGX_HAS_CLEARCOAT
// The coat's normal, or the shading normal where the surface hook has not set it.
vec3 ggx_coat_normal(SlSurface s) { return dot(ggx_coat.normal, ggx_coat.normal) > 0.5 ? ggx_coat.normal : s.normal; }
// The material's coat (ggx_layers.glsl) over the radiance `below` of the layers under it.
vec3 ggx_clearcoat_over(vec3 below, SlSurface s, vec3 l, vec3 E) {
    vec3 n = ggx_coat_normal(s), v = s.view;
    ggx_to_space(n, l, v);
    return ggx_coat_layer(below, E, ggx_coat.weight, ggx_coat.alpha, n, v, l);
}
#endif

#ifdef GGX_HAS_TRANSMISSION
// The dielectric's Fresnel at cosine c (with KHR_materials_specular's colour and strength where
// carried) as one share, its largest channel: what the specular lobe takes from the light that
// would enter the surface.
float ggx_dielectric_share(float c, SlSurface s) {
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS && defined(GGX_HAS_SPECULAR)
    vec3 F = ggx_dielectric_fresnel(c, ggx_gltf_dielectric_f0(), ggx_spec_color, ggx_spec_strength);
#elif SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    vec3 F = ggx_dielectric_fresnel(c, ggx_gltf_dielectric_f0(), vec3(1.0), 1.0);
#else
    vec3 F = ggx_fresnel(c, s);
#endif
    return max(F.r, max(F.g, F.b));
}
// What the layers over the base leave of it at the view: the sheen's albedo scaling and the coat's
// 1 − w·F_c(n_c·v), as they dim the base under point lights.
float ggx_share_under_layers(SlSurface s) {
    float k = 1.0;
#ifdef GGX_HAS_SHEEN
    k *= ggx_sheen.scale;
#endif
#ifdef GGX_HAS_CLEARCOAT
    k *= 1.0 - ggx_coat.weight * ggx_coat_fresnel(clamp(dot(ggx_coat_normal(s), s.view), 0.0, 1.0));
#endif
    return k;
}
// What the scene behind the surface is multiplied by: transmission × (1 − metallic) (metals absorb
// what enters them) × base colour (the tint) × (1 − F(n·v)) (the dielectric's Fresnel at the view:
// exact for a smooth wall, the lobe's directional albedo otherwise approximated by it) × what the
// layers over the base leave × the volume's Beer–Lambert transmittance along its path.
vec3 ggx_transmittance(SlSurface s) {
    float f = ggx_dielectric_share(clamp(dot(s.normal, s.view), 0.0, 1.0), s);
    return ggx_trans.weight * (1.0 - s.metallic) * (1.0 - f) * ggx_share_under_layers(s) * s.base_color *
           ggx_volume_transmittance(ggx_volume_distances());
}
// A light behind the wall (n·l < 0) seen through it: the extension's BTDF V_T·D_T, the GGX lobe
// about the light mirrored through the surface (H_T = normalize(v + l − 2(n·l)n)) with the
// transmitted roughness, times (1 − F(v·H_T)), the tint and the volume's absorption, × E·|n·l|.
vec3 ggx_transmitted_light(SlSurface s, vec3 n, vec3 v, vec3 l, vec3 E) {
    float n_dot_l = dot(n, l);
    if (n_dot_l >= 0.0) return vec3(0.0);
    vec3 h, mirrored = l - 2.0 * n_dot_l * n;
    float dg = ggx_DG_over_4(n, mirrored, v, s.alpha * ggx_transmission_roughness_scale(), h);
    float f = ggx_dielectric_share(dot(v, h), s);
    return ggx_trans.weight * (1.0 - s.metallic) * (1.0 - f) * dg * (-n_dot_l) * s.base_color *
           ggx_volume_transmittance(ggx_volume_distances()) * E;
}
#endif
// The diffuse's share of the light entering the surface: 1 − transmission (KHR_materials_transmission).
float ggx_diffuse_share() {
#ifdef GGX_HAS_TRANSMISSION
    return 1.0 - ggx_trans.weight;
#else
    return 1.0;
#endif
}

vec3 ggx_model(SlSurface s, vec3 l, vec3 E) {
    vec3 n = s.normal, v = s.view;
    ggx_to_space(n, l, v);
    float n_dot_l = max(dot(n, l), 0.0);
    vec3 h;
    float dg = ggx_base_DG_over_4(s, n, l, v, h);
    vec3 F = ggx_fresnel(dot(l, h), s);
#if GGX_ZERO_SPECULAR
    dg = 0.0;
#endif
#if defined(GGX_HAS_SPECULAR)
    // the extension's dielectric_brdf: the diffuse under 1 − max(F_d) of the dielectric's Fresnel
    vec3 Fd = ggx_dielectric_fresnel(dot(l, h), ggx_gltf_dielectric_f0(), ggx_spec_color, ggx_spec_strength);
#ifdef GGX_HAS_IRIDESCENCE
    Fd = mix(Fd, ggx_film_fresnel(abs(dot(l, h)), ggx_dielectric_f0_colour(), ggx_irid.film_ior, ggx_irid.thickness),
             ggx_irid.weight);
#endif
    vec3 diffuse = (1.0 - max(Fd.r, max(Fd.g, Fd.b))) * (1.0 - s.metallic) * ggx_diffuse_share() * s.base_color * SL_INV_PI;
    vec3 base = (diffuse + F * dg) * E * n_dot_l;
#elif SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    vec3 diffuse = (1.0 - F) * (1.0 - s.metallic) * ggx_diffuse_share() * s.base_color * SL_INV_PI;
    vec3 base = (diffuse + F * dg) * E * n_dot_l;
#else
    vec3 base = (ggx_diffuse_share() * s.base_color * SL_INV_PI + s.specular * F * dg) * E * n_dot_l;
#endif
#ifdef GGX_HAS_TRANSMISSION
    base += ggx_transmitted_light(s, n, v, l, E);
#endif
#ifdef GGX_HAS_SHEEN
    base = ggx_sheen_layer(base, E, ggx_sheen.colour, ggx_sheen.roughness, ggx_sheen.scale, n, v, l);
#endif
#ifdef GGX_HAS_CLEARCOAT
    base = ggx_clearcoat_over(base, s, l, E);
#endif
    return base;
}

// The model's lobes (ABI 1.14, the SDK's lobe contract): the ggx BRDF is one GGX microfacet lobe
// plus Lambert, so the description is exact: α, F0 (Schlick's from η, or glTF's
// mix(0.04, base, metallic) with the diffuse under 1 − F), F90 = 1, weight k_s; with
// fresnel = exact the exact dielectric Fresnel (eta). GGX_ZERO_SPECULAR switches the lobe off.
SlLobes ggx_lobes(SlSurface s) {
    SlLobes L = sl_lobes_none();
    L.count = 1;
    L.lobe[0].alpha = max(s.alpha, GGX_MIN_ALPHA);
    L.lobe[0].f90 = vec3(1.0);
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    L.diffuse = (1.0 - s.metallic) * s.base_color;
    L.diffuse_coupled = true;
    L.lobe[0].f0 = mix(vec3(ggx_gltf_dielectric_f0()), s.base_color, s.metallic);
    L.lobe[0].weight = 1.0;
#ifdef GGX_HAS_SPECULAR
    // KHR_materials_specular: the dielectric's F0 and F90 (strength) mixed with the metal's;
    // approximated: integrators weight the diffuse by 1 − F per channel, not by 1 − max(F_d)
    L.lobe[0].f0 = mix(min(vec3(ggx_gltf_dielectric_f0()) * ggx_spec_color, vec3(1.0)) * ggx_spec_strength,
                       s.base_color, s.metallic);
    L.lobe[0].f90 = vec3(mix(ggx_spec_strength, 1.0, s.metallic));
#endif
#else
    L.diffuse = s.base_color;
    L.lobe[0].f0 = vec3(ggx_f0_from_eta(sl_mat_eta));
    L.lobe[0].weight = s.specular;
#if SL_MAT_FRESNEL != SL_MAT_FRESNEL_SCHLICK
    L.lobe[0].eta = sl_mat_eta;
#endif
#endif
#ifdef GGX_HAS_IRIDESCENCE
    // KHR_materials_iridescence: the film's Fresnel at the view as a constant (F0 = F90) mixed in
    // by its weight, as the Khronos sample viewer lights it by the environment; point lights take
    // it at each half vector.
    vec3 film = ggx_film(clamp(dot(s.normal, s.view), 0.0, 1.0), s);
    L.lobe[0].f0 = mix(L.lobe[0].f0, film, ggx_irid.weight);
    L.lobe[0].f90 = mix(L.lobe[0].f90, film, ggx_irid.weight);
#endif
#ifdef GGX_HAS_ANISOTROPY
    // KHR_materials_anisotropy, approximated: the contract's lobes are isotropic about s.normal (no
    // bent normal), so the lobe gets the isotropic α of the same peak and slope-space area,
    // √(α_t·α_b): the stretched highlight of an environment becomes a wider round one.
    vec2 aa = ggx_aniso_alphas(s.alpha, ggx_aniso.strength);
    L.lobe[0].alpha = sqrt(aa.x * aa.y);
#endif
#if GGX_ZERO_SPECULAR
    L.lobe[0].weight = 0.0;
#endif
    // KHR_materials_transmission: the environment behind the surface reaches it through the scene
    // behind (ggx_scene_behind), so integrators see only the diffuse's remaining share
    L.diffuse *= ggx_diffuse_share();
#ifdef GGX_HAS_SHEEN
    // the sheen, approximated as a diffuse albedo colour·E(n·v): what it reflects of a uniform
    // environment, not its grazing shape; the layers below scaled by 1 − max(colour)·E(n·v). With
    // diffuse_coupled, integrators weight the diffuse by about 1 − F0 of lobe 0: divided out.
    L.diffuse *= ggx_sheen.scale;
    L.lobe[0].weight *= ggx_sheen.scale;
    vec3 sheen = ggx_sheen.colour * ggx_sheen_E(clamp(dot(s.normal, s.view), 0.0, 1.0), ggx_sheen.roughness);
    L.diffuse += L.diffuse_coupled ? sheen / max(1.0 - L.lobe[0].f0, vec3(0.05)) : sheen;
#endif
#ifdef GGX_HAS_CLEARCOAT
    // the coat as lobe 1 with the constant Fresnel F_c(n_c·v) (F0 = F90), weight w; the layers
    // below weighted by 1 − w·F_c, as for point lights; about the coat's own normal (ABI 1.26),
    // as point lights see it.
    float fc = ggx_coat_fresnel(clamp(dot(ggx_coat_normal(s), s.view), 0.0, 1.0));
    L.diffuse *= 1.0 - ggx_coat.weight * fc;
    L.lobe[0].weight *= 1.0 - ggx_coat.weight * fc;
    L.count = 2;
    L.lobe[1] = SlLobe(vec3(fc), vec3(fc), max(ggx_coat.alpha, GGX_MIN_ALPHA), ggx_coat.weight, 0.0);
    L.normal[1] = ggx_coat_normal(s);
#endif
    return L;
}

// Debug views (the head assignment's modes 4–6), summed over the lights.
vec3 ggx_debug_D(SlSurface s, vec3 l, vec3 E) {
    vec3 n = s.normal, v = s.view;
    ggx_to_space(n, l, v);
    vec3 h = normalize(l + v);
#ifdef GGX_HAS_ANISOTROPY
    vec3 t, b;
    ggx_aniso_frame(t, b);
    return vec3(ggx_aniso_D(n, t, b, h, ggx_aniso_alphas(s.alpha, ggx_aniso.strength)));
#else
    return vec3(ggx_D(dot(n, h), max(s.alpha, GGX_MIN_ALPHA)));
#endif
}
vec3 ggx_debug_G(SlSurface s, vec3 l, vec3 E) {
    vec3 n = s.normal, v = s.view;
    ggx_to_space(n, l, v);
    vec3 h = normalize(l + v);
#ifdef GGX_HAS_ANISOTROPY
    vec3 t, b;
    ggx_aniso_frame(t, b);
    return vec3(ggx_aniso_G(n, t, b, l, v, ggx_aniso_alphas(s.alpha, ggx_aniso.strength)));
#else
    float a = max(s.alpha, GGX_MIN_ALPHA);
    return vec3(ggx_G1(v, n, h, a) * ggx_G1(l, n, h, a));
#endif
}
vec3 ggx_debug_F(SlSurface s, vec3 l, vec3 E) {
    vec3 n = s.normal, v = s.view;
    ggx_to_space(n, l, v);
    if (dot(n, l) <= 0.0) return vec3(0.0); // light not visible: shown as 0
    vec3 h = normalize(l + v);
    return ggx_fresnel(dot(l, h), s);
}

// "ggx-clearcoat": the coat's own reflection (KHR_materials_clearcoat), summed over the lights; 0
// for a material without a coat or with ggx.layer_clearcoat off.
vec3 ggx_debug_clearcoat(SlSurface s, vec3 l, vec3 E) {
#ifdef GGX_HAS_CLEARCOAT
    return ggx_clearcoat_over(vec3(0.0), s, l, E);
#else
    return vec3(0.0);
#endif
}

// "ggx-specular": KHR_materials_specular's inputs after textures, specularColor × specular (the
// dielectric's F0 relative to the one its ior gives); 1 for a material without the layer.
vec3 ggx_debug_specular(SlSurface s) {
#ifdef GGX_HAS_SPECULAR
    return ggx_spec_color * ggx_spec_strength;
#else
    return vec3(1.0);
#endif
}

// "ggx-sheen": the sheen's own reflection (KHR_materials_sheen), summed over the lights; 0 for a
// material without it or with ggx.layer_sheen off.
vec3 ggx_debug_sheen(SlSurface s, vec3 l, vec3 E) {
#ifdef GGX_HAS_SHEEN
    vec3 n = s.normal, v = s.view;
    ggx_to_space(n, l, v);
    return ggx_sheen_layer(vec3(0.0), E, ggx_sheen.colour, ggx_sheen.roughness, 0.0, n, v, l);
#else
    return vec3(0.0);
#endif
}

#if defined(GGX_HAS_TRANSMISSION) && defined(SL_SCENE_BEHIND)
// The SCENE_BEHIND hook (the core's captured opaque scene, shaders/scene_behind.glsl): looked up
// where the transmitted path leaves the material (straight through a thin wall), at the mip level
// the Khronos sample viewer picks, log2(size) × the transmitted roughness: level 0 for a smooth
// wall, the whole screen's average at roughness 1.
vec3 ggx_scene_behind(SlSurface s) {
    float roughness = sqrt(max(s.alpha, 0.0)) * ggx_transmission_roughness_scale();
    float lod = roughness * sl_scene_behind_levels;
    vec3 behind = textureLod(sl_scene_behind, sl_screen_uv(ggx_trans.exit), lod).rgb;
#ifdef GGX_HAS_DISPERSION
    // KHR_materials_dispersion: red and blue each from where their own refracted ray leaves
    behind.r = textureLod(sl_scene_behind, sl_screen_uv(ggx_disp.exit_red), lod).r;
    behind.b = textureLod(sl_scene_behind, sl_screen_uv(ggx_disp.exit_blue), lod).b;
#endif
    return ggx_transmittance(s) * behind;
}
#endif

// "ggx-dispersion": how far (pixels) the red (r) and blue (b) lookups of the scene behind lie from
// the green one (KHR_materials_dispersion); 0 without the layer (or without a volume).
vec3 ggx_debug_dispersion(SlSurface s) {
#if defined(GGX_HAS_DISPERSION) && defined(SL_SCENE_BEHIND)
    vec2 g = sl_screen_uv(ggx_trans.exit);
    return vec3(length((sl_screen_uv(ggx_disp.exit_red) - g) * sl_viewport_size), 0.0,
                length((sl_screen_uv(ggx_disp.exit_blue) - g) * sl_viewport_size));
#else
    return vec3(0.0);
#endif
}

// "ggx-transmission": what the scene behind is multiplied by (ggx_transmittance); 0 for a material
// without KHR_materials_transmission or with ggx.layer_transmission off.
vec3 ggx_debug_transmission(SlSurface s) {
#ifdef GGX_HAS_TRANSMISSION
    return ggx_transmittance(s);
#else
    return vec3(0.0);
#endif
}

// "ggx-iridescence": the base's specular Fresnel at the view with the film mixed in
// (KHR_materials_iridescence), mix(F(n·v), F_film(n·v), weight); 0 for a material without the
// layer or with ggx.layer_iridescence off.
vec3 ggx_debug_iridescence(SlSurface s) {
#ifdef GGX_HAS_IRIDESCENCE
    return ggx_fresnel(clamp(dot(s.normal, s.view), 0.0, 1.0), s);
#else
    return vec3(0.0);
#endif
}

// "ggx-anisotropy": KHR_materials_anisotropy's direction in the surface's (tangent, bitangent) frame
// after the rotation, encoded as the anisotropy texture encodes it (rg = 0.5 + 0.5·direction), and
// the strength in blue; 0 for a material without the layer or with ggx.layer_anisotropy off.
vec3 ggx_debug_anisotropy(SlSurface s) {
#ifdef GGX_HAS_ANISOTROPY
    vec2 d = vec2(dot(ggx_aniso.t, s.tangent), dot(ggx_aniso.t, s.bitangent));
    return vec3(0.5 + 0.5 * d, ggx_aniso.strength);
#else
    return vec3(0.0);
#endif
}
