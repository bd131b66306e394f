// normal-map: pure functions (no uniforms, no textures), shared by the surface hook, the
// debug views and the GLSL unit tests (tests/test_normal_map.c evaluates them and compares
// with C). The bake tool (tools/nm_tools.c) implements the same steps in C.

// Smallest n·v the surface hook lets a mapped normal have (see nm_face_viewer).
const float NM_MIN_NDOTV = 0.02;

// Image "up" (the direction a +Y normal map's green channel encodes) on the surface, in units
// of the core's bitangent s.bitangent = w·cross(n, t). The core's convention (scenes/README.md):
// v = 0 is the image's TOP row (textures upload top row first) and the bitangent points toward
// decreasing v (core/scene/tangents.c: −dP/dv; primitives; flip_v meshes regenerate frames),
// i.e. up in the image: +1. tests/test_normal_map.c ("orientation") checks this against the
// core's own texture sampling; if the core's convention changes, that test fails and this
// constant (and NM_IMAGE_UP_SIGN in tools/nm_tools.h) must change with it.
const float NM_IMAGE_UP_SIGN = 1.0;

// Texel (0..1 per channel) → vector (−1..1). No normalisation here: a grey texel decodes to 0.
vec3 nm_decode(vec3 texel) { return texel * 2.0 - 1.0; }

// Tangent-space strength as glTF's normalTexture.scale: xy scaled by k, z kept (clamped to the
// upper hemisphere, a tangent-space normal below the surface is a broken texel), unit result.
// Degenerate input (a grey texel, or k = 0 with z = 0) gives the unperturbed (0, 0, 1).
vec3 nm_tangent_scaled(vec3 n, float k) {
    vec3 m = vec3(n.xy * k, max(n.z, 0.0));
    float l2 = dot(m, m);
    return l2 > 1e-12 ? m * inversesqrt(l2) : vec3(0.0, 0.0, 1.0);
}

// Tangent space → world: T (increasing u), U (image up), N: an orthonormal frame.
vec3 nm_from_tangent_space(vec3 nt, vec3 T, vec3 U, vec3 N) {
    vec3 m = nt.x * T + nt.y * U + nt.z * N;
    float l2 = dot(m, m);
    return l2 > 1e-12 ? m * inversesqrt(l2) : N;
}

// Object-space normal (decoded) → world through the normal matrix; `front` false flips it for
// back faces (the core's N is already flipped there). Strength k ∈ [0, 1] blends from the
// interpolated normal N (k = 0) to the map (k = 1); a zero blend falls back to N.
vec3 nm_from_object_space(vec3 no, mat3 normal_matrix, bool front, vec3 N, float k) {
    vec3 w = normal_matrix * no;
    float l2 = dot(w, w);
    w = l2 > 1e-20 ? w * inversesqrt(l2) : N;
    if (!front) w = -w;
    if (k >= 1.0) return w;
    vec3 m = mix(N, w, clamp(k, 0.0, 1.0));
    l2 = dot(m, m);
    return l2 > 1e-12 ? m * inversesqrt(l2) : N;
}

// Guard for normals facing away from the viewer (n·v < ε with ε = NM_MIN_NDOTV): bends n
// toward v, n' = normalize(n + (ε − n·v)·v). Then n'·v = ε/√(1 − (n·v)² + ε²) ≥ ε/√(1 + ε²),
// so every BRDF sees a visible normal (no NaN from 1/(n·v), no black holes), |n + …|² ≥ ε² > 0
// so the normalisation is safe even for n = −v (result: v), and normals with n·v ≥ ε are
// returned unchanged (bit for bit).
vec3 nm_face_viewer(vec3 n, vec3 v) {
    float d = dot(n, v);
    if (d >= NM_MIN_NDOTV) return n;
    return normalize(n + (NM_MIN_NDOTV - d) * v);
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
// Continuous in n (at r·g = t the
// root is n itself), so the shading has no edge where normals start to bend; n'·v > 0 (r' and
// v both lie above the surface, so r' ≠ −v). Normals whose reflection is valid are returned
// unchanged (bit for bit), and so is n when v lies below g's surface (a smooth mesh's
// silhouette: there is no surface to reflect above; nm_face_viewer still guards). A normal
// below the surface (n·g < 0: an object-space map on the wrong side) would mirror v like −n,
// validly while facing away, so it is first laid onto the surface (continuous at n·g = 0).
vec3 nm_valid_reflection(vec3 n, vec3 v, vec3 g) {
    float vz = dot(v, g), t = min(0.9 * vz, 0.01);
    if (vz <= 0.0) return n;
    float ng = dot(n, g);
    if (ng >= 0.0 && dot(2.0 * dot(n, v) * n - v, g) >= t) return n;
    vec3 x = n - ng * g;
    float xl = length(x);
    if (xl < 1e-6) return g; // n = g reflects validly, so n = −g: no azimuth to keep
    x /= xl;
    float vx = dot(v, x), p = vx * vx + vz * vz, sq = abs(vx) * sqrt(max(p - t * t, 0.0));
    bool away = vx <= 0.0;
    float e = away ? vz - t : vz + t, q = e * e / (2.0 * (away ? p - vz * t + sq : vx * vx + vz * (vz + t) + sq));
    vec2 ab = away ? vec2(sqrt(q), sqrt(max(1.0 - q, 0.0))) : vec2(sqrt(max(1.0 - q, 0.0)), sqrt(q));
    return normalize(ab.x * x + ab.y * g);
}

// The view guard of every mapped normal: a valid reflection first (the convention), then
// n·v ≥ ε (what every BRDF needs, at views within ~1° of the horizon).
vec3 nm_view_guard(vec3 n, vec3 v, vec3 g) { return nm_face_viewer(nm_valid_reflection(n, v, g), v); }

// IEC 61966-2-1 sRGB decoding: debug views output decode(x) so that the display pass's sRGB
// encoding shows x itself (the PNG holds the texel values, as the map file does).
vec3 nm_srgb_decode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
