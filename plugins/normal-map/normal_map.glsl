// normal-map: the SURFACE hook and the two debug views. Uniforms come from the composer:
//   normal_map_strength (float), normal_map_green (int: 0 = +Y/OpenGL, 1 = −Y/DirectX),
//   normal_map_lod_bias (float, mip levels)
//   sl_mat_normal_map (sampler2D, only when the material carries a map),
//   sl_mat_normal_strength (float), SL_MAT_NORMAL_SPACE (define: tangent / object).
// Everything that reads them sits inside #if SL_MAT_HAS_NORMAL_MAP, so this file also compiles
// into a program of a material without a map (when a debug view of this plugin is selected).
#include "nm_lib.glsl"

#if defined(SL_MAT_HAS_NORMAL_MAP)
// An object-space map holds one normal per surface point (no tiling), but the core samples
// every material texture with REPEAT: within half a texel of the image border, bilinear
// filtering would blend in the opposite border (on a sphere, north-pole normals at the south
// pole). The lookup is clamped half a level-0 texel inside [0, 1]. (Clamping by the half texel
// of the coarser mip actually read was measured worse: it also shifts samples at seams that
// legitimately wrap, like a sphere's u = 0/1 meridian.)
vec2 nm_object_uv(vec2 uv) {
    vec2 half_texel = 0.5 / vec2(textureSize(sl_mat_normal_map, 0));
    return clamp(uv, half_texel, 1.0 - half_texel);
}

// The mapped world-space normal of s, before the view guard.
// In texture-space passes (draw_scene uv_space) facing follows the UV layout, and the core does not
// flip the normal there: every fragment counts as front-facing.
bool nm_front_facing() { return gl_FrontFacing || sl_uv_space != 0; }

vec3 nm_mapped_normal(SlSurface s) {
#if SL_MAT_NORMAL_SPACE == SL_MAT_NORMAL_SPACE_OBJECT
    vec3 texel = texture(sl_mat_normal_map, nm_object_uv(sl_uv_normal_map(s)), normal_map_lod_bias).rgb;
#else
    vec3 texel = texture(sl_mat_normal_map, sl_uv_normal_map(s), normal_map_lod_bias).rgb;
#endif
    float k = normal_map_strength * sl_mat_normal_strength;
#if SL_MAT_NORMAL_SPACE == SL_MAT_NORMAL_SPACE_OBJECT
    return nm_from_object_space(nm_decode(texel), sl_normal_matrix, nm_front_facing(), s.normal, k);
#else
    vec3 nt = nm_decode(texel);
    if (normal_map_green != 0) nt.y = -nt.y;
    nt = nm_tangent_scaled(nt, k);
    // On a back face the core flips N (and with it the bitangent); flipping T as well makes the
    // result exactly −(front-face normal): a bump seen from behind is a dent.
    vec3 T = nm_front_facing() ? s.tangent : -s.tangent;
    return nm_from_tangent_space(nt, T, NM_IMAGE_UP_SIGN * s.bitangent, s.normal);
#endif
}
#endif

void nm_surface(inout SlSurface s) {
#if defined(SL_MAT_HAS_NORMAL_MAP)
    s.lod_bias = normal_map_lod_bias; // the SDK contract other plugins' lookups follow (phong's gloss)
    // The mapped normal is bent where its reflection would fall below the surface, as Cycles'
    // Normal Map node does (sl_view_guard), except where there is no viewer (texture-space
    // passes: sss irradiance) and for models that handle normals facing away from the viewer
    // themselves (SL_MODEL_MASKS_FACING_AWAY: the SDK's promise to such models, ABI 1.4).
#if defined(SL_MODEL_MASKS_FACING_AWAY)
    vec3 n = nm_mapped_normal(s);
#else
    vec3 n = sl_uv_space != 0 ? nm_mapped_normal(s) : sl_view_guard(nm_mapped_normal(s), s.view, s.normal);
#endif
    // Keep the frame orthonormal around the new normal (anisotropic models read it), with the
    // same handedness.
    float w = dot(cross(s.normal, s.tangent), s.bitangent) < 0.0 ? -1.0 : 1.0;
    vec3 t = s.tangent - n * dot(n, s.tangent);
    float tl = length(t);
    if (tl < 1e-6) {
        t = abs(n.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n);
        tl = length(t);
    }
    s.tangent = t / tl;
    s.bitangent = cross(n, s.tangent) * w;
    s.normal = n;
#endif
}

// "normal-map-texture": the texel values as stored in the file (the PNG of this view shows
// the map's own colours); (0.5, 0.5, 1), the flat tangent-space texel, where there is no map.
vec3 nm_debug_texture(SlSurface s) {
#if defined(SL_MAT_HAS_NORMAL_MAP)
    return nm_srgb_decode(texture(sl_mat_normal_map, sl_uv_normal_map(s), normal_map_lod_bias).rgb);
#else
    return nm_srgb_decode(vec3(0.5, 0.5, 1.0));
#endif
}

// "final-normal": the world-space normal after every surface hook, encoded n·0.5 + 0.5 on
// screen (PNG values, like a normal map file; the core's "normal" view writes the same values
// into the linear buffer instead, so its PNG is sRGB-encoded).
vec3 nm_debug_final_normal(SlSurface s) { return nm_srgb_decode(s.normal * 0.5 + 0.5); }
