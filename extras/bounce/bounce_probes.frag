// bounce: the irradiance probes (one full-screen triangle over an atlas of the grid's slices side
// by side, a texel per probe). Each probe sums every virtual point light (bounce.c builds the list from the
// reflective shadow maps),
//   e_j = Φ_j max(cos θ_j, 0) / (π d² + A_j)   light j's irradiance at normal incidence: a
//        Lambertian disk of flux Φ_j and area A_j seen at distance d on its axis, finite as d → 0,
// from ω_j, the unit direction from the probe to light j, into the order-2 spherical harmonics of
// irradiance (Ramamoorthi & Hanrahan 2001): E(n) = Σ_k C_k P_k(n) with the polynomials
//   P = 1, y, z, x, xy, yz, 3z² − 1, xz, x² − y²   and   C_k = Â_l K_k² Σ_j e_j P_k(ω_j),
// Â_l K_k² = 1/4 (l = 0), 1/2 (l = 1), 15/16, 15/16, 5/64, 15/16, 15/64 (l = 2): the clamped
// cosine's 1/4 + t/2 + 5/16 (3t² − 1)/2 for a single light. Stored as 27 floats (C_0.rgb …
// C_8.rgb), four per target; bounce.glsl evaluates them. Visibility between the lights and the
// probes is not traced.
layout(std430, binding = 8) readonly buffer BounceVpls {
    vec4 bounce_vpl[]; // per light: position, area A_j; normal, 0; flux Φ_j, 0
};
uniform int bounce_vpl_count;
uniform vec3 bounce_box_min, bounce_box_max;
uniform vec3 bounce_grid; // probes per axis
layout(location = 0) out vec4 o_probe[7];

const float BOUNCE_PI = 3.14159265358979;

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    int gx = int(bounce_grid.x);
    vec3 x = mix(bounce_box_min, bounce_box_max, (vec3(t.x % gx, t.y, t.x / gx) + 0.5) / bounce_grid);
    vec3 s0 = vec3(0.0), s1 = vec3(0.0), s2 = vec3(0.0), s3 = vec3(0.0), s4 = vec3(0.0), s5 = vec3(0.0);
    vec3 s6 = vec3(0.0), s7 = vec3(0.0), s8 = vec3(0.0);
    for (int j = 0; j < bounce_vpl_count; j++) {
        vec4 pa = bounce_vpl[3 * j];
        vec3 v = pa.xyz - x; // probe → light
        float d2 = dot(v, v);
        vec3 w = v * inversesqrt(max(d2, 1e-20));
        float cos_j = -dot(bounce_vpl[3 * j + 1].xyz, w);
        if (cos_j <= 0.0) continue;
        vec3 e = bounce_vpl[3 * j + 2].rgb * (cos_j / (BOUNCE_PI * d2 + pa.w));
        s0 += e, s1 += e * w.y, s2 += e * w.z, s3 += e * w.x;
        s4 += e * (w.x * w.y), s5 += e * (w.y * w.z), s6 += e * (3.0 * w.z * w.z - 1.0);
        s7 += e * (w.x * w.z), s8 += e * (w.x * w.x - w.y * w.y);
    }
    // the targets are half floats: a sum beyond their range is held at their largest value, finite
    const float big = 65504.0;
    s0 = min(s0, big), s1 = clamp(s1, -big, big), s2 = clamp(s2, -big, big), s3 = clamp(s3, -big, big);
    s4 = clamp(s4, -big, big), s5 = clamp(s5, -big, big), s6 = clamp(s6, -big, big), s7 = clamp(s7, -big, big);
    s8 = clamp(s8, -big, big);
    vec3 c0 = 0.25 * s0, c1 = 0.5 * s1, c2 = 0.5 * s2, c3 = 0.5 * s3;
    vec3 c4 = 0.9375 * s4, c5 = 0.9375 * s5, c6 = 0.078125 * s6, c7 = 0.9375 * s7, c8 = 0.234375 * s8;
    o_probe[0] = vec4(c0, c1.x), o_probe[1] = vec4(c1.yz, c2.xy), o_probe[2] = vec4(c2.z, c3);
    o_probe[3] = vec4(c4, c5.x), o_probe[4] = vec4(c5.yz, c6.xy), o_probe[5] = vec4(c6.z, c7);
    o_probe[6] = vec4(c8, 0.0);
}
