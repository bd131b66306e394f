// many-lights: the G-buffer writer, composed into each material's program (draw_scene
// `fragment`, ABI 1.7): the material's own surface hooks fill the SlSurface, stored as
//   g0 RGBA32F  world position xyz (exact), material index + 1 (0: nothing drawn)
//   g1 RGBA16F  shading normal xyz (half floats, ~1e-3 relative), ao
//   g2 RGBA16F  base colour rgb (linear), alpha (GGX α)
//   g3 RGBA16F  specular, opacity, lod_bias, metallic (SlSurface.metallic, ABI 1.7)
//   g4 R32F     the pixel's footprint of normals (sl_normal_footprint, ABI 1.23): the deferred pass
//               filters lobes over the forward pass's own, not one from the G-buffer's normals
//               (their screen derivatives cross silhouettes and follow normal maps)
// Not stored (README "G-buffer"): uv, tangent frame, geometric normal, object position.
layout(location = 0) out vec4 many_lights_g0;
layout(location = 1) out vec4 many_lights_g1;
layout(location = 2) out vec4 many_lights_g2;
layout(location = 3) out vec4 many_lights_g3;
layout(location = 4) out float many_lights_g4;
uniform int many_lights_material;

void main() {
    SlSurface s = sl_surface_from_varyings();
#ifdef SL_MAT_HAS_ALPHA_CUTOFF
    if (sl_coverage(s) < sl_mat_alpha_cutoff) discard;
#endif
    sl_run_surface_hooks(s);
    many_lights_g0 = vec4(s.position, float(many_lights_material + 1));
    many_lights_g1 = vec4(s.normal, s.ao);
    many_lights_g2 = vec4(s.base_color, s.alpha);
    many_lights_g3 = vec4(s.specular, s.opacity, s.lod_bias, s.metallic);
    many_lights_g4 = sl_normal_footprint;
}
