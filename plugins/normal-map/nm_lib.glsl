// normal-map: pure functions (no uniforms, no textures), shared by the surface hook, the
// debug views and the GLSL unit tests (tests/test_normal_map.c evaluates them and compares
// with C). The bake tool (tools/nm_tools.c) implements the same steps in C. The view guard of
// a mapped normal is the core's (sl_view_guard): the clear coat's normal texture takes it too.
#include "sl:normal_guard.glsl"

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

// IEC 61966-2-1 sRGB decoding: debug views output decode(x) so that the display pass's sRGB
// encoding shows x itself (the PNG holds the texel values, as the map file does).
vec3 nm_srgb_decode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
