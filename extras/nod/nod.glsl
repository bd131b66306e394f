// nod: VERTEX hook, run only on meshes of nodes tagged "nod" (nod.c). The motion is defined in
// the scene's world space of the rest pose (nod_motion.glsl), shared by every mesh under the
// tagged node (a skull, ears and a nose each have their own object space); the result goes back
// to the mesh's object space with sl_model's inverse (transpose(sl_normal_matrix)).
#include "nod_motion.glsl"

void nod_vertex(inout SlVertex v) {
    vec3 pw = (sl_model * vec4(v.position, 1.0)).xyz;
    vec3 u = nod_region_unit();
    float t = nod_time();
    float th = nod_theta(t);
    vec2 w = nod_weight(dot((nod_mirrored(pw) ? nod_reflect(pw) : pw) - nod_pivot, u));
    if (th * w.x == 0.0 && th * w.y == 0.0) return; // at rest (t = 0, below the region): untouched, bit for bit
    mat3 M = mat3(sl_model), Minv = transpose(sl_normal_matrix);
    v.position += Minv * (nod_displace(pw, t) - pw);
    v.normal = transpose(M) * nod_normal(pw, sl_normal_matrix * v.normal, t);
    v.tangent.xyz = Minv * nod_tangent(pw, M * v.tangent.xyz, t);
}
