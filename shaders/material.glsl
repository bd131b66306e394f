// 1 in texture-space passes (draw_scene uv_space): the mesh is rasterised at uv*2-1, so facing
// follows the UV layout (unmirrored UVs are front-facing there), not the surface or the view.
uniform int sl_uv_space;
// The core's material inputs: base_color (linear RGB) and base_color_map (sRGB texture).
// Textures are read at sl_uv_<key>(s) (generated per material: the slot's UV set and transform).
// A map without an explicit base_color is used as is (factor 1, as in glTF). Times the vertex
// colour (glTF 2.0 COLOR_0, linear RGBA: baseColorFactor × baseColorTexture × COLOR_0) in the
// programs of materials a coloured mesh uses (SL_MAT_USES_VERTEX_COLOR, forward.c), for every
// shading model (they read s.base_color); a mesh without colours drawn by one reads white.
#ifdef SL_MAT_USES_VERTEX_COLOR
in vec4 v_color;
#endif
vec3 sl_base_color(SlSurface s) {
#if defined(SL_MAT_HAS_BASE_COLOR_MAP) && defined(SL_MAT_HAS_BASE_COLOR)
    vec3 c = sl_mat_base_color * texture(sl_mat_base_color_map, sl_uv_base_color_map(s)).rgb;
#elif defined(SL_MAT_HAS_BASE_COLOR_MAP)
    vec3 c = texture(sl_mat_base_color_map, sl_uv_base_color_map(s)).rgb;
#else
    vec3 c = sl_mat_base_color;
#endif
#ifdef SL_MAT_USES_VERTEX_COLOR
    c *= v_color.rgb;
#endif
    return c;
}

// glTF 2.0 emission: emissiveFactor × emissiveTexture × emissive_strength, added to the shaded
// radiance (forward.c calls it only for materials carrying "emissive"; glTF's factor defaults to
// 0, so a texture alone emits nothing), times what the model's layers over it leave of it
// (s.emission_weight, ABI 1.20: a clear coat dims the emission below it by its Fresnel).
#ifdef SL_MAT_HAS_EMISSIVE
vec3 sl_emission(SlSurface s) {
    vec3 e = sl_mat_emissive * sl_mat_emissive_strength;
#ifdef SL_MAT_HAS_EMISSIVE_MAP
    e *= texture(sl_mat_emissive_map, sl_uv_emissive_map(s)).rgb;
#endif
    return e * s.emission_weight;
}
#endif

// glTF 2.0 alphaMode MASK (materials carrying "alpha_cutoff") and BLEND (alpha_blend): the
// coverage the cut-off tests and the blend weighs by, opacity (baseColorFactor.a) times the base
// colour texture's alpha (and the vertex colour's).
#if defined(SL_MAT_ALPHA_BLEND) && SL_MAT_ALPHA_BLEND
#define SL_ALPHA_BLENDED 1
#endif
#if defined(SL_MAT_HAS_ALPHA_CUTOFF) || defined(SL_ALPHA_BLENDED)
float sl_coverage(SlSurface s) {
    float a = sl_mat_opacity;
#ifdef SL_MAT_HAS_BASE_COLOR_MAP
    a *= texture(sl_mat_base_color_map, sl_uv_base_color_map(s)).a;
#endif
#ifdef SL_MAT_USES_VERTEX_COLOR
    a *= v_color.a; // COLOR_0's alpha (VEC3: 1)
#endif
    return a;
}
#endif

// Before ABI 1.7 these took the UV (s.uv): kept for code written then (UV set 0, untransformed
// slots only; the SlSurface forms honour texCoord and KHR_texture_transform).
vec3 sl_base_color(vec2 uv) {
    SlSurface s;
    s.uv = uv;
    s.uv1 = uv;
    return sl_base_color(s);
}
#if defined(SL_MAT_HAS_ALPHA_CUTOFF) || defined(SL_ALPHA_BLENDED)
float sl_coverage(vec2 uv) {
    SlSurface s;
    s.uv = uv;
    s.uv1 = uv;
    return sl_coverage(s);
}
#endif
