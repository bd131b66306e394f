// SURFACE hook of the ssao example: the surface's ambient occlusion times the visibility the pass
// computed for the pixel it covers. s.ao is read by the ambient and environment terms only (the
// SDK's contract: sl_surface.ao), so direct light is untouched.
uniform sampler2D ssao_visibility; // the pass's "ssao.ao", on the plugin's reserved unit

void ssao_occlude(inout SlSurface s) {
    vec4 c = sl_view_proj * vec4(s.position, 1.0); // where the surface is on screen, in [0, 1]
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    s.ao *= texture(ssao_visibility, uv).r;
}
