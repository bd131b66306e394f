// envmap GLSL library: the lat-long and cube-face conventions, low-discrepancy sequences and
// the GGX / cosine sampling every envmap program shares (the prefilter passes, the forward
// chunks, the background). Pure functions: no uniforms, so tests evaluate them directly.
// C twin: envmap_core.h / cube.c (the tests compare the two).

const float ENVMAP_PI = 3.14159265358979323846;
#ifdef ENVMAP_PROBE_UNIT // tests only: a cube sampler on a given unit
layout(binding = ENVMAP_PROBE_UNIT) uniform samplerCube envmap_probe;
#endif
const float ENVMAP_HALF_MAX = 65504.0;

// View distance from NDC z through the inverse projection's z and w rows, k = (−inv[10], −inv[14],
// inv[11], inv[15]) (perspective and orthographic alike; reflections.c, depth_lin).
float envmap_view_distance(vec4 k, float ndc_z) { return (k.x * ndc_z + k.y) / (k.z * ndc_z + k.w); }

// Lat-long, the orientation of Blender and three.js: d = (−sinθ cosφ, cosθ, −sinθ sinφ),
// φ = atan2(−z, −x), u = φ/2π wrapped to [0,1) (three.js: atan(z, x)/2π + ½), v = θ/π (v = 0 up).
// Seen from inside, u grows to the right: u = 0 faces −X, ¼ faces −Z, ½ faces +X, ¾ faces +Z.
vec3 envmap_latlong_dir(vec2 uv) {
    float phi = 2.0 * ENVMAP_PI * uv.x, theta = ENVMAP_PI * uv.y;
    return vec3(-sin(theta) * cos(phi), cos(theta), -sin(theta) * sin(phi));
}
vec2 envmap_dir_latlong(vec3 d) {
    d = normalize(d);
    // atan(0, 0) is undefined in GLSL: the poles get u = 0 (any u is the same point there)
    float phi = (abs(d.x) + abs(d.z) > 0.0) ? atan(-d.z, -d.x) : 0.0;
    float u = phi * (0.5 / ENVMAP_PI);
    u = u - floor(u);
    return vec2(u, acos(clamp(d.y, -1.0, 1.0)) / ENVMAP_PI);
}

// Cube face f (GL order +X −X +Y −Y +Z −Z), face coordinates st in [0,1] → direction
// (GL 4.5 table 8.19 inverted; not normalised).
vec3 envmap_cube_dir(int face, vec2 st) {
    vec2 ab = 2.0 * st - 1.0;
    float a = ab.x, b = ab.y;
    if (face == 0) return vec3(1.0, -b, -a);
    if (face == 1) return vec3(-1.0, -b, a);
    if (face == 2) return vec3(a, 1.0, b);
    if (face == 3) return vec3(a, -1.0, -b);
    if (face == 4) return vec3(a, -b, 1.0);
    return vec3(-a, -b, -1.0);
}

// Solid angle of a face texel centred at face coordinates ab in [-1,1]² of width 2/size
// (differential form; the callers renormalise sums to 4π).
float envmap_texel_solid_angle(vec2 ab, float size) {
    float r2 = 1.0 + dot(ab, ab);
    return (4.0 / (size * size)) / (r2 * sqrt(r2));
}

// Exact solid angle of texel xy (integer corner) of a size² face.
float envmap_area_element(float x, float y) { return atan(x * y, sqrt(x * x + y * y + 1.0)); }
float envmap_texel_solid_angle_exact(vec2 xy, float size) {
    vec2 a = 2.0 * xy / size - 1.0, b = 2.0 * (xy + 1.0) / size - 1.0;
    return envmap_area_element(a.x, a.y) - envmap_area_element(a.x, b.y) - envmap_area_element(b.x, a.y) +
           envmap_area_element(b.x, b.y);
}

// R_y(−yaw) as a mat3 is built on the CPU (envmap_rot); this is the C twin's em_rotate_y.
vec3 envmap_rotate_y(vec3 d, float degrees) {
    float a = radians(degrees), c = cos(a), s = sin(a);
    return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

// Hammersley point i of n (radical inverse in base 2).
vec2 envmap_hammersley(uint i, uint n) {
    uint b = i;
    b = (b << 16u) | (b >> 16u);
    b = ((b & 0x55555555u) << 1u) | ((b & 0xAAAAAAAAu) >> 1u);
    b = ((b & 0x33333333u) << 2u) | ((b & 0xCCCCCCCCu) >> 2u);
    b = ((b & 0x0F0F0F0Fu) << 4u) | ((b & 0xF0F0F0F0u) >> 4u);
    b = ((b & 0x00FF00FFu) << 8u) | ((b & 0xFF00FF00u) >> 8u);
    return vec2((float(i) + 0.5) / float(n), float(b) * 2.3283064365386963e-10);
}
// Roberts' R2 sequence: an open-ended low-discrepancy sequence (references accumulate it
// over frames without knowing the final count).
vec2 envmap_r2(uint i) {
    return fract(vec2(0.5) + float(i) * vec2(0.7548776662466927, 0.5698402909980532));
}
// Per-pixel Cranley–Patterson rotation.
vec2 envmap_hash2(uvec2 p) {
    uvec3 v = uvec3(p, p.x ^ p.y) * uvec3(1664525u, 1013904223u, 2654435761u);
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z; v.y += v.z * v.x;
    return vec2(v.xy) * 2.3283064365386963e-10;
}

// An orthonormal frame around unit n (Duff et al. 2017: continuous except at n.z = −1 → sign).
void envmap_frame(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// GGX half-vector distributed as D(h)(n·h), local frame (z = n).
vec3 envmap_sample_ggx_D(vec2 xi, float alpha) {
    float a2 = alpha * alpha;
    float cos2 = (1.0 - xi.y) / (1.0 + (a2 - 1.0) * xi.y);
    float c = sqrt(max(cos2, 0.0)), s = sqrt(max(1.0 - cos2, 0.0));
    float phi = 2.0 * ENVMAP_PI * xi.x;
    return vec3(s * cos(phi), s * sin(phi), c);
}
// GGX visible normals (Heitz 2018), v in the local frame (z = n, v.z > 0). The PDF of h is
// G1(v) max(0, v·h) D(h) / v.z, so f·cos/pdf of a reflection = F · G(v,l) / G1(v).
vec3 envmap_sample_vndf(vec3 v, float alpha, vec2 xi) {
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 1e-12 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(xi.x), phi = 2.0 * ENVMAP_PI * xi.y;
    float p1 = r * cos(phi), p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
}
// The standard Smith G1 of GGX measured from the normal (the VNDF's own): used to divide out
// the sampling density, whatever G the BRDF itself uses.
float envmap_smith_g1(float n_dot_x, float alpha) {
    float c2 = max(n_dot_x * n_dot_x, 1e-12);
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * (1.0 - c2) / c2));
}
// Cosine-distributed direction, local frame.
vec3 envmap_sample_cosine(vec2 xi) {
    float r = sqrt(xi.x), phi = 2.0 * ENVMAP_PI * xi.y;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - xi.x)));
}

// Replaces NaN/Inf by 0 / the half limit and clamps to what RGBA16F stores.
vec3 envmap_finite(vec3 c) {
    bvec3 bad = bvec3(isnan(c.x), isnan(c.y), isnan(c.z));
    c = mix(c, vec3(0.0), bad);
    return clamp(c, vec3(0.0), vec3(ENVMAP_HALF_MAX));
}
