/* ggx: the Cook–Torrance microfacet BRDF with the GGX distribution (Walter et al. 2007), exact
 * dielectric Fresnel, Schlick, and the glTF metallic-roughness combination, chosen per material.
 * GLSL: the SDK shader library's ggx_brdf.glsl (pure BRDF terms, shared with every model that
 * needs them: envmap, sss, extras), ggx_model.glsl (the shading model and debug views),
 * ggx_surface.glsl (material inputs → SlSurface). See README.md. */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include <math.h>
#include <stdlib.h>

static const char *const fresnel_modes[] = {"exact", "schlick", "metallic-roughness", NULL};
static const char *const spaces[] = {"world", "camera", NULL};
static const char *const g1_angles[] = {"normal", "half-vector", NULL};

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    /* globals */
    P(.id = "space", .type = SL_PARAM_ENUM, .enum_values = spaces, .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "debug",
      .description = "Space the BRDF is evaluated in; world and camera must agree (a rotation)."),
    P(.id = "zero_specular", .type = SL_PARAM_BOOL, .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "debug",
      .description = "Diffuse only: drops the specular term of every ggx material."),
    P(.id = "g1_angle", .type = SL_PARAM_ENUM, .enum_values = g1_angles, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "model",
      .description = "Angle θ_x in G1: from the normal (Walter et al. 2007) or from h (the head assignment's wording)."),
    P(.id = "specular_aa", .type = SL_PARAM_BOOL, .default_value = {.b = true},
      .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB,
      .group = "quality",
      .description = "Toksvig specular antialiasing: normal-map variance from its mip chain widens alpha."),
    P(.id = "layer_clearcoat", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the clear coat of materials that carry one (KHR_materials_clearcoat)."),
    P(.id = "layer_sheen", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the sheen of materials that carry one (KHR_materials_sheen)."),
    P(.id = "layer_specular", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the specular strength and colour of materials that carry them (KHR_materials_specular)."),
    P(.id = "layer_iridescence", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the thin film of materials that carry one (KHR_materials_iridescence)."),
    P(.id = "layer_anisotropy", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the anisotropy of materials that carry it (KHR_materials_anisotropy)."),
    P(.id = "layer_transmission", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the transmission of materials that carry it (KHR_materials_transmission): "
                                        "the opaque scene seen through them."),
    P(.id = "layer_dispersion", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the dispersion of volumes that carry it (KHR_materials_dispersion): "
                                        "an index of refraction per colour channel."),
    P(.id = "layer_volume", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the volume of transmissive materials that carry one (KHR_materials_volume): "
                                        "refraction through its thickness and its absorption."),
    /* material keys */
    P(.id = "alpha", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {0.3f}}, .min = 0, .max = 1,
      .step = 0.01f, .group = "ggx", .description = "GGX α (width of the microfacet distribution); 0 is clamped to 2e-3."),
    P(.id = "roughness", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {0.5f}}, .min = 0,
      .max = 1, .step = 0.01f, .group = "ggx", .material_input = "roughness",
      .description = "Perceptual roughness (glTF): α = roughness²."),
    P(.id = "roughness_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "ggx", .material_input = "metallic_roughness_texture",
      .description = "Roughness in the green channel (glTF layout), times roughness when given; with fresnel = "
                     "metallic-roughness, metalness in the blue channel, times metallic."),
    P(.id = "specular", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}}, .min = 0,
      .max = 1, .step = 0.01f, .group = "ggx", .description = "k_s, the weight of the specular term."),
    P(.id = "specular_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "ggx", .description = "k_s from the red channel (linear), times specular when given."),
    P(.id = "eta", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.0f / 1.5f}},
      .min = 0.05f, .max = 20, .step = 0.01f, .group = "ggx",
      .description = "Relative index of refraction η = n1/n2 (air over glass: 1/1.5)."),
    P(.id = "fresnel", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_MATERIAL, .enum_values = fresnel_modes,
      .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "ggx", .material_input = "brdf",
      .description = "exact dielectric Fresnel, Schlick, or glTF metallic-roughness (F0 = mix(0.04, base, metallic))."),
    P(.id = "ior", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.5f}}, .min = 0,
      .max = 10, .step = 0.01f, .group = "ggx", .material_input = "ior",
      .description = "fresnel = metallic-roughness: the dielectric's index of refraction (KHR_materials_ior), "
                     "F0 = ((ior - 1)/(ior + 1))^2; 0.04 without it."),
    P(.id = "metallic", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "ggx", .material_input = "metallic", .description = "Metalness for fresnel = metallic-roughness."),
    /* KHR_materials_specular (README "Layers"), for fresnel = metallic-roughness */
    P(.id = "dielectric_specular", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}}, .min = 0,
      .max = 1, .step = 0.01f, .group = "specular", .material_input = "specular",
      .description = "Strength of the dielectric's specular reflection (its F0 and F90); 0: diffuse only."),
    P(.id = "dielectric_specular_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "specular", .material_input = "specular_texture",
      .description = "Specular strength in the alpha channel, times dielectric_specular."),
    P(.id = "dielectric_specular_color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1, 1, 1}},
      .min = 0, .max = 100, .group = "specular", .material_input = "specular_color",
      .description = "Colour scaling the dielectric's F0 (min(F0 * colour, 1)); F90 stays the strength."),
    P(.id = "dielectric_specular_color_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .group = "specular",
      .material_input = "specular_color_texture", .description = "Specular colour (sRGB), times dielectric_specular_color."),
    /* KHR_materials_sheen (README "Layers") */
    P(.id = "sheen_color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL, .group = "sheen", .material_input = "sheen_color",
      .description = "Colour of the sheen (Charlie microfibres) over the material; black: no sheen."),
    P(.id = "sheen_color_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .group = "sheen",
      .material_input = "sheen_color_texture", .description = "Sheen colour (sRGB), times sheen_color."),
    P(.id = "sheen_roughness", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "sheen", .material_input = "sheen_roughness", .description = "Sheen roughness: alpha = roughness^2 (0 without it)."),
    P(.id = "sheen_roughness_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "sheen", .material_input = "sheen_roughness_texture",
      .description = "Sheen roughness in the alpha channel, times sheen_roughness."),
    /* KHR_materials_transmission and _volume (README "Layers") */
    P(.id = "transmission", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "transmission", .material_input = "transmission",
      .description = "Share of the light entering the surface that passes through it instead of being diffused: the "
                     "opaque scene behind, tinted by the base colour."),
    P(.id = "transmission_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "transmission", .material_input = "transmission_texture",
      .description = "Transmission in the red channel, times transmission."),
    P(.id = "thickness", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1000, .step = 0.01f,
      .group = "transmission", .material_input = "thickness",
      .description = "Thickness of the volume under a transmissive surface, in the mesh's units; 0 or absent: a thin wall."),
    P(.id = "thickness_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "transmission", .material_input = "thickness_texture",
      .description = "Thickness in the green channel, times thickness."),
    P(.id = "attenuation_distance", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}},
      .min = 1e-6f, .max = 1e9f, .step = 0.01f, .group = "transmission", .material_input = "attenuation_distance",
      .description = "Distance in the volume after which white light has become attenuation_color (Beer-Lambert); "
                     "absent: no absorption."),
    P(.id = "attenuation_color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1, 1, 1}},
      .min = 0, .max = 1, .group = "transmission", .material_input = "attenuation_color",
      .description = "What white light turns into after attenuation_distance in the volume."),
    P(.id = "dispersion", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 100, .step = 0.01f,
      .group = "transmission", .material_input = "dispersion",
      .description = "20 / Abbe number of the volume: its IOR per colour channel (KHR_materials_dispersion); 0: none."),
    /* KHR_materials_iridescence (README "Layers"), for fresnel = metallic-roughness */
    P(.id = "iridescence", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "iridescence", .material_input = "iridescence",
      .description = "Weight of the thin film's Fresnel in the base's specular reflection; 0: no film."),
    P(.id = "iridescence_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "iridescence", .material_input = "iridescence_texture",
      .description = "Iridescence weight in the red channel, times iridescence."),
    P(.id = "iridescence_ior", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.3f}}, .min = 1,
      .max = 5, .step = 0.01f, .group = "iridescence", .material_input = "iridescence_ior",
      .description = "Index of refraction of the thin film."),
    P(.id = "iridescence_thickness_min", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {100}},
      .min = 0, .max = 5000, .step = 1, .group = "iridescence", .material_input = "iridescence_thickness_minimum",
      .description = "Film thickness (nm) where the thickness map's green channel is 0."),
    P(.id = "iridescence_thickness_max", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {400}},
      .min = 0, .max = 5000, .step = 1, .group = "iridescence", .material_input = "iridescence_thickness_maximum",
      .description = "Film thickness (nm) where the thickness map's green channel is 1, and without the map; 0: no film."),
    P(.id = "iridescence_thickness_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "iridescence", .material_input = "iridescence_thickness_texture",
      .description = "Film thickness in the green channel, from iridescence_thickness_min to _max."),
    /* KHR_materials_anisotropy (README "Layers") */
    P(.id = "anisotropy", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "anisotropy", .material_input = "anisotropy_strength",
      .description = "Anisotropy strength: the specular lobe's alpha along the direction is mix(alpha, 1, strength^2)."),
    P(.id = "anisotropy_rotation", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = -6.2832f, .max = 6.2832f,
      .step = 0.01f, .unit = "rad", .group = "anisotropy", .material_input = "anisotropy_rotation",
      .description = "Direction of the stretch, radians counter-clockwise from the tangent toward the bitangent."),
    P(.id = "anisotropy_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "anisotropy", .material_input = "anisotropy_texture",
      .description = "Direction in red and green (2 * rg - 1, tangent space, then rotated), strength in blue (times anisotropy)."),
    /* KHR_materials_clearcoat (README "Layers") */
    P(.id = "clearcoat", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "clearcoat", .material_input = "clearcoat",
      .description = "Clear-coat weight: a second GGX lobe (IOR 1.5) over the material, which it dims by 1 - weight*F."),
    P(.id = "clearcoat_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "clearcoat", .material_input = "clearcoat_texture",
      .description = "Clear-coat weight in the red channel, times clearcoat."),
    P(.id = "clearcoat_roughness", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "clearcoat", .material_input = "clearcoat_roughness",
      .description = "Perceptual roughness of the coat: its alpha = roughness^2 (0 without it)."),
    P(.id = "clearcoat_roughness_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "clearcoat", .material_input = "clearcoat_roughness_texture",
      .description = "Coat roughness in the green channel, times clearcoat_roughness."),
    P(.id = "clearcoat_normal_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "clearcoat", .material_input = "clearcoat_normal_texture",
      .description = "The coat's own tangent-space normal map (+Y up); without it the coat follows the mesh's normal."),
    P(.id = "clearcoat_normal_scale", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}},
      .min = 0, .max = 10, .step = 0.01f, .group = "clearcoat", .material_input = "clearcoat_normal_scale",
      .description = "Scale of the coat normal map's X and Y."),
};

#define C(...) {.struct_size = sizeof(sl_shader_chunk_desc), __VA_ARGS__}
static const sl_shader_chunk_desc chunks[] = {
    /* no SL_CHUNK_MASKS_FACING_AWAY: normal maps bend this model's normals as Cycles does
     * (README, "Numerical guards") */
    C(.hook = SL_HOOK_SHADING_MODEL, .file = "ggx_model.glsl", .function = "ggx_model", .name = "ggx"),
    C(.hook = SL_HOOK_MODEL_LOBES, .file = "ggx_model.glsl", .function = "ggx_lobes", .name = "ggx"),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_alpha", .when_material_has = "alpha"),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_roughness",
      .when_material_has = "roughness", .order = 1),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_roughness_map",
      .when_material_has = "roughness_map", .order = 2),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_metallic",
      .when_material_has = "metallic", .order = 1),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_specular",
      .when_material_has = "specular"),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_specular_map",
      .when_material_has = "specular_map", .order = 1),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_specular_aa",
      .when_material_has = "normal_map", .order = 20),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_dielectric_specular",
      .when_material_has = "dielectric_specular", .order = 3),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_dielectric_specular_map",
      .when_material_has = "dielectric_specular_map", .order = 4),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_dielectric_specular_color",
      .when_material_has = "dielectric_specular_color", .order = 3),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_dielectric_specular_color_map",
      .when_material_has = "dielectric_specular_color_map", .order = 4),
    /* after normal-map (order 10): the albedo scaling reads the shading normal */
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_sheen", .when_material_has = "sheen_color",
      .order = 21),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_sheen", .name = "ggx-sheen",
      .description = "the sheen's own reflection, summed over lights"),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "ggx_model.glsl", .function = "ggx_debug_specular", .name = "ggx-specular",
      .description = "KHR_materials_specular: specular colour times strength (1 without the layer)"),
    /* before normal-map (order 10): the coat keeps the mesh's normal */
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_clearcoat",
      .when_material_has = "clearcoat", .order = 5),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_clearcoat",
      .name = "ggx-clearcoat", .description = "the clear coat's own reflection, summed over lights"),
    /* after the coat and sheen (their dimming of the layers below) and the normal map */
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_iridescence",
      .when_material_has = "iridescence", .when_param = "layer_iridescence", .order = 6),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "ggx_model.glsl", .function = "ggx_debug_iridescence", .name = "ggx-iridescence",
      .description = "KHR_materials_iridescence: the specular Fresnel at the view with the thin film mixed in"),
    /* after the normal map (order 10) and specular AA (20): the frame and α it reads */
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_anisotropy",
      .when_material_has = "anisotropy", .when_param = "layer_anisotropy", .order = 23),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "ggx_model.glsl", .function = "ggx_debug_anisotropy", .name = "ggx-anisotropy",
      .description = "KHR_materials_anisotropy: direction in tangent space as rg (0.5 + 0.5 dir), strength in b"),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_transmission",
      .when_material_has = "transmission", .when_param = "layer_transmission", .order = 22),
    C(.hook = SL_HOOK_SCENE_BEHIND, .file = "ggx_model.glsl", .function = "ggx_scene_behind",
      .when_material_has = "transmission", .when_param = "layer_transmission"),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "ggx_model.glsl", .function = "ggx_debug_dispersion", .name = "ggx-dispersion",
      .description = "KHR_materials_dispersion: pixels from the green lookup of the scene behind to the red (r) and blue (b) ones"),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "ggx_model.glsl", .function = "ggx_debug_transmission",
      .name = "ggx-transmission", .description = "what the scene behind is multiplied by (transmission, tint, Fresnel, absorption)"),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_D", .name = "ggx-d",
      .description = "GGX distribution D(h), summed over lights"),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_G", .name = "ggx-g",
      .description = "Smith masking-shadowing G = G1(v)G1(l)"),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_F", .name = "ggx-f",
      .description = "Fresnel F(l·h); 0 where the light is not visible"),
};

static const sl_key_desc keys[] = {
    {.struct_size = sizeof(sl_key_desc), .key = "Z", .param = "zero_specular", .description = "toggle zero specular"},
};

/* ---- the sheen's directional albedo (ggx_layers.glsl, KHR_materials_sheen) ------------------- */
/* The same Charlie distribution and visibility as ggx_layers.glsl (Conty Estevez & Kulla 2017). */
#define SHEEN_MU 32
#define SHEEN_ROUGH 8
static double sheen_L(double x, double a) {
    double t = (1 - a) * (1 - a);
    double A = 25.3245 * t + 21.5473 * (1 - t), B = 3.32435 * t + 3.82987 * (1 - t), C = 0.16801 * t + 0.19823 * (1 - t);
    double D = -1.27393 * t - 1.97760 * (1 - t), E = -4.85967 * t - 4.32054 * (1 - t);
    return A / (1 + B * pow(x, C)) + D * x + E;
}
static double sheen_lambda(double c, double a) {
    return c < 0.5 ? exp(sheen_L(c, a)) : exp(2 * sheen_L(0.5, a) - sheen_L(1 - c, a));
}
/* E(μ, α) = ∫ D·V·(n·l) dl, midpoint rule in (cos θ_l, φ) over the half of the hemisphere that
 * the symmetry about the plane of v and n gives twice */
static double sheen_albedo(double mu, double alpha) {
    enum { NT = 48, NP = 48 };
    alpha = fmax(alpha, 0.07 * 0.07);
    double inv = 1 / alpha, vx = sqrt(fmax(1 - mu * mu, 0)), sum = 0, lv = sheen_lambda(mu, alpha);
    for (int i = 0; i < NT; i++) {
        double ct = (i + 0.5) / NT, st = sqrt(1 - ct * ct), ll = sheen_lambda(ct, alpha);
        for (int j = 0; j < NP; j++) {
            double ph = (j + 0.5) * M_PI / NP, hx = st * cos(ph) + vx, hy = st * sin(ph), hz = ct + mu;
            double nh = hz / sqrt(hx * hx + hy * hy + hz * hz), sin2 = fmax(1 - nh * nh, 0);
            double d = (2 + inv) * pow(sin2, 0.5 * inv) / (2 * M_PI);
            sum += d / ((1 + lv + ll) * 4 * mu);
        }
    }
    return sum * 2 * (1.0 / NT) * (M_PI / NP);
}

typedef struct ggx {
    const sl_host *host;
    float sheen_albedo[SHEEN_ROUGH * SHEEN_MU]; /* [roughness][μ], μ and roughness from 0 to 1 */
    bool sheen_ready;
} ggx;

/* Programs with a sheen (uniform ggx_sheen_albedo) get the table, made at the first of them. */
static void ggx_bind(void *user, unsigned program, int material, const sl_frame *frame) {
    (void)material, (void)frame;
    ggx *g = user;
    int at = glGetUniformLocation(program, "ggx_sheen_albedo");
    if (at < 0) return;
    if (!g->sheen_ready) {
        for (int r = 0; r < SHEEN_ROUGH; r++)
            for (int m = 0; m < SHEEN_MU; m++) {
                double rough = (double)r / (SHEEN_ROUGH - 1), mu = fmax((double)m / (SHEEN_MU - 1), 1e-3);
                g->sheen_albedo[r * SHEEN_MU + m] = (float)sheen_albedo(mu, rough * rough);
            }
        g->sheen_ready = true;
    }
    glUniform4fv(at, SHEEN_ROUGH * SHEEN_MU / 4, g->sheen_albedo);
}

static sl_status ggx_activate(void *user) {
    ggx *g = user;
    const char *missing = NULL;
    if (!sl_gl_load(g->host->gl_get_proc_address, &missing)) {
        g->host->log(g->host, SL_LOG_ERROR, "GL entry point %s missing", missing ? missing : "?");
        return SL_ERR_GL;
    }
    return SL_OK;
}

static void ggx_destroy(void *user) { free(user); }

static sl_status ggx_create(const sl_host *host, void **user) {
    ggx *g = calloc(1, sizeof *g);
    *user = g;
    if (!g) return SL_ERR_FAILED;
    g->host = host;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    /* ground truth for the specular_aa knob (shadelab-bench --plugin ggx, --reference ggx) */
    static const sl_reference_desc reference = {
        .struct_size = sizeof reference, .settings = "core.ssaa=8 core.anisotropy=1 ggx.specular_aa=false",
        .description = "8x8 supersampling without specular antialiasing: every sample shades the normal map at its "
                       "own, finer mip level."};
    host->set_reference(host, &reference);
    return host->set_bind_callback(host, ggx_bind, g);
}

/* The glTF metallic-roughness BRDF (fresnel = metallic-roughness) and its inputs: imported
 * glTF materials load this plugin (the host reads this list without calling create). */
static const char *const ggx_inputs[] = {"brdf", "metallic", "roughness", "metallic_roughness_texture", "ior",
                                         "sheen_color", "sheen_color_texture", "sheen_roughness",
                                         "sheen_roughness_texture", "specular", "specular_texture", "specular_color", "specular_color_texture",
                                         "clearcoat", "clearcoat_texture", "clearcoat_roughness",
                                         "clearcoat_roughness_texture", "clearcoat_normal_texture",
                                         "clearcoat_normal_scale", "transmission", "transmission_texture", "thickness",
                                         "thickness_texture", "attenuation_distance", "attenuation_color", "dispersion", "iridescence",
                                         "iridescence_texture", "iridescence_ior", "iridescence_thickness_minimum",
                                         "iridescence_thickness_maximum", "iridescence_thickness_texture",
                                         "anisotropy_strength", "anisotropy_rotation", "anisotropy_texture", NULL};

static const char *const ggx_models[] = {"ggx", NULL};
static const sl_plugin_desc ggx_desc = {
    SL_PLUGIN_HEADER,
    .id = "ggx",
    .version = "1.0",
    .description = "Cook-Torrance GGX microfacet BRDF: exact/Schlick/metallic-roughness Fresnel, D/G/F debug views.",
    .create = ggx_create,
    .activate = ggx_activate,
    .destroy = ggx_destroy,
    .material_inputs = ggx_inputs,
    .shading_models = ggx_models,
};

SL_DEFINE_PLUGIN(ggx_desc)
