// The core's occlusion SURFACE hook (core_plugin.c), in its own file: chunk files are included
// once each, material.glsl always.
// glTF 2.0 occlusion (SURFACE hook, materials with "occlusion_map"): ao = 1 + strength · (r − 1)
// on s.ao, which only the ambient and environment terms read, so direct light is unaffected.
#ifdef SL_MAT_HAS_OCCLUSION_MAP
void sl_surface_occlusion(inout SlSurface s) {
    s.ao *= 1.0 + sl_mat_occlusion_strength * (texture(sl_mat_occlusion_map, sl_uv_occlusion_map(s)).r - 1.0);
}
#endif
