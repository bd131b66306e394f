// Forward material fragment stage. The composer places the generated functions
// sl_base_color(), sl_run_surface_hooks() and sl_shade_surface() before this file. A plugin's
// main (draw_scene `fragment`, ABI 1.7) follows it with SL_CUSTOM_MAIN defined; a full-screen
// material pass (SL_FULLSCREEN_MATERIAL) has no varyings: it builds its surface itself.
#ifndef SL_FULLSCREEN_MATERIAL
in vec3 v_world_pos;
in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec3 v_object_pos;
#ifdef SL_MAT_USES_UV1
in vec2 v_uv1;
#endif
#endif

#ifndef SL_CUSTOM_MAIN
layout(location = 0) out vec4 o_color;
#endif
#ifdef SL_MOTION_VECTORS
in vec4 v_clip_now, v_clip_prev;
layout(location = 1) out vec2 o_motion; // "motion": UV now minus UV in the previous frame
#endif
#ifdef SL_NORMAL_TARGET
layout(location = SL_NORMAL_LOCATION) out vec4 o_normal; // "normal" (pass.h, ABI 1.13)
#endif

// What "normal" holds (pass.h, ABI 1.13): the shading normal after the surface hooks in view space
// (unit, on the viewer's side of the surface), and in w the GGX α the surface hooks left (1 where
// none sets it). The forward pass and the depth pre-pass (prepass.frag) write the same.
vec4 sl_normal_target(SlSurface s) { return vec4(normalize(mat3(sl_view) * s.normal), s.alpha); }

// The pixel's footprint of the normal n (common.glsl, ABI 1.23) and its change to the pixel's
// centre (ABI 1.28), from its screen derivatives: call in uniform control flow, before any discard.
// The jitter moved the image by sl_jitter pixels, so the fragment samples the surface sl_jitter
// pixels short of its pixel's centre.
void sl_set_normal_footprint(vec3 n) {
    vec3 dx = dFdx(n), dy = dFdy(n);
    sl_normal_footprint = length(cross(dx, dy)) / SL_PI;
    sl_normal_to_centre = sl_jitter.x * dx + sl_jitter.y * dy;
}

#ifndef SL_FULLSCREEN_MATERIAL
SlSurface sl_surface_from_varyings() {
    SlSurface s;
    s.position = v_world_pos;
    s.view = normalize(sl_camera_pos - v_world_pos);
    vec3 g = cross(dFdx(v_world_pos), dFdy(v_world_pos));
    float glen = length(g);
    vec3 n = v_normal;
    float nlen = length(n);
    // Degenerate interpolated normals (zero-area triangles, bad meshes) fall back to the
    // geometric normal, then to the view direction, so shading never sees NaN.
    n = nlen > 1e-12 ? n / nlen : (glen > 1e-20 ? g / glen : s.view);
    if (!gl_FrontFacing && sl_uv_space == 0) n = -n;
    sl_set_normal_footprint(n);
    s.normal = n;
    s.geometric_normal = glen > 1e-20 ? g / glen : n;
    if (dot(s.geometric_normal, n) < 0.0) s.geometric_normal = -s.geometric_normal;
    vec3 t = v_tangent.xyz - n * dot(n, v_tangent.xyz);
    float tlen = length(t);
    if (tlen < 1e-8) { // no usable tangent: any vector orthogonal to n
        t = abs(n.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n);
        tlen = length(t);
    }
    s.tangent = t / tlen;
    s.bitangent = cross(n, s.tangent) * (v_tangent.w < 0.0 ? -1.0 : 1.0);
    s.uv = v_uv;
#ifdef SL_MAT_USES_UV1
    s.uv1 = v_uv1;
#else
    s.uv1 = v_uv;
#endif
    s.metallic = 0.0;
    s.base_color = sl_base_color(s);
    s.alpha = 1.0;
    s.specular = 1.0;
    s.ao = 1.0;
    s.opacity = 1.0;
    s.lod_bias = 0.0;
    s.object_position = v_object_pos;
    s.emission_weight = vec3(1.0);
    return s;
}
#endif

#if (defined(SL_ALPHA_BLENDED) || defined(SL_SCENE_BEHIND)) && !defined(SL_CUSTOM_MAIN) && !defined(SL_FULLSCREEN_MATERIAL)
// glTF alphaMode BLEND, drawn by the core's forward-blend pass over the opaque image with no depth
// attachment: the fragment tests the opaque depth itself, which holds sl_blend_ssaa² samples per
// pixel (core.ssaa), and weighs its coverage by the share of them it is in front of (the
// blended surface is shaded once per pixel; the opaque edges behind keep their supersampling).
// sl_blend_ssaa is 0 in other passes (a plugin's draw_scene): the fragment is then written opaque
// (alpha 1) under that pass's own depth test, as before blending existed (sss keeps chart coverage
// in its targets' alpha). The forward-behind pass (SL_SCENE_BEHIND, ABI 1.17) draws its opaque
// materials over the captured scene the same way.
uniform sampler2D sl_blend_depth;
uniform int sl_blend_ssaa;
float sl_blend_visible() {
    // do-whiles (called with k >= 1): llvmpipe ran a for loop's body once more after the last
    // pass, every lane masked, at full cost (4 fetches for 1 without supersampling)
    int k = max(sl_blend_ssaa, 1), front = 0, j = 0;
    ivec2 p = ivec2(gl_FragCoord.xy) * k;
    do {
        int i = 0;
        do front += gl_FragCoord.z < texelFetch(sl_blend_depth, p + ivec2(i, j), 0).r ? 1 : 0;
        while (++i < k);
    } while (++j < k);
    return float(front) / float(k * k);
}
#endif

#ifndef SL_CUSTOM_MAIN
void main() {
    SlSurface s = sl_surface_from_varyings();
#ifdef SL_MAT_HAS_ALPHA_CUTOFF
    if (sl_coverage(s) < sl_mat_alpha_cutoff) discard; // glTF alphaMode MASK
#endif
    float alpha = 1.0;
#ifdef SL_ALPHA_BLENDED
    // glTF alphaMode BLEND: the pass blends alpha·c + (1 − alpha)·behind (alpha kept in the target)
    if (sl_blend_ssaa > 0) {
        alpha = clamp(sl_coverage(s), 0.0, 1.0) * sl_blend_visible();
        if (alpha <= 0.0) discard;
    }
#elif defined(SL_SCENE_BEHIND)
    // drawn by forward-behind over the opaque image: covering the share of depth samples it is in front of
    if (sl_blend_ssaa > 0) {
        alpha = sl_blend_visible();
        if (alpha <= 0.0) discard;
    }
#endif
    sl_run_surface_hooks(s);
    // Radiance beyond what the colour target holds (65504 in RGBA16F) would become Inf there:
    // clamp to it (SL_MAX_RADIANCE, scene.h). An explicit comparison, not min(): NaN compares
    // false and stays NaN, so a shading bug is not painted white (the stability tests look for it).
    vec3 c = sl_shade_surface(s);
    o_color = vec4(mix(c, vec3(SL_MAX_RADIANCE), greaterThan(c, vec3(SL_MAX_RADIANCE))), alpha);
#ifdef SL_MOTION_VECTORS
    o_motion = 0.5 * (v_clip_now.xy / v_clip_now.w - v_clip_prev.xy / v_clip_prev.w);
#endif
#ifdef SL_NORMAL_TARGET
    o_normal = sl_normal_target(s);
#endif
}
#endif
