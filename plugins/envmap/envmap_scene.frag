// envmap-reflections: the opaque scene as the forward pass shades it, without screen-space
// reflections of its own (SL_CUSTOM_MAIN leaves them out of envmap_shading.glsl), and for each
// pixel the lookup direction and GGX alpha of its smoothest lobe, for envmap_reflections.frag to
// trace (reflections=screen). Blended and see-through materials are left out: a reflected ray
// passes through them to what is behind.
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_lobe; // lookup direction (world; 0: none), alpha

void main() {
#if defined(SL_ALPHA_BLENDED) || defined(SL_SCENE_BEHIND)
    discard;
#else
    SlSurface s = sl_surface_from_varyings();
#ifdef SL_MAT_HAS_ALPHA_CUTOFF
    if (sl_coverage(s) < sl_mat_alpha_cutoff) discard;
#endif
    sl_run_surface_hooks(s);
    vec3 c = sl_shade_surface(s);
    o_color = vec4(mix(c, vec3(SL_MAX_RADIANCE), greaterThan(c, vec3(SL_MAX_RADIANCE))), 1.0);
    o_lobe = vec4(0.0, 0.0, 0.0, 2.0);
    SlLobes L = sl_model_lobes(s);
    if (dot(s.normal, s.view) <= 0.0 || (L.flags & SL_LOBES_MODEL_AT_DOMINANT_LIGHT) != 0) return;
    float alpha = 2.0;
    for (int k = 0; k < L.count && k < SL_MAX_LOBES; ++k)
        if (L.lobe[k].weight > 0.0) alpha = min(alpha, max(L.lobe[k].alpha, GGX_MIN_ALPHA));
    if (alpha < 2.0)
        o_lobe = vec4(envmap_lookup_dir(s.normal, reflect(-s.view, s.normal), alpha), alpha);
#endif
}
