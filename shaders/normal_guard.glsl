// The view guard of a perturbed shading normal (normal maps, a clear coat's normal texture):
// pure functions of their arguments, part of the SDK (ABI 1.29), so every plugin that perturbs a
// normal guards it the same way. normal-map's tests (plugins/normal-map/tests/test_normal_map.c)
// evaluate them against the C derivation in tests/view_guard.h.

// Smallest n·v a guarded normal has (see sl_face_viewer).
const float SL_MIN_NDOTV = 0.02;

// Guard for normals facing away from the viewer (n·v < ε with ε = SL_MIN_NDOTV): bends n
// toward v, n' = normalize(n + (ε − n·v)·v). Then n'·v = ε/√(1 − (n·v)² + ε²) ≥ ε/√(1 + ε²),
// so every BRDF sees a visible normal (no NaN from 1/(n·v), no black holes), |n + …|² ≥ ε² > 0
// so the normalisation is safe even for n = −v (result: v), and normals with n·v ≥ ε are
// returned unchanged (bit for bit).
vec3 sl_face_viewer(vec3 n, vec3 v) {
    float d = dot(n, v);
    if (d >= SL_MIN_NDOTV) return n;
    return normalize(n + (SL_MIN_NDOTV - d) * v);
}

// Guard for mapped normals whose mirror direction of v falls below the surface (Blender's
// Cycles does the same in its Normal Map node, the reference the project is checked against):
// n is tilted back toward the interpolated normal g, keeping its azimuth about g, until the
// mirror direction r = 2(n·v)n − v rises t = min(0.9·(v·g), 0.01) above the surface (Cycles'
// threshold).
// With n' = a·x + b·g (x: n's direction in the surface plane, a² + b² = 1, a, b ≥ 0),
// r·g = t reads 2ab·vx = t + vz − 2b²·vz; squared, a quadratic in b² whose roots, written so
// that nothing cancels in float near grazing views (p = vx² + vz², s = |vx|·√(p − t²)), are
//   a² = (vz − t)² / (2(p − vz·t + s))   (n' near g), the solution when vx ≤ 0 (n leans away
//       from the viewer: the left side ≤ 0, and this root makes the right side t − vz + 2a²vz ≤ 0);
//   b² = (vz + t)² / (2(vx² + vz(vz + t) + s))   (n' near the surface), when vx > 0.
// Continuous in n (at r·g = t the root is n itself), so the shading has no edge where normals
// start to bend; n'·v > 0 (r' and v both lie above the surface, so r' ≠ −v). Normals whose
// reflection is valid are returned unchanged (bit for bit), and so is n when v lies below g's
// surface (a smooth mesh's silhouette: there is no surface to reflect above; sl_face_viewer
// still guards). A normal below the surface (n·g < 0: an object-space map on the wrong side)
// would mirror v like −n, validly while facing away, so it is first laid onto the surface
// (continuous at n·g = 0).
vec3 sl_valid_reflection(vec3 n, vec3 v, vec3 g) {
    float vz = dot(v, g), t = min(0.9 * vz, 0.01);
    if (vz <= 0.0) return n;
    float ng = dot(n, g);
    if (ng >= 0.0 && dot(2.0 * dot(n, v) * n - v, g) >= t) return n;
    vec3 x = n - ng * g;
    float xl = length(x);
    if (xl < 1e-6) return g; // n = −g (n = g reflects validly): no azimuth to keep
    x /= xl;
    float vx = dot(v, x), p = vx * vx + vz * vz, sq = abs(vx) * sqrt(max(p - t * t, 0.0));
    bool away = vx <= 0.0;
    float e = away ? vz - t : vz + t, q = e * e / (2.0 * (away ? p - vz * t + sq : vx * vx + vz * (vz + t) + sq));
    vec2 ab = away ? vec2(sqrt(q), sqrt(max(1.0 - q, 0.0))) : vec2(sqrt(max(1.0 - q, 0.0)), sqrt(q));
    return normalize(ab.x * x + ab.y * g);
}

// The view guard of every mapped normal: a valid reflection first (the convention), then
// n·v ≥ ε (what every BRDF needs, at views within ~1° of the horizon).
vec3 sl_view_guard(vec3 n, vec3 v, vec3 g) { return sl_face_viewer(sl_valid_reflection(n, v, g), v); }
