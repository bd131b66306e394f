// Tessellation evaluation stage of displaced materials (sdk shader.h, DISPLACEMENT, ABI 1.7):
// interpolates the patch's vertex, moves it along its normal by sl_run_displacement() and writes
// what forward.vert writes for undisplaced materials, so forward.frag and depth.frag are unchanged.
layout(triangles, fractional_odd_spacing, ccw) in;

in vec3 te_position[];
in vec3 te_normal[];
in vec4 te_tangent[];
in vec2 te_uv[];
in vec3 te_object_pos[];

out vec3 v_world_pos;
out vec3 v_normal;
out vec4 v_tangent;
out vec2 v_uv;
out vec3 v_object_pos;
#ifdef SL_MAT_USES_VERTEX_COLOR
in vec4 te_color[];
out vec4 v_color;
#endif
#ifdef SL_MAT_USES_UV1
in vec2 te_uv1[];
out vec2 v_uv1;
#endif

uniform int sl_uv_space; // texture-space passes rasterise at uv*2-1

#ifdef SL_MOTION_VECTORS
in vec3 te_prev_position[];
uniform mat4 sl_unjittered_view_proj, sl_prev_view_proj, sl_prev_model;
out vec4 v_clip_now, v_clip_prev;
#endif

// The patch's vertex at barycentric b (b may leave the triangle slightly: finite differences).
// `precise`: a point on a shared edge is computed from the same two corners by both patches.
SlVertex sl_tess_vertex(vec3 b) {
    SlVertex v;
    precise vec3 p = b.x * te_position[0] + b.y * te_position[1] + b.z * te_position[2];
    v.position = p;
    vec3 n = b.x * te_normal[0] + b.y * te_normal[1] + b.z * te_normal[2];
    float len = length(n);
    v.normal = len > 1e-12 ? n / len : vec3(0.0);
    v.tangent = b.x * te_tangent[0] + b.y * te_tangent[1] + b.z * te_tangent[2];
    v.tangent.w = v.tangent.w < 0.0 ? -1.0 : 1.0;
    v.uv = b.x * te_uv[0] + b.y * te_uv[1] + b.z * te_uv[2];
    return v;
}

void main() {
    vec3 b = gl_TessCoord;
    SlVertex v = sl_tess_vertex(b);
    float h = sl_run_displacement(v);
    h = h == h ? h : 0.0; // a NaN height leaves the vertex where it was
    precise vec3 p = v.position + h * v.normal;
    vec3 n = v.normal;
#ifdef SL_TESS_NORMALS
    // The displaced surface's normal, normalize(n - grad h) with grad h the surface gradient of h
    // (Mikkelsen 2020, "Surface gradient based bump mapping", eq. 2-4; the h·dn term of a curved
    // base is left out). Directional derivatives of h along the patch's two edges by forward
    // differences (a step of 1/1024 of the edge), solved for the gradient in the triangle's plane.
    const float d = 1.0 / 1024.0;
    float ha = sl_run_displacement(sl_tess_vertex(b + d * vec3(-1.0, 1.0, 0.0)));
    float hb = sl_run_displacement(sl_tess_vertex(b + d * vec3(-1.0, 0.0, 1.0)));
    vec3 e1 = te_position[1] - te_position[0], e2 = te_position[2] - te_position[0];
    float ga = (ha - h) / d, gb = (hb - h) / d; // = dot(grad h, e1), dot(grad h, e2)
    float a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
    float det = a11 * a22 - a12 * a12;
    if (det > 1e-20 * a11 * a22 && ga == ga && gb == gb && n != vec3(0.0)) {
        vec3 g = ((a22 * ga - a12 * gb) * e1 + (a11 * gb - a12 * ga) * e2) / det;
        g -= n * dot(g, n);
        n = normalize(n - g);
    }
#endif
    vec4 world = sl_model * vec4(p, 1.0);
    v_world_pos = world.xyz;
    v_normal = sl_normal_matrix * n;
    v_tangent = vec4(mat3(sl_model) * v.tangent.xyz, v.tangent.w);
    v_uv = v.uv;
    v_object_pos = b.x * te_object_pos[0] + b.y * te_object_pos[1] + b.z * te_object_pos[2];
#ifdef SL_MAT_USES_VERTEX_COLOR
    v_color = b.x * te_color[0] + b.y * te_color[1] + b.z * te_color[2];
#endif
#ifdef SL_MAT_USES_UV1
    v_uv1 = b.x * te_uv1[0] + b.y * te_uv1[1] + b.z * te_uv1[2];
#endif
    gl_Position = sl_uv_space != 0 ? vec4(v.uv * 2.0 - 1.0, 0.0, 1.0) : sl_view_proj * world;
#ifdef SL_MOTION_VECTORS
    vec3 prev = b.x * te_prev_position[0] + b.y * te_prev_position[1] + b.z * te_prev_position[2] + h * v.normal;
    v_clip_now = sl_unjittered_view_proj * world;
    v_clip_prev = sl_prev_view_proj * (sl_prev_model * vec4(prev, 1.0));
#endif
}
