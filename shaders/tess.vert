// Vertex stage of displaced materials (DISPLACEMENT hooks, sdk shader.h ABI 1.7). The composer
// places the generated sl_run_vertex_hooks() before this file; the vertex goes on, in object
// space after the VERTEX hooks, to the tessellation stages (tess.tesc, tess.tese), which do what
// forward.vert does for undisplaced materials.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;
layout(location = 3) in vec2 a_uv;

out vec3 tc_position;
out vec3 tc_normal;
out vec4 tc_tangent;
out vec2 tc_uv;
out vec3 tc_object_pos; // rest pose (SlSurface.object_position)
#ifdef SL_MAT_USES_VERTEX_COLOR
layout(location = 6) in vec4 a_color;
out vec4 tc_color;
#endif
#ifdef SL_MAT_USES_UV1 // as forward.vert: a texture of the material reads the second UV set
layout(location = 4) in vec2 a_uv1;
out vec2 tc_uv1;
#endif
#ifdef SL_MOTION_VECTORS
out vec3 tc_prev_position; // with the VERTEX hooks at the previous frame's time
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
    tc_prev_position = prev.position;
#endif
    sl_run_vertex_hooks(v);
    tc_position = v.position;
    tc_normal = v.normal;
    tc_tangent = v.tangent;
    tc_uv = v.uv;
    tc_object_pos = a_position;
#ifdef SL_MAT_USES_VERTEX_COLOR
    tc_color = a_color;
#endif
#ifdef SL_MAT_USES_UV1
    tc_uv1 = a_uv1;
#endif
}
