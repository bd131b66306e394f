// Forward material vertex stage. The composer places the generated sl_run_vertex_hooks()
// before this file.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;
layout(location = 3) in vec2 a_uv;
#ifdef SL_MAT_USES_UV1 // a texture of the material reads the second UV set (glTF texCoord 1)
layout(location = 4) in vec2 a_uv1;
out vec2 v_uv1;
#endif
#ifdef SL_MAT_USES_VERTEX_COLOR // a coloured mesh uses the material (glTF COLOR_0; others read white)
layout(location = 6) in vec4 a_color;
out vec4 v_color;
#endif

out vec3 v_world_pos;
out vec3 v_normal;
out vec4 v_tangent;
out vec2 v_uv;
out vec3 v_object_pos; // rest-pose object-space position (SlSurface.object_position)

uniform int sl_uv_space; // texture-space passes rasterise at uv*2-1

#ifdef SL_MOTION_VECTORS
// "motion" (pass.h): this frame's and the previous frame's clip position, both unjittered; the
// previous one with the VERTEX hooks evaluated at the previous frame's time (forward.c).
uniform mat4 sl_unjittered_view_proj, sl_prev_view_proj, sl_prev_model;
out vec4 v_clip_now, v_clip_prev;
layout(location = 5) in vec3 a_prev_position; // last frame's: a deformed mesh's moved (deform.c)
#endif

void main() {
    SlVertex v = SlVertex(a_position, a_normal, a_tangent, a_uv);
#ifdef SL_MOTION_VECTORS
    SlVertex prev = v;
    prev.position = a_prev_position;
    sl_hook_time = sl_prev_time;
    sl_run_vertex_hooks(prev);
    sl_hook_time = sl_motion_time_now();
#endif
    sl_run_vertex_hooks(v);
    vec4 world = sl_model * vec4(v.position, 1.0);
    v_world_pos = world.xyz;
    v_normal = sl_normal_matrix * v.normal;
    v_tangent = vec4(mat3(sl_model) * v.tangent.xyz, v.tangent.w);
    v_uv = v.uv;
#ifdef SL_MAT_USES_UV1
    v_uv1 = a_uv1;
#endif
#ifdef SL_MAT_USES_VERTEX_COLOR
    v_color = a_color;
#endif
    v_object_pos = a_position;
    gl_Position = sl_uv_space != 0 ? vec4(v.uv * 2.0 - 1.0, 0.0, 1.0) : sl_view_proj * world;
#ifdef SL_MOTION_VECTORS
    v_clip_now = sl_unjittered_view_proj * world;
    v_clip_prev = sl_prev_view_proj * (sl_prev_model * vec4(prev.position, 1.0));
#endif
}
