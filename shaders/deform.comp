// Morph targets and skins (glTF 2.0 §3.7.2.2, §3.7.3) for one mesh, one invocation per vertex
// (core/render/deform.c): the rest shape plus the weighted target displacements, then the
// weighted sum of the joint matrices, written into the vertex buffers every draw reads. See
// sl_mesh_deform in core/scene/scene.h for the formulas.
layout(local_size_x = 64) in;

// per vertex: position (3), normal (3), tangent (4)
layout(std430, binding = 0) readonly buffer SlDeformRest { float sl_rest[]; };
// per target, per vertex: position, normal and tangent displacements (3 each)
layout(std430, binding = 1) readonly buffer SlDeformTargets { float sl_targets[]; };
// per vertex sl_influences joint indices, then per vertex sl_influences weights (float bits)
layout(std430, binding = 2) readonly buffer SlDeformInfluences { uint sl_influence[]; };
// sl_joint_count matrices (16 floats, column-major), then sl_target_count weights
layout(std430, binding = 3) readonly buffer SlDeformFrame { float sl_frame[]; };
layout(std430, binding = 4) writeonly buffer SlDeformPositions { float sl_out_position[]; };
layout(std430, binding = 5) writeonly buffer SlDeformNormals { float sl_out_normal[]; };
layout(std430, binding = 6) writeonly buffer SlDeformTangents { float sl_out_tangent[]; };

uniform int sl_vertex_count, sl_target_count, sl_influences, sl_joint_count;

vec3 sl_rest3(uint v, uint o) { return vec3(sl_rest[10u * v + o], sl_rest[10u * v + o + 1u], sl_rest[10u * v + o + 2u]); }

vec3 sl_target3(uint t, uint v, uint o) {
    uint i = (t * uint(sl_vertex_count) + v) * 9u + o;
    return vec3(sl_targets[i], sl_targets[i + 1u], sl_targets[i + 2u]);
}

mat4 sl_joint_matrix(uint j) {
    uint i = 16u * j;
    return mat4(sl_frame[i], sl_frame[i + 1u], sl_frame[i + 2u], sl_frame[i + 3u],
                sl_frame[i + 4u], sl_frame[i + 5u], sl_frame[i + 6u], sl_frame[i + 7u],
                sl_frame[i + 8u], sl_frame[i + 9u], sl_frame[i + 10u], sl_frame[i + 11u],
                sl_frame[i + 12u], sl_frame[i + 13u], sl_frame[i + 14u], sl_frame[i + 15u]);
}

vec3 sl_unit_or(vec3 v, vec3 fallback) {
    float l = length(v);
    return l > 1e-20 ? v / l : fallback;
}

void main() {
    uint v = gl_GlobalInvocationID.x;
    if (v >= uint(sl_vertex_count)) return;
    vec3 p = sl_rest3(v, 0u), n = sl_rest3(v, 3u);
    vec4 t = vec4(sl_rest3(v, 6u), sl_rest[10u * v + 9u]);
    vec3 n0 = n, t0 = t.xyz;
    for (int k = 0; k < sl_target_count; k++) {
        float w = sl_frame[16 * sl_joint_count + k];
        if (w == 0.0) continue;
        p += w * sl_target3(uint(k), v, 0u);
        n += w * sl_target3(uint(k), v, 3u);
        t.xyz += w * sl_target3(uint(k), v, 6u);
    }
    n = sl_unit_or(n, n0);
    t.xyz = sl_unit_or(t.xyz, t0);
    if (sl_influences > 0) {
        mat4 m = mat4(0.0);
        uint base = v * uint(sl_influences), weights = uint(sl_vertex_count * sl_influences);
        for (int k = 0; k < sl_influences; k++) {
            float w = uintBitsToFloat(sl_influence[weights + base + uint(k)]);
            if (w != 0.0) m += w * sl_joint_matrix(sl_influence[base + uint(k)]);
        }
        mat3 a = mat3(m);
        // normals by the cofactor matrix (det · inverse transpose), turned with a mirroring matrix
        mat3 cof = mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1]));
        float det = dot(a[0], cross(a[1], a[2]));
        p = (m * vec4(p, 1.0)).xyz;
        n = sl_unit_or((det < 0.0 ? -1.0 : 1.0) * (cof * n), n);
        t.xyz = sl_unit_or(a * t.xyz, t.xyz);
    }
    for (uint c = 0u; c < 3u; c++) {
        sl_out_position[3u * v + c] = p[c];
        sl_out_normal[3u * v + c] = n[c];
        sl_out_tangent[4u * v + c] = t[c];
    }
    sl_out_tangent[4u * v + 3u] = t.w;
}
