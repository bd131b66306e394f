// Tessellation control stage of displaced materials (sdk shader.h, DISPLACEMENT, ABI 1.7). The
// composer places the plugins' chunks and the generated sl_tess_edge_level() and
// sl_run_displacement() before this file.
layout(vertices = 3) out;

const float SL_TESS_MAX_LEVEL = 48.0;

in vec3 tc_position[];
in vec3 tc_normal[];
in vec4 tc_tangent[];
in vec2 tc_uv[];
in vec3 tc_object_pos[];
out vec3 te_position[];
out vec3 te_normal[];
out vec4 te_tangent[];
out vec2 te_uv[];
out vec3 te_object_pos[];
#ifdef SL_MAT_USES_VERTEX_COLOR
in vec4 tc_color[];
out vec4 te_color[];
#endif
#ifdef SL_MAT_USES_UV1
in vec2 tc_uv1[];
out vec2 te_uv1[];
#endif
#ifdef SL_MOTION_VECTORS
in vec3 tc_prev_position[];
out vec3 te_prev_position[];
#endif

// One edge's level from its two endpoints only, in a canonical order (lexicographic in world
// space): the two patches sharing an edge compute it from the same values in the same order and
// agree bit for bit, whatever the winding of each — no T-junctions, no cracks.
float sl_tess_shared_edge_level(vec3 a, vec3 b) {
    bool swap = a.x > b.x || (a.x == b.x && (a.y > b.y || (a.y == b.y && a.z > b.z)));
    float level = swap ? sl_tess_edge_level(b, a) : sl_tess_edge_level(a, b);
    // NaN (a bad chunk) and Inf end as the nearest bound, never as a discarded patch. At most 48:
    // llvmpipe (Mesa 22.3), which reports gl_MaxTessGenLevel = 64, drew a displaced plane of 32
    // patches at level 64 with holes and torn triangles (32 and 48 clean); the core also splits
    // tessellated draws into 16 patches each (scene_gpu.c), which cured the same tearing at level 32.
    return clamp(level == level ? level : 1.0, 1.0, min(float(gl_MaxTessGenLevel), SL_TESS_MAX_LEVEL));
}

void main() {
    te_position[gl_InvocationID] = tc_position[gl_InvocationID];
    te_normal[gl_InvocationID] = tc_normal[gl_InvocationID];
    te_tangent[gl_InvocationID] = tc_tangent[gl_InvocationID];
    te_uv[gl_InvocationID] = tc_uv[gl_InvocationID];
    te_object_pos[gl_InvocationID] = tc_object_pos[gl_InvocationID];
#ifdef SL_MAT_USES_VERTEX_COLOR
    te_color[gl_InvocationID] = tc_color[gl_InvocationID];
#endif
#ifdef SL_MAT_USES_UV1
    te_uv1[gl_InvocationID] = tc_uv1[gl_InvocationID];
#endif
#ifdef SL_MOTION_VECTORS
    te_prev_position[gl_InvocationID] = tc_prev_position[gl_InvocationID];
#endif
    if (gl_InvocationID == 0) {
        vec3 w0 = (sl_model * vec4(tc_position[0], 1.0)).xyz;
        vec3 w1 = (sl_model * vec4(tc_position[1], 1.0)).xyz;
        vec3 w2 = (sl_model * vec4(tc_position[2], 1.0)).xyz;
        // outer level i belongs to the edge opposite vertex i (where gl_TessCoord[i] = 0)
        float e0 = sl_tess_shared_edge_level(w1, w2);
        float e1 = sl_tess_shared_edge_level(w2, w0);
        float e2 = sl_tess_shared_edge_level(w0, w1);
        gl_TessLevelOuter[0] = e0;
        gl_TessLevelOuter[1] = e1;
        gl_TessLevelOuter[2] = e2;
        gl_TessLevelInner[0] = max(e0, max(e1, e2));
    }
}
