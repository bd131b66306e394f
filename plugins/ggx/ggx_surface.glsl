// Surface hooks filling s.alpha (GGX α) and s.specular (k_s) from the material. Each runs only
// for materials carrying its key (when_material_has), so a material pays only for its inputs.
#include "ggx_layers.glsl"
#include "sl:normal_guard.glsl" // the clear coat's normal texture
#ifdef SL_MAT_HAS_ALPHA
void ggx_surface_alpha(inout SlSurface s) { s.alpha = sl_mat_alpha; }
#endif
#ifdef SL_MAT_HAS_ROUGHNESS
void ggx_surface_roughness(inout SlSurface s) { s.alpha = sl_mat_roughness * sl_mat_roughness; }
#endif
#ifdef SL_MAT_HAS_METALLIC
// glTF metallicFactor (SlSurface.metallic, ABI 1.7; the metallic-roughness Fresnel reads it).
void ggx_surface_metallic(inout SlSurface s) { s.metallic = sl_mat_metallic; }
#endif
#ifdef SL_MAT_HAS_ROUGHNESS_MAP
// Perceptual roughness in the map's green channel (glTF metallic-roughness layout), times
// the roughness factor when given; α = roughness². With fresnel = metallic-roughness the blue
// channel is the metalness, times the metallic factor (glTF 2.0 §3.9.2; metallic runs first).
void ggx_surface_roughness_map(inout SlSurface s) {
    vec4 mr = texture(sl_mat_roughness_map, sl_uv_roughness_map(s));
#ifdef SL_MAT_HAS_ROUGHNESS
    float r = sl_mat_roughness * mr.g;
#else
    float r = mr.g;
#endif
    s.alpha = r * r;
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    s.metallic *= mr.b;
#endif
}
#endif
#ifdef SL_MAT_HAS_SPECULAR
void ggx_surface_specular(inout SlSurface s) { s.specular = sl_mat_specular; }
#endif
#ifdef SL_MAT_HAS_SPECULAR_MAP
// k_s from the red channel of a (linear) specular map, times the specular factor when given.
void ggx_surface_specular_map(inout SlSurface s) {
#ifdef SL_MAT_HAS_SPECULAR
    s.specular = sl_mat_specular * texture(sl_mat_specular_map, sl_uv_specular_map(s)).r;
#else
    s.specular = texture(sl_mat_specular_map, sl_uv_specular_map(s)).r;
#endif
}
#endif

#ifdef SL_MAT_HAS_NORMAL_MAP
// Specular antialiasing (Toksvig 2005, in the GGX form α'² = α² + (1 − |N̄|)/|N̄|): the core's
// mip chain of the normal map is a box filter of the encoded normals, so the trilinear fetch
// at this pixel's footprint gives the average normal N̄ over it; the shorter it is, the more
// the normals below the pixel vary, and that variance widens the lobe. At the finest level
// |N̄| = 1 and α is unchanged. Runs after the material inputs and the normal-map plugin's hook (order 20).
// Not in a TAA still's jittered frames (sl_texture_lod_bias < 0, ABI 1.30): they read the map at
// their share of the pixel and their mean resolves the bumps itself; widening each frame's lobe
// as well darkened and blurred the still (README). Motion and a still's first frame keep it.
void ggx_surface_specular_aa(inout SlSurface s) {
#if GGX_SPECULAR_AA
    if (sl_texture_lod_bias < 0.0) return;
    vec3 avg = texture(sl_mat_normal_map, sl_uv_normal_map(s)).xyz * 2.0 - 1.0;
    float len = clamp(length(avg), 1e-3, 1.0);
    float variance = (1.0 - len) / len;
    s.alpha = sqrt(min(s.alpha * s.alpha + variance, 1.0));
#endif
}
#endif

#ifdef SL_MAT_HAS_CLEARCOAT
// KHR_materials_clearcoat's inputs, read once per fragment into ggx_coat. Runs before the
// normal-map hook (order 10): the coat does not follow the base's normal texture (the extension:
// without a clearcoatNormalTexture the coat has no normal mapping), so its normal is taken here,
// or from its own normal texture in this (pre-mapping) tangent frame.
void ggx_surface_clearcoat(inout SlSurface s) {
#ifdef GGX_HAS_CLEARCOAT
    float w = sl_mat_clearcoat, r = 0.0;
#ifdef SL_MAT_HAS_CLEARCOAT_MAP
    w *= texture(sl_mat_clearcoat_map, sl_uv_clearcoat_map(s)).r;
#endif
#ifdef SL_MAT_HAS_CLEARCOAT_ROUGHNESS
    r = sl_mat_clearcoat_roughness;
#endif
#ifdef SL_MAT_HAS_CLEARCOAT_ROUGHNESS_MAP
    r *= texture(sl_mat_clearcoat_roughness_map, sl_uv_clearcoat_roughness_map(s)).g;
#endif
    vec3 n = s.normal;
#ifdef SL_MAT_HAS_CLEARCOAT_NORMAL_MAP
    vec3 t = texture(sl_mat_clearcoat_normal_map, sl_uv_clearcoat_normal_map(s)).xyz * 2.0 - 1.0;
#ifdef SL_MAT_HAS_CLEARCOAT_NORMAL_SCALE
    t.xy *= sl_mat_clearcoat_normal_scale;
#endif
    vec3 m = s.tangent * t.x + s.bitangent * t.y + s.normal * t.z;
    // guarded as normal-map guards the base's (sl:normal_guard.glsl), except without a viewer
    if (dot(m, m) > 1e-12) n = sl_uv_space != 0 ? normalize(m) : sl_view_guard(normalize(m), s.view, s.normal);
#endif
    ggx_coat = GgxClearcoat(clamp(w, 0.0, 1.0), r * r, n);
#ifdef SL_MAT_HAS_EMISSIVE
    // the coat lies over the emission too: it keeps 1 − w·F_c(n_c·v) of it (the extension's
    // "Emission"), as of the layers below under every light
    s.emission_weight *= 1.0 - ggx_coat.weight * ggx_coat_fresnel(clamp(dot(n, s.view), 0.0, 1.0));
#endif
#endif
}
#endif

// KHR_materials_specular's inputs into ggx_spec_strength / ggx_spec_color; the maps run after
// the factors (order) and multiply them.
#ifdef SL_MAT_HAS_DIELECTRIC_SPECULAR
void ggx_surface_dielectric_specular(inout SlSurface s) {
#ifdef GGX_HAS_SPECULAR
    ggx_spec_strength = sl_mat_dielectric_specular;
#endif
}
#endif
#ifdef SL_MAT_HAS_DIELECTRIC_SPECULAR_MAP
void ggx_surface_dielectric_specular_map(inout SlSurface s) {
#ifdef GGX_HAS_SPECULAR
    ggx_spec_strength *= texture(sl_mat_dielectric_specular_map, sl_uv_dielectric_specular_map(s)).a;
#endif
}
#endif
#ifdef SL_MAT_HAS_DIELECTRIC_SPECULAR_COLOR
void ggx_surface_dielectric_specular_color(inout SlSurface s) {
#ifdef GGX_HAS_SPECULAR
    ggx_spec_color = sl_mat_dielectric_specular_color;
#endif
}
#endif
#ifdef SL_MAT_HAS_DIELECTRIC_SPECULAR_COLOR_MAP
void ggx_surface_dielectric_specular_color_map(inout SlSurface s) {
#ifdef GGX_HAS_SPECULAR
    ggx_spec_color *= texture(sl_mat_dielectric_specular_color_map, sl_uv_dielectric_specular_color_map(s)).rgb;
#endif
}
#endif

#ifdef SL_MAT_HAS_SHEEN_COLOR
// KHR_materials_sheen's inputs into ggx_sheen, with the albedo scaling of the layers below.
void ggx_surface_sheen(inout SlSurface s) {
#ifdef GGX_HAS_SHEEN
    vec3 c = sl_mat_sheen_color;
    float r = 0.0;
#ifdef SL_MAT_HAS_SHEEN_COLOR_MAP
    c *= texture(sl_mat_sheen_color_map, sl_uv_sheen_color_map(s)).rgb;
#endif
#ifdef SL_MAT_HAS_SHEEN_ROUGHNESS
    r = sl_mat_sheen_roughness;
#endif
#ifdef SL_MAT_HAS_SHEEN_ROUGHNESS_MAP
    r *= texture(sl_mat_sheen_roughness_map, sl_uv_sheen_roughness_map(s)).a;
#endif
    float e = ggx_sheen_E(clamp(dot(s.normal, s.view), 0.0, 1.0), r);
    ggx_sheen = GgxSheen(c, r, 1.0 - max(c.r, max(c.g, c.b)) * e);
#endif
}
#endif

#ifdef GGX_HAS_VOLUME
// The path into the volume of index `ior` from air, r = refract(−v, n, 1/ior) (straight on under
// total internal reflection, which cannot happen from air), and its world length through the
// thickness τ (mesh units along r): τ/|M⁻¹r|.
vec3 ggx_volume_path(SlSurface s, float ior, float thickness, out float distance) {
    vec3 r = -s.view, bent = refract(-s.view, s.normal, 1.0 / max(ior, 1.0));
    if (dot(bent, bent) > 0.5) r = normalize(bent);
    distance = max(thickness, 0.0) / max(length(transpose(sl_normal_matrix) * r), 1e-6);
    return r;
}
#endif

#ifdef SL_MAT_HAS_TRANSMISSION
// KHR_materials_transmission's inputs into ggx_trans, once per fragment, after the normal map
// (order 22). With KHR_materials_volume's thickness τ (mesh units) the path into the volume is
// refracted by the IOR from air, r = refract(−v, n, 1/ior), and leaves it after τ measured in the
// mesh's space along r: a world length τ/|M⁻¹r| (M⁻¹ = transpose of sl_normal_matrix), as the
// extension's thickness is "given in the coordinate space of the mesh".
void ggx_surface_transmission(inout SlSurface s) {
#ifdef GGX_HAS_TRANSMISSION
    float t = sl_mat_transmission, distance = 0.0;
#ifdef SL_MAT_HAS_TRANSMISSION_MAP
    t *= texture(sl_mat_transmission_map, sl_uv_transmission_map(s)).r;
#endif
    vec3 r = -s.view;
#ifdef GGX_HAS_VOLUME
    float thickness = sl_mat_thickness;
#ifdef SL_MAT_HAS_THICKNESS_MAP
    thickness *= texture(sl_mat_thickness_map, sl_uv_thickness_map(s)).g;
#endif
    r = ggx_volume_path(s, ggx_ior(), thickness, distance);
#ifdef GGX_HAS_DISPERSION
    // KHR_materials_dispersion: red and blue along their own refracted rays
    vec3 iors = ggx_dispersion_iors(ggx_ior(), max(sl_mat_dispersion, 0.0));
    float d_red, d_blue;
    vec3 r_red = ggx_volume_path(s, iors.r, thickness, d_red), r_blue = ggx_volume_path(s, iors.b, thickness, d_blue);
    ggx_disp = GgxDispersion(s.position + r_red * d_red, s.position + r_blue * d_blue, vec3(d_red, distance, d_blue));
#endif
#endif
    ggx_trans = GgxTransmission(clamp(t, 0.0, 1.0), distance, s.position + r * distance);
#endif
}
#endif

#ifdef SL_MAT_HAS_IRIDESCENCE
// KHR_materials_iridescence's inputs into ggx_irid, once per fragment: the weight (factor × R of
// its texture), the thickness mix(minimum, maximum, G of the thickness texture) or the maximum
// without that texture, and the film's IOR. A film of thickness 0 is no film (weight 0).
void ggx_surface_iridescence(inout SlSurface s) {
#ifdef GGX_HAS_IRIDESCENCE
    float w = sl_mat_iridescence, eta = 1.3, d_min = 100.0, d_max = 400.0;
#ifdef SL_MAT_HAS_IRIDESCENCE_MAP
    w *= texture(sl_mat_iridescence_map, sl_uv_iridescence_map(s)).r;
#endif
#ifdef SL_MAT_HAS_IRIDESCENCE_IOR
    eta = sl_mat_iridescence_ior;
#endif
#ifdef SL_MAT_HAS_IRIDESCENCE_THICKNESS_MIN
    d_min = sl_mat_iridescence_thickness_min;
#endif
#ifdef SL_MAT_HAS_IRIDESCENCE_THICKNESS_MAX
    d_max = sl_mat_iridescence_thickness_max;
#endif
    float d = d_max;
#ifdef SL_MAT_HAS_IRIDESCENCE_THICKNESS_MAP
    d = mix(d_min, d_max, texture(sl_mat_iridescence_thickness_map, sl_uv_iridescence_thickness_map(s)).g);
#endif
    d = max(d, 0.0);
    ggx_irid = GgxIridescence(d > 0.0 ? clamp(w, 0.0, 1.0) : 0.0, d, max(eta, 1.0));
#endif
}
#endif

#ifdef SL_MAT_HAS_ANISOTROPY
// KHR_materials_anisotropy's inputs into ggx_aniso, once per fragment, after the normal map (order
// 23). The direction in (tangent, bitangent) space is (cos r, sin r), r = anisotropyRotation
// (counter-clockwise from the tangent), or the texture's rg·2 − 1 (normalised) rotated by r, whose
// blue channel multiplies the strength; in the world it is made orthogonal to the shading normal.
void ggx_surface_anisotropy(inout SlSurface s) {
#ifdef GGX_HAS_ANISOTROPY
    float strength = sl_mat_anisotropy, r = 0.0;
#ifdef SL_MAT_HAS_ANISOTROPY_ROTATION
    r = sl_mat_anisotropy_rotation;
#endif
    vec2 rot = vec2(cos(r), sin(r)), d = rot;
#ifdef SL_MAT_HAS_ANISOTROPY_MAP
    vec3 tex = texture(sl_mat_anisotropy_map, sl_uv_anisotropy_map(s)).rgb;
    vec2 td = tex.rg * 2.0 - 1.0;
    td = dot(td, td) > 1e-8 ? normalize(td) : vec2(1.0, 0.0);
    d = mat2(rot.x, rot.y, -rot.y, rot.x) * td;
    strength *= tex.b;
#endif
    vec3 dir = s.tangent * d.x + s.bitangent * d.y, t = dir - s.normal * dot(s.normal, dir);
    if (dot(t, t) < 1e-12) t = cross(s.normal, abs(s.normal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0));
    t = normalize(t);
    ggx_aniso = GgxAnisotropy(clamp(strength, 0.0, 1.0), t, cross(s.normal, t));
#endif
}
#endif
