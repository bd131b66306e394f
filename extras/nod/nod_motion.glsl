// nod: the deformation, its normal/tangent transform (pure functions of the rest-pose position
// and the time, so tests evaluate them directly). World space of the rest pose throughout.
//   d = p − pivot, h = d·u (u = normalised nod_region), w = smoothstep(0, blend, h) (step at 0),
//   θ(t) = radians(amplitude)·sin(2π f t), a = θ·w, k = normalised axis,
//   p' = p + (R(a) − I) d  (Rodrigues; the increment is exactly 0 when a = 0, so t = 0 is the
//   rest pose bit for bit).
// Jacobian: J = R(a) + (∂R/∂a d) ⊗ ∇a = R(a) (I + v' uᵀ), v' = θ w'(h) (k × d) (∂R/∂a = R K).
// Normals by J^{-T} ∝ R(a)(I − u v'ᵀ/(1 + u·v')), tangents by J (Sherman–Morrison).

vec3 nod_axis_unit() { float l = length(nod_axis); return l > 1e-8 ? nod_axis / l : vec3(1.0, 0.0, 0.0); }
vec3 nod_region_unit() { float l = length(nod_region); return l > 1e-8 ? nod_region / l : vec3(0.0, 1.0, 0.0); }

// the animation's time: the viewer's free-running sl_time, or a held pose (nod.pose_time >= 0)
float nod_time() { return nod_pose_time >= 0.0 ? nod_pose_time : sl_time; }

float nod_theta(float t) { return radians(nod_amplitude) * sin(2.0 * SL_PI * nod_frequency * t); }

// weight w(h) and its derivative dw/dh
vec2 nod_weight(float h) {
    if (nod_blend <= 0.0) return vec2(h >= 0.0 ? 1.0 : 0.0, 0.0);
    float x = clamp(h / nod_blend, 0.0, 1.0);
    return vec2(x * x * (3.0 - 2.0 * x), 6.0 * x * (1.0 - x) / nod_blend);
}

// (R(a) − I) x for unit axis k
vec3 nod_rotate_delta(vec3 x, vec3 k, float a) {
    float c = cos(a), s = sin(a);
    return x * (c - 1.0) + cross(k, x) * s + k * (dot(k, x) * (1.0 - c));
}
vec3 nod_rotate(vec3 x, vec3 k, float a) { return x + nod_rotate_delta(x, k, a); }

// Mirror (nod.mirror ≠ 0): points on the negative side of the plane through the origin with
// normal m are reflected (S = I − 2mmᵀ), moved, and reflected back, so the motion repeats
// mirrored (the other ear). S is its own inverse and keeps normals' transform (S J S)⁻ᵀ = S J⁻ᵀ S.
bool nod_mirrored(vec3 p) { return dot(nod_mirror, nod_mirror) > 1e-12 && dot(p, nod_mirror) < 0.0; }
vec3 nod_reflect(vec3 x) { vec3 m = normalize(nod_mirror); return x - 2.0 * dot(x, m) * m; }

vec3 nod_displace(vec3 p, float t) {
    bool mir = nod_mirrored(p);
    vec3 q = mir ? nod_reflect(p) : p;
    vec3 d = q - nod_pivot;
    float a = nod_theta(t) * nod_weight(dot(d, nod_region_unit())).x;
    vec3 delta = nod_rotate_delta(d, nod_axis_unit(), a);
    return p + (mir ? nod_reflect(delta) : delta);
}

// normal (xyz) of the deformed surface at rest position p with rest normal n; method per NOD_NORMALS
vec3 nod_normal_unmirrored(vec3 p, vec3 n, float t) {
    vec3 d = p - nod_pivot, k = nod_axis_unit(), u = nod_region_unit();
    float th = nod_theta(t);
    vec2 w = nod_weight(dot(d, u));
#if NOD_NORMALS == NOD_NORMALS_REST
    return n;
#elif NOD_NORMALS == NOD_NORMALS_RIGID
    return nod_rotate(n, k, th * w.x);
#else
    vec3 v = th * w.y * cross(k, d);
    float den = max(1.0 + dot(u, v), 1e-4); // ≤ 0 only if the band folds over (huge angle, thin band)
    return nod_rotate(n - u * (dot(v, n) / den), k, th * w.x);
#endif
}

vec3 nod_tangent_unmirrored(vec3 p, vec3 tg, float t) {
    vec3 d = p - nod_pivot, k = nod_axis_unit(), u = nod_region_unit();
    float th = nod_theta(t);
    vec2 w = nod_weight(dot(d, u));
#if NOD_NORMALS == NOD_NORMALS_REST
    return tg;
#elif NOD_NORMALS == NOD_NORMALS_RIGID
    return nod_rotate(tg, k, th * w.x);
#else
    return nod_rotate(tg + th * w.y * cross(k, d) * dot(u, tg), k, th * w.x);
#endif
}

vec3 nod_normal(vec3 p, vec3 n, float t) {
    if (!nod_mirrored(p)) return nod_normal_unmirrored(p, n, t);
    return nod_reflect(nod_normal_unmirrored(nod_reflect(p), nod_reflect(n), t));
}
vec3 nod_tangent(vec3 p, vec3 tg, float t) {
    if (!nod_mirrored(p)) return nod_tangent_unmirrored(p, tg, t);
    return nod_reflect(nod_tangent_unmirrored(nod_reflect(p), nod_reflect(tg), t));
}
