// sss texture-space diffusion (d'Eon & Luebke 2007, GPU Gems 3 ch. 14): one 1D Gaussian blur of
// the UV-space irradiance along u or v. The chain blurᵢ = blur(blurᵢ₋₁, vᵢ − vᵢ₋₁) builds each
// Gaussian of the profile from the previous one; the v pass also writes the running sum
// Σ_{j≤i} wⱼ·blurⱼ (second attachment; the previous sum is read from sss_sum_in).
//
// Texels carry coverage in alpha (1 where a surface was rasterised, 0 elsewhere) and rgb
// premultiplied by it. Near a UV chart's edge (a seam, the atlas border) a tap can fall partly
// or wholly outside the chart:
//  - partly (one of the two texels its linear filtering reads is uncovered): the missing texel
//    is extrapolated linearly from the two covered ones before it (2·c₁ − c₂);
//  - wholly: the tap is replaced by its mirror tap reflected through the centre, 2·c₀ − c₊.
// Both are exact for a lighting gradient running into the seam, so the two sides of a seam are
// blurred without bias and meet (a renormalised one-sided blur shifts each side by about the
// gradient times the blur width, in opposite directions: a visible step). Extrapolations are
// clamped at 0. A pair with neither tap on the chart drops out and the weights are
// renormalised, so a uniformly lit chart stays uniform up to its edges.
//
// Interior texels (SSS_TS_INTERIOR, a second program): where every texel the taps can read is
// covered (the plugin classifies texels per direction from the coverage and the stretch map and
// selects them with the depth test, sss.c: ts_classify), the taps are the hardware's linear
// filtering alone, the branches above never taken — the same sums without their cost (llvmpipe
// runs both sides of a branch). Uncovered texels take this path too: ×c0.a makes them 0.
//
// SSS_LOOP_NOTE: the tap loops are do-whiles. llvmpipe runs a loop's body under a mask of the
// lanes still in it, and a for loop's test at the top ran the body once more after the last tap
// with every lane masked, at full cost (4 runs for 3 tap pairs).
//
// Stretch correction: sss_stretch_map holds the surface length of one texel along u and v in
// millimetres of the profile (the "sss-stretch" pass), so σ in texels = σ_mm / (mm per texel).
#include "sss_lib.glsl"

uniform sampler2D sss_src;
uniform sampler2D sss_stretch_map;
uniform vec2 sss_dir;          // (1, 0): along u; (0, 1): along v
uniform float sss_sigma_mm;    // standard deviation of this step
uniform int sss_taps;
uniform float sss_offsets[31]; // in units of σ (sss_profile.c: sss_blur_taps)
uniform float sss_weights[31]; // sum to 1
uniform sampler2D sss_sum_in;  // v pass: the sum so far
uniform vec3 sss_acc_weight;   // this Gaussian's RGB weight in the profile (v pass)
uniform int sss_first;         // 1 for the first Gaussian: no sum so far
uniform float sss_max_texels;  // widest σ in texels (degenerate stretch near UV poles)

layout(location = 0) out vec4 o_blur;
layout(location = 1) out vec4 o_sum;

vec4 sss_texel(ivec2 q) {
    ivec2 size = textureSize(sss_src, 0);
    return any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)) ? vec4(0.0) : texelFetch(sss_src, q, 0);
}

// The source at texel p moved by t texels along sss_dir (texel centres at integers, linear in
// between), extrapolating a missing neighbour; false when neither neighbour is covered.
bool sss_tap(ivec2 p, vec2 uv, float t, out vec3 v) {
    vec4 f = texture(sss_src, uv);
    v = f.a > 0.0 ? f.rgb / f.a : vec3(0.0);
    if (f.a >= 0.999) return true; // both texels covered: the hardware's linear filtering
    ivec2 d = ivec2(sss_dir);
    float i0 = floor(t), w = t - i0;
    ivec2 q = p + int(i0) * d;
    vec4 a = sss_texel(q), b = sss_texel(q + d);
    if (a.a <= 0.0 && b.a <= 0.0) return false;
    vec3 va = a.a > 0.0 ? a.rgb / a.a : vec3(0.0), vb = b.a > 0.0 ? b.rgb / b.a : vec3(0.0);
    if (b.a <= 0.0) {
        vec4 a2 = sss_texel(q - d);
        vb = a2.a > 0.0 ? max(2.0 * va - a2.rgb / a2.a, vec3(0.0)) : va;
    } else if (a.a <= 0.0) {
        vec4 b2 = sss_texel(q + 2 * d);
        va = b2.a > 0.0 ? max(2.0 * vb - b2.rgb / b2.a, vec3(0.0)) : vb;
    }
    v = mix(va, vb, w);
    return true;
}

#ifdef SSS_TS_INTERIOR
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 size = vec2(textureSize(sss_src, 0));
    vec4 c0 = texelFetch(sss_src, p, 0);
    // uncovered texels have no stretch: any finite σ (the result is multiplied by c0.a = 0)
    float mm_per_texel = max(dot(texelFetch(sss_stretch_map, p, 0).xy, sss_dir), 1e-20);
    float sigma = min(sss_sigma_mm / mm_per_texel, sss_max_texels);
    vec2 uv = (vec2(p) + 0.5) / size;
    vec2 texel = sss_dir / size;
    int half_taps = sss_taps / 2;
    float wc = sss_weights[half_taps];
    vec3 sum = wc * c0.rgb; // covered: alpha 1
    float wsum = wc;
    int t = 1; // half_taps >= 1 (sss.ts_taps >= 3); a do-while: see SSS_LOOP_NOTE below
    do {
        float w = sss_weights[half_taps + t], o = sss_offsets[half_taps + t] * sigma;
        sum += w * (texture(sss_src, uv - o * texel).rgb + texture(sss_src, uv + o * texel).rgb);
        wsum += 2.0 * w;
    } while (++t <= half_taps);
    vec4 result = vec4(sum / wsum, 1.0) * c0.a;
#else
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 size = vec2(textureSize(sss_src, 0));
    vec4 c0 = texelFetch(sss_src, p, 0);
    float mm_per_texel = dot(texelFetch(sss_stretch_map, p, 0).xy, sss_dir);
    vec4 result = c0;
    if (c0.a > 0.0 && mm_per_texel > 0.0) {
        float sigma = min(sss_sigma_mm / mm_per_texel, sss_max_texels);
        vec2 uv = (vec2(p) + 0.5) / size;
        vec2 texel = sss_dir / size;
        vec3 centre = c0.rgb / c0.a;
        int half_taps = sss_taps / 2;
        float wc = sss_weights[half_taps];
        vec3 sum = wc * centre;
        float wsum = wc;
        int t = 1;
        do {
            float w = sss_weights[half_taps + t], o = sss_offsets[half_taps + t] * sigma;
            vec3 va, vb;
            bool ha = sss_tap(p, uv - o * texel, -o, va), hb = sss_tap(p, uv + o * texel, o, vb);
            if (!ha && !hb) continue;
            if (!ha) va = max(2.0 * centre - vb, vec3(0.0));
            if (!hb) vb = max(2.0 * centre - va, vec3(0.0));
            sum += w * (va + vb);
            wsum += 2.0 * w;
        } while (++t <= half_taps);
        result = vec4(sum / wsum, 1.0) * c0.a;
    }
#endif
    o_blur = result;
    // the sum's alpha is the coverage (from the first Gaussian on)
    vec4 before = sss_first != 0 ? vec4(0.0, 0.0, 0.0, result.a) : texelFetch(sss_sum_in, p, 0);
    o_sum = vec4(before.rgb + result.rgb * sss_acc_weight, before.a);
}
