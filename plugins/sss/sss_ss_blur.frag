// sss screen-space separable subsurface scattering (Jimenez, Zsolnai, Jarabo, Freude, Auzinger,
// Wu, von der Pahlen, Wimmer, Gutierrez 2015, "Separable Subsurface Scattering", CGF 34(6)):
// one of the two 1D convolutions of the diffuse buffer. The 1D kernel is the skin profile
// integrated across the blur direction, Σᵢ wᵢ g(vᵢ, x) — exactly the profile's response to a
// line, so a lit stripe spreads as in the full 2D diffusion.
//
// Depth-aware: a tap at screen offset x (mm, in the plane of the centre pixel) whose surface lies
// Δ mm deeper or nearer is 3D distance √(x² + Δ²) away, and each Gaussian is separable in 3D:
// g(x)·exp(−Δ²/2v). The weight lost this way (and the weight of taps off the skin, coverage 0)
// goes to the centre pixel, as in Jimenez et al.'s "follow surface" lerp: energy is kept and
// nothing leaks across depth discontinuities.
#include "sss_lib.glsl"

uniform sampler2D sss_src;      // premultiplied diffuse, coverage in alpha
uniform sampler2D sss_depth;    // window depth of the diffuse prepass
uniform sampler2D sss_kernel;   // texel (tap, gaussian): (RGB weight, offset mm)
uniform float sss_variance[6];  // mm², per Gaussian
uniform int sss_taps;
uniform int sss_gaussians;
uniform vec2 sss_dir;           // (1, 0) horizontal, (0, 1) vertical
uniform vec2 sss_px_per_unit;   // pixels per world unit at distance 1: (P00·W/2, P11·H/2)
uniform float sss_mm;           // world length of 1 mm of the profile (the material's sss_radius)
uniform vec2 sss_depth_params;  // (P[2][2], P[3][2]) of the camera projection
uniform float sss_max_px;       // widest offset, pixels
uniform int sss_follow_surface; // 0: ignore depth (a plain blur, for comparison)

layout(location = 0) out vec4 o_blur;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(sss_src, 0);
    vec4 c0 = texelFetch(sss_src, p, 0);
    if (c0.a <= 0.0) { o_blur = vec4(0.0); return; }
    vec3 centre = c0.rgb / c0.a;
    float d0 = sss_linear_depth(texelFetch(sss_depth, p, 0).r, sss_depth_params.x, sss_depth_params.y);
    float px_per_mm = dot(sss_px_per_unit, sss_dir) * sss_mm / max(d0, 1e-20);
    vec3 sum = vec3(0.0), wsum = vec3(0.0);
    // do-whiles (taps >= 3, gaussians >= 1): llvmpipe ran a for loop's body once more after the
    // last pass, every lane masked, at full cost (18 × 7 kernel terms for 17 × 6)
    int t = 0;
    do {
        float x_mm = texelFetch(sss_kernel, ivec2(t, 0), 0).a;
        float off = clamp(x_mm * px_per_mm, -sss_max_px, sss_max_px);
        ivec2 q = p + ivec2(round(off * sss_dir));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec4 c = texelFetch(sss_src, q, 0);
        if (c.a <= 0.0) continue;
        float d = sss_linear_depth(texelFetch(sss_depth, q, 0).r, sss_depth_params.x, sss_depth_params.y);
        float dz = sss_follow_surface != 0 ? (d - d0) / sss_mm : 0.0;
        vec3 w = vec3(0.0);
        int g = 0;
        do w += texelFetch(sss_kernel, ivec2(t, g), 0).rgb * exp(-dz * dz / (2.0 * sss_variance[g]));
        while (++g < sss_gaussians);
        sum += w * (c.rgb / c.a);
        wsum += w;
    } while (++t < sss_taps);
    vec3 result = sum + max(vec3(1.0) - wsum, vec3(0.0)) * centre;
    o_blur = vec4(result * c0.a, c0.a);
}
