// bounce: a reflective shadow map (Dachsbacher & Stamminger 2005), composed into each material's
// program (draw_scene `fragment`, ABI 1.7) and drawn from a directional light, orthographic. Per
// texel, the light its surface sends back:
//   o_flux      rgb  diffuse albedo × the light's irradiance at normal incidence, where the surface
//                    faces the light (its flux over the texel's area across the light), w its luminance
//   o_position  xyz  world position × w, w
//   o_normal    xyz  shading normal × w, w |position|² (the spread of a level's positions)
// so the texture's mip levels average them into virtual point lights: flux, and position and
// normal weighted by flux (a texel that sends nothing back does not move them).
layout(location = 0) out vec4 o_flux;
layout(location = 1) out vec4 o_position;
layout(location = 2) out vec4 o_normal;
uniform vec3 bounce_light_dir; // where the light travels (world, unit)
uniform vec3 bounce_light_E;   // its colour × irradiance

void main() {
    SlSurface s = sl_surface_from_varyings();
#ifdef SL_MAT_HAS_ALPHA_CUTOFF
    if (sl_coverage(s) < sl_mat_alpha_cutoff) discard;
#endif
    sl_run_surface_hooks(s);
    bool lit = dot(s.geometric_normal, -bounce_light_dir) > 0.0;
    vec3 flux = lit ? sl_model_lobes(s).diffuse * bounce_light_E : vec3(0.0);
    flux = max(flux, vec3(0.0));
    float w = dot(flux, vec3(0.2126, 0.7152, 0.0722));
    o_flux = vec4(flux, w);
    o_position = vec4(s.position * w, w);
    o_normal = vec4(s.normal * w, dot(s.position, s.position) * w);
}
