// envmap's forward chunks: the "mirror" and "environment" shading models and the AMBIENT hook
// that lights every material from the environment. Every model is lit through the SDK's lobe
// contract (sl_model_lobes, ABI 1.14: a diffuse albedo and GGX lobes), naming none:
//   split sum   diffuse irradiance (SH or convolved cube) × the diffuse albedo + per lobe the
//               prefiltered specular chain × environment BRDF (F0·A + F90·B) × weight; a model
//               without lobes gets the contract's fallback (Lambert with base_color)
//   reference   Monte Carlo integration of the source environment with the model's own f
//               (sl_shading_model), the lobes only choosing where to sample
// envmap's own models (it may name them):
//   mirror      L(reflect(−v, n)), tinted by base_color when the material gives one
//   environment L(n), likewise
#include "envmap_common.glsl"
#include "sl:ggx_brdf.glsl"

uniform sampler2D envmap_src2d;   // the source as loaded (lat-long) …
uniform samplerCube envmap_srccube; // … or as a cube; envmap_is_cube says which
uniform bool envmap_is_cube;
uniform vec2 envmap_src_size;     // lat-long (w, h) or (face size, face size)
uniform samplerCube envmap_spec;  // prefiltered specular chain
uniform float envmap_spec_lod_max;// its last level (roughness 1)
uniform samplerCube envmap_irr;   // convolved irradiance (E/π)
uniform vec3 envmap_sh[9];        // SH irradiance (E/π), coefficients × Â_l/π × basis norm
uniform sampler2D envmap_lut;     // environment BRDF (A, B), envmap_lut_size² (the parameter's uniform)
uniform mat3 envmap_rot;          // world → map: R_y(−yaw)
uniform float envmap_scale;       // the scene environment's intensity
#if ENVMAP_SPECULAR == ENVMAP_SPECULAR_FIS || ENVMAP_SPECULAR == ENVMAP_SPECULAR_HYBRID
uniform samplerCube envmap_base;  // the base cube with its solid-angle-weighted mips (specular=fis reads it)
uniform float envmap_base_size;   // its face size
#endif

// A scene whose environment is one constant radiance (SL_ENVIRONMENT_CONSTANT, ABI 1.27: no map,
// a colour) has these programs: every lookup below returns that radiance, sl_ambient_irradiance/π
// (colour × intensity, the core's uniform), so the prefiltered chain, the SH and the lobe table are
// neither read nor made, and the split sum's specular is each lobe's albedo × it — what every
// specular mode gives in a uniform environment (its furnace; a normal-mapped lobe is faded at the
// horizon along its dominant direction, as specular=dominant); envmap_render checks it against the
// general path over a "constant:" map (README, "What it does").
#ifdef SL_ENVIRONMENT_CONSTANT
#define ENVMAP_CONSTANT_RADIANCE (sl_ambient_irradiance * SL_INV_PI)
#endif

// Radiance arriving from world direction d.
vec3 envmap_source(vec3 d, float lod) {
#ifdef SL_ENVIRONMENT_CONSTANT
    return ENVMAP_CONSTANT_RADIANCE;
#endif
    vec3 m = envmap_rot * d;
    vec3 c = envmap_is_cube ? textureLod(envmap_srccube, m, lod).rgb
                            : textureLod(envmap_src2d, envmap_dir_latlong(m), lod).rgb;
    return c * envmap_scale;
}
// Mip level for a lookup `angle` radians wide (a lat-long's u seam has no usable derivatives,
// so levels are chosen from the direction's own screen-space change).
float envmap_source_lod(float angle) {
    float texel = envmap_is_cube ? 0.5 * ENVMAP_PI / envmap_src_size.x : ENVMAP_PI / envmap_src_size.y;
    return max(0.0, log2(max(angle, 1e-8) / texel));
}

vec3 envmap_diffuse(vec3 n) { // E(n)/π: the outgoing radiance of a white Lambert surface
#ifdef SL_ENVIRONMENT_CONSTANT
    return ENVMAP_CONSTANT_RADIANCE;
#endif
    vec3 m = envmap_rot * n;
#if defined(ENVMAP_IRRADIANCE) && ENVMAP_IRRADIANCE == ENVMAP_IRRADIANCE_CONVOLVED
    vec3 e = textureLod(envmap_irr, m, 0.0).rgb;
#else
    float x = m.x, y = m.y, z = m.z;
    vec3 e = envmap_sh[0] + envmap_sh[1] * y + envmap_sh[2] * z + envmap_sh[3] * x + envmap_sh[4] * (x * y) +
             envmap_sh[5] * (y * z) + envmap_sh[6] * (3.0 * z * z - 1.0) + envmap_sh[7] * (x * z) +
             envmap_sh[8] * (x * x - y * y);
    e = max(e, vec3(0.0)); // order-2 SH rings negative opposite a strong sun: clamp
#endif
    return e * envmap_scale;
}

// The chain's level for α (em_alpha_lod's twin, <envmap/prefilter.h>): envmap_spec_map 0 =
// level m for perceptual roughness m/L (L = the last level), 1 = α halving per level from 1.
uniform int envmap_spec_map; // = the level_map parameter; 0 for a shadelab-cube chain
float envmap_spec_lod_log(float alpha) {
    float top = envmap_spec_lod_max, a1 = exp2(1.0 - top);
    return alpha >= a1 ? top + log2(alpha) : alpha / a1;
}
float envmap_spec_lod(float alpha) {
    return envmap_spec_map == 1 ? envmap_spec_lod_log(alpha) : sqrt(alpha) * envmap_spec_lod_max;
}
vec3 envmap_specular(vec3 r, float alpha) {
#ifdef SL_ENVIRONMENT_CONSTANT
    return ENVMAP_CONSTANT_RADIANCE;
#endif
    return textureLod(envmap_spec, envmap_rot * r, envmap_spec_lod(alpha)).rgb * envmap_scale;
}
// The chain of Blinn-Phong lobes (the lobe contract's shapes, ABI 1.19; envmap.c makes it only
// where a program reads it): the level for α holds the environment filtered by the n = v = r
// Blinn-Phong lobe of power p = sl_lobe_blinn_power(α). At n·v = μ the lobe, a cone about h
// reflected about the surface, is μ× narrower across the plane of incidence than along it (l moves
// 2μ× as far as h across it, 2× along it): μ× the solid angle of the n = v = r lobe. It is read
// as the isotropic lobe of that solid angle, power p/μ (read at p, the band test's error at
// gloss 0.5 was 0.164 instead of 0.107 on sqrt-map levels: phong README, "Lobes"). Its levels are always spaced by
// 2× in α (level_map=log): between the sqrt map's levels, 4× apart at low α, the trilinear blend
// of two widths gives the lobe a tail, which a tail-free Blinn-Phong lobe shows next to a sun.
uniform samplerCube envmap_spec_blinn;
vec3 envmap_specular_blinn(vec3 r, float alpha, float mu) {
#ifdef SL_ENVIRONMENT_CONSTANT
    return ENVMAP_CONSTANT_RADIANCE;
#endif
    float a = sl_lobe_blinn_alpha(sl_lobe_blinn_power(alpha) / max(mu, 0.05));
    return textureLod(envmap_spec_blinn, envmap_rot * r, envmap_spec_lod_log(a)).rgb * envmap_scale;
}

// The direction the prefiltered chain is looked up along. The split sum's n = v = r lobe sits on
// the mirror direction r; GGX's real lobe, with the G and cos factors, peaks between r and n, the
// more so the rougher (the off-specular peak). specular=dominant uses Lagarde & de Rousiers' fit
// ("Moving Frostbite to PBR", SIGGRAPH 2014 course notes, §4.9.3): lerp(n, r, s(√s + α)) with
// s = 1 − α, normalised (their "roughness" is α).
vec3 envmap_dominant_dir(vec3 n, vec3 r, float alpha) {
    float s = clamp(1.0 - alpha, 0.0, 1.0);
    return normalize(mix(n, r, s * (sqrt(s) + alpha)));
}
vec3 envmap_lookup_dir(vec3 n, vec3 r, float alpha) {
#if ENVMAP_SPECULAR == ENVMAP_SPECULAR_DOMINANT || ENVMAP_SPECULAR == ENVMAP_SPECULAR_FILTERED || \
    ENVMAP_SPECULAR == ENVMAP_SPECULAR_FITTED
    return envmap_dominant_dir(n, r, alpha);
#else
    return r;
#endif
}

// Screen-space reflections (reflections=screen; README, "Reflections of the scene"): before the
// forward pass envmap draws the opaque scene (envmap_scene.frag) and traces, once per texel of that
// image, a ray along the smoothest lobe's lookup direction (envmap_reflections.frag). Here a lobe
// smoother than envmap_refl_alpha takes the radiance the ray found where it found one — one
// bilinear read of the premultiplied (radiance × weight, weight), so texels where nothing was
// found or traced (a rough neighbour, the sky) only thin the reflection at a silhouette — fading to
// the environment alone between half of envmap_refl_alpha and it (one ray cannot stand for a wide
// lobe). One read: on llvmpipe a branch's body costs every pixel that could take it.
#if defined(ENVMAP_REFLECTIONS) && ENVMAP_REFLECTIONS == ENVMAP_REFLECTIONS_SCREEN && !defined(SL_CUSTOM_MAIN) && \
    !defined(SL_FULLSCREEN_MATERIAL)
#define ENVMAP_SCREEN_RAYS 1
uniform sampler2D envmap_refl;       // (radiance × weight, weight) per texel of the scene's image
uniform mat4 envmap_refl_view_proj;  // the view it was drawn with (no jitter)
uniform float envmap_refl_alpha;     // lobes this rough or rougher: the environment alone
#endif
// What the screen-space ray of this pixel found: (radiance × weight, weight); 0 without rays
vec4 envmap_scene_found(SlSurface s) {
#ifdef ENVMAP_SCREEN_RAYS
    vec4 c = envmap_refl_view_proj * vec4(s.position, 1.0);
    return c.w > 0.0 ? textureLod(envmap_refl, c.xy / c.w * 0.5 + 0.5, 0.0) : vec4(0.0);
#else
    return vec4(0.0);
#endif
}
// How much of a lobe of this alpha the scene found replaces (0 without rays)
float envmap_scene_weight(vec4 found, float alpha) {
#ifdef ENVMAP_SCREEN_RAYS
    return found.a * (1.0 - smoothstep(0.5 * envmap_refl_alpha, envmap_refl_alpha, alpha));
#else
    return 0.0;
#endif
}
// radiance along a lobe of this alpha: the environment's (env), or the scene's where the ray met it
vec3 envmap_with_scene(vec4 found, float alpha, vec3 env) {
    return mix(env, found.rgb / max(found.a, 1e-6), envmap_scene_weight(found, alpha));
}

// (A, B, C): texel i ↔ n·v = i/(n−1), j ↔ r = j/(n−1); C(n·v) the diffuse Fresnel weight
vec3 envmap_brdf(float mu, float alpha) {
    vec2 x = vec2(mu, sqrt(alpha));
    float n = float(envmap_lut_size);
    return texture(envmap_lut, (x * (n - 1.0) + 0.5) / n).rgb;
}

// Per-sample random numbers for the reference: an R2 sequence continued across the frames that
// are averaged (sl_sample_index, ABI 1.9: accumulated frames and a TAA still's), rotated per pixel;
// envmap.reference_seed starts another, independent sequence (noise measured across seeds).
vec2 envmap_xi(uint i, vec2 rot) {
    uint k = uint(envmap_reference_samples);
    return fract(envmap_r2(uint(sl_sample_index) * k + i) + rot);
}
vec2 envmap_reference_rotation() {
    uint seed = uint(envmap_reference_seed);
    return envmap_hash2(uvec2(gl_FragCoord.xy) + uvec2(seed * 7919u, seed * 104729u));
}

// Schlick's Fresnel between f0 and f90 (the lobe contract's F), c = l·h.
vec3 envmap_schlick(float c, vec3 f0, vec3 f90) {
    float m = clamp(1.0 - c, 0.0, 1.0), m2 = m * m;
    return f0 + (f90 - f0) * (m2 * m2 * m);
}

// Horizon occlusion for normal-mapped normals (Russell 2015, "Horizon occlusion for normal mapped
// reflections", Marmoset): a lookup direction d bent below the geometric surface (d·n_g < 0)
// would pick up light from under it; the factor fades it out, (1 + 1.3 d·n_g)² clamped. Only for
// normal-mapped materials: n_g is the flat triangle normal, and a tessellated smooth mesh's
// interpolated normals lean a degree or more off it, which would darken grazing samples.
float envmap_horizon(vec3 d, vec3 ng) {
#if defined(SL_MAT_HAS_NORMAL_MAP)
    float h = clamp(1.0 + 1.3 * dot(d, ng), 0.0, 1.0);
    return h * h;
#else
    return 1.0;
#endif
}
// The same for one sampled direction l (fis, the reference): light from under the geometric
// surface is blocked, a hard cut (a sample is one direction, not a lobe).
float envmap_above(vec3 l, vec3 ng) {
#if defined(SL_MAT_HAS_NORMAL_MAP)
    return dot(l, ng) > 0.0 ? 1.0 : 0.0;
#else
    return 1.0;
#endif
}
// Specular occlusion from the surface's ambient occlusion (an AO map or glTF occlusionTexture,
// s.ao): Lagarde & de Rousiers 2014 ("Moving Frostbite to PBR", §4.10.2), an approximation fitted
// to a cone-shaped visibility: clamp((n·v + ao)^(2^(−16α − 1)) − 1 + ao, 0, 1). 1 when ao = 1.
float envmap_specular_occlusion(float n_dot_v, float ao, float alpha) {
    return clamp(pow(max(n_dot_v + ao, 0.0), exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

#if ENVMAP_SPECULAR == ENVMAP_SPECULAR_FIS || ENVMAP_SPECULAR == ENVMAP_SPECULAR_HYBRID
// Filtered importance sampling (Křivánek & Colbert 2007, GPU Gems 3 ch. 20): envmap_fis_samples
// GGX visible-normal samples (Heitz 2018) of the real lobe for this n and v, each read from the
// base cube at the mip level whose texel solid angle matches the sample's share of the lobe,
// Ω_s = 1/(N·F·pdf(l)) with F the frames averaged into the image shown (sl_sample_count: a TAA
// still's frames × accumulated frames; 1 when nothing averages), lod = ½ log2(Ω_s/Ω_texel)
// + envmap.fis_lod_bias (K&C: +1; see the README). The weights are the BRDF's f·cos/pdf =
// F(v·h)·G(v,l)/G1(v), per channel (Schlick with f0, as the reference), whose expectation is the
// environment BRDF (F0·A + B) = `albedo`. The estimate is Monte Carlo with a control variate
// (e.g. Owen, "Monte Carlo theory, methods and examples", ch. 8.9): c = the prefiltered chain
// along the dominant direction, and
//     albedo·c + (1/N) Σ w_i (L_i − c),
// unbiased for any c (E[w] = albedo), exact in a uniform environment for any N (L_i = c), and
// with the split sum's answer as its noise-free part. Until issue 16's last round it was the
// ratio Σ w L / Σ w × albedo, which is exact in the furnace too but biased by O(1/N) in every
// frame, a bias accumulating frames does not remove: courtyard metal α = 1, N = 32 × 32 frames,
// −1.4 % on the sphere mean, N = 16 × 64 frames −4.4 % (measured against the C quadrature,
// bench/ibl_rim.c). The per-pixel sequence is rotated per pixel and continued over the averaged
// frames (sl_sample_index), so accumulating converges to the filtered integral — whose remaining
// bias (the mips' box filter) the bench charts. `beta` scales the Monte Carlo correction:
// 1 = fis, 0 = the control variate alone (= specular=dominant, no sample taken); specular=hybrid
// fades it out towards rough α (envmap_hybrid_beta). Returns the specular radiance (albedo included).
uniform float envmap_accumulated; // frames averaged into the image shown (sl_sample_count)
vec3 envmap_fis_specular(SlSurface s, float alpha, vec3 r, vec3 f0, vec3 f90, vec3 albedo, float beta) {
    vec3 n = s.normal, v = s.view;
    vec3 t, b;
    envmap_frame(n, t, b);
    vec3 vl = vec3(dot(v, t), dot(v, b), dot(v, n));
    if (vl.z <= 0.0) return vec3(0.0);
    int count = clamp(envmap_fis_samples, 1, 32);
    vec2 rot = envmap_hash2(uvec2(gl_FragCoord.xy));
    float g1v = envmap_smith_g1(vl.z, alpha);
    float texel = 4.0 * ENVMAP_PI / (6.0 * envmap_base_size * envmap_base_size);
    float lod_max = log2(envmap_base_size);
    // the control variate: the split sum's prefiltered radiance along the dominant direction
    // (Lagarde & de Rousiers 2014 §4.9.3, as specular=dominant), horizon-faded as it is there
    vec3 d = envmap_dominant_dir(n, r, alpha);
    vec3 c = textureLod(envmap_spec, envmap_rot * d, envmap_spec_lod(alpha)).rgb * envmap_horizon(d, s.geometric_normal);
    vec3 sum = vec3(0.0);
    if (beta <= 0.0) count = 0; // the split sum alone: no sample (uniform per material unless α is mapped)
    // A do-while: llvmpipe runs a loop's body under a mask of the lanes still in it, and a for
    // loop's test at the top ran it once more after the last sample, every lane masked, at full
    // cost. With count = 0 its one run (masked by i < count) adds nothing.
    int i = 0;
    do {
        vec2 xi = fract(envmap_r2(uint(sl_sample_index) * uint(count) + uint(i)) + rot);
        vec3 hl = envmap_sample_vndf(vl, alpha, xi);
        vec3 ll = 2.0 * dot(vl, hl) * hl - vl;
        if (i >= count || ll.z <= 0.0) continue; // weight 0 (G1(l) = 0): contributes 0 to the mean
        vec3 h = t * hl.x + b * hl.y + n * hl.z, l = t * ll.x + b * ll.y + n * ll.z;
        vec3 w = envmap_schlick(dot(l, h), f0, f90) * (ggx_G1(v, n, h, alpha) * ggx_G1(l, n, h, alpha) / g1v);
        // pdf(l) = G1(v) D(h) / (4 n·v) for visible-normal sampling
        float pdf = g1v * ggx_D(hl.z, alpha) / (4.0 * vl.z);
        // the estimate's samples are all frames' (the R2 points continue across an accumulated
        // render): K&C's footprint with N·frames, so accumulating also shrinks the blur
        float lod = clamp(0.5 * log2(1.0 / (float(count) * envmap_accumulated * max(pdf, 1e-20) * texel)) +
                              envmap_fis_lod_bias, 0.0, lod_max);
        // light from under the geometric surface (normal maps) is blocked (the weight stays)
        sum += w * (envmap_above(l, s.geometric_normal) * textureLod(envmap_base, envmap_rot * l, lod).rgb - c);
    } while (++i < count);
    // A frame's estimate dips below 0 where its few samples read darker than c with large
    // weights. A single frame (shown, or fed to TAA) is clamped at 0; an accumulated render is
    // not: the clamp would bias its mean upwards (band test, N = 1 × 64 frames, α = 1: +7 %),
    // and the mean of the frames is what converges to the (non-negative) integral.
    vec3 est = albedo * c + beta * sum / float(max(count, 1));
    return (envmap_accumulated > 1.0 ? est : max(est, vec3(0.0))) * envmap_scale;
}
#endif

#if ENVMAP_SPECULAR == ENVMAP_SPECULAR_FILTERED
// specular=filtered: filtered importance sampling (Křivánek & Colbert 2007, GPU Gems 3 ch. 20)
// with one sample set shared by every pixel, read from the prefiltered GGX chain, so a frame is
// a smooth function of (n, v, α): no per-pixel random pattern. The set is a Fibonacci spiral on
// the unit disk, r_i = √((i + o_x)/N), φ_i = 2π·frac(i/golden ratio + o_y) (the disk's most even
// N-point set), with the same offset o for every pixel of a frame: (½, 0) in frame 0 (every frame
// in motion, the first of a still), and in frame k of a still or an accumulated render
// (sl_sample_index) o = R2(k) − (0, ½) — a Cranley–Patterson rotation that moves every point
// within its ring and turns the spiral, so the frames' sub-lobes fall between each other's and
// the still's mean fills the lobe in (a small bright sun's highlight, one dot per sub-lobe in a
// single frame, is smoothed). Mapped
// to the pixel's real lobe by GGX visible-normal sampling (Heitz 2018), whose disk is aligned
// with the plane of incidence: the pattern turns with the view, and the lobe is stretched and cut
// by the horizon as the real one is (the split sum's n = v = r lobe is not). Each sample stands
// for Ω_s = 1/(N·pdf(l)) of the lobe (K&C) and reads the chain at the roughness whose n = v = r
// lobe covers that much, α_s = 2^bias·√(Ω_s/4π) (the lobe's peak density is 1/(4πα²)), at most
// α: N smooth sub-lobes tile the real lobe. K&C read box-filtered mips instead; a coarse mip's
// texel grid lies wherever it lies, and the sub-lobes then read whole quarter faces (a sharp band
// of the band test was off by 20–45 % that way at N = 16). Weights F(v·h)·G(v,l)/G1(v) per
// channel; the estimate is the weighted mean Σ w L / Σ w times the environment BRDF (F0·A + F90·B)
// from the LUT, so a uniform environment gives the LUT exactly for any N (the furnace).
vec3 envmap_filtered_specular(SlSurface s, float alpha, vec3 f0, vec3 f90, vec3 albedo) {
    vec3 n = s.normal, v = s.view;
    vec3 t, b;
    envmap_frame(n, t, b);
    vec3 vl = vec3(dot(v, t), dot(v, b), dot(v, n));
    if (vl.z <= 0.0) return vec3(0.0);
    int count = clamp(envmap_filtered_samples, 1, 64);
    float spread = exp2(envmap_filtered_lod_bias) / sqrt(4.0 * ENVMAP_PI * float(count));
    // Deconvolution: the sub-lobes blur the sampled lobe; at its peak a sub-lobe is α_s² =
    // 4^bias·α²/N, and a blur adds its variance to α² (as NDF filtering for shading antialiasing
    // does, Kaplanyan et al. 2016), so the set samples the narrower lobe α/√(1 + k·4^bias/N) that
    // comes out at α. k = filtered_deconvolve: 1 by that argument; the chain's sub-lobes are wider
    // than their nominal α (trilinear between levels 4× apart in α, the prefilter's lod bias), and
    // k = 3 measured best against Cycles (README, "The first frame"). 0: off. The weights follow
    // the sampled lobe; the LUT's albedo stays α's, so the furnace is exact.
    alpha /= sqrt(1.0 + envmap_filtered_deconvolve * exp2(2.0 * envmap_filtered_lod_bias) / float(count));
    float g1v = envmap_smith_g1(vl.z, alpha);
    // The visible-normal sampler lays its disk out from the view's azimuth, which turns all the
    // way round the point where v = n (the middle of a sphere): the set is turned back by that
    // azimuth, so it stays put in the surface frame (t, b) there, where the sampler's view-
    // dependent squeeze vanishes; elsewhere the pattern moves as smoothly as the view does.
    float turn = (vl.x != 0.0 || vl.y != 0.0) ? atan(vl.x, -vl.y) * (0.5 / ENVMAP_PI) : 0.0;
    vec2 shift = envmap_r2(uint(sl_sample_index)) - vec2(0.0, 0.5); // (½, 0) at frame 0
    vec3 sum = vec3(0.0), wsum = vec3(0.0);
    // What every sample shares, out of the loop: the visible-normal sampler's frame
    // (envmap_sample_vndf's first lines) and the spiral's angle, turned by the golden angle from
    // sample to sample (a rotation: no sine or cosine per sample)
    vec3 vh = normalize(vec3(alpha * vl.x, alpha * vl.y, vl.z));
    float lensq = vh.x * vh.x + vh.y * vh.y, sq = 0.5 * (1.0 + vh.z);
    vec3 t1 = lensq > 1e-12 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0), t2 = cross(vh, t1);
    float phi0 = 2.0 * ENVMAP_PI * (shift.y - turn), golden = 2.0 * ENVMAP_PI * 0.6180339887498949;
    vec2 cs = vec2(cos(phi0), sin(phi0)), step = vec2(cos(golden), sin(golden));
    int i = 0; // a do-while: see envmap_fis_specular
    do {
        float r = sqrt((float(i) + shift.x) / float(count)), p1 = r * cs.x, p2 = r * cs.y;
        cs = vec2(cs.x * step.x - cs.y * step.y, cs.y * step.x + cs.x * step.y);
        p2 = (1.0 - sq) * sqrt(max(1.0 - p1 * p1, 0.0)) + sq * p2;
        vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
        vec3 hl = normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
        float vdh = dot(vl, hl);
        vec3 ll = 2.0 * vdh * hl - vl;
        if (ll.z <= 0.0) continue; // below the horizon: weight 0
        vec3 l = t * ll.x + b * ll.y + n * ll.z;
        // F(v·h) G1(l)/G1(v)·G1(v): G1(v) divides out (a visible normal has v·h > 0), and l·h = v·h
        vec3 w = envmap_schlick(vdh, f0, f90) * envmap_smith_g1(ll.z, alpha);
        float pdf = g1v * ggx_D(hl.z, alpha) / (4.0 * vl.z);
        float sub_alpha = min(1.0, spread * inversesqrt(max(pdf, 1e-20)));
        sum += w * envmap_above(l, s.geometric_normal) *
               textureLod(envmap_spec, envmap_rot * l, envmap_spec_lod(sub_alpha)).rgb;
        wsum += w;
    } while (++i < count);
    return albedo * sum / max(wsum, vec3(1e-6)) * envmap_scale;
}
#endif

#if ENVMAP_SPECULAR == ENVMAP_SPECULAR_FITTED
uniform sampler2DArray envmap_lobe_table; // lobe_fit_table.h: (θ_v, α) cells, 2 layers
uniform vec3 envmap_lobe_grid; // its first row's α, rows per unit α, columns per radian of θ_v (lobe_fit.h)
// specular=fitted: GGX's real lobe at (n·v, α) as three lobes of the prefiltered chain, laid along
// the plane of incidence: tap k reads the chain at roughness a_k along r turned by t_k towards n,
// weighted w_k (Σ w = 1: the furnace is exact). The real lobe is narrower across the plane than
// the chain's n = v = r lobe (μ×: l moves 2μ× as far as h across it, 2× along it), leans
// towards n and is cut by the horizon; the mix is fitted to it in L2 over the sphere, offline,
// per cell of a (α, θ_v) table (lobe_fit.h, tools/lobe_fit_tool.c: α = 0.1…1 by 0.1, θ_v = 0…85°
// by 5°), read bilinearly. Below α = 0.1 the α = 0.1 row is shrunk about r by α/0.1 (a narrow
// GGX lobe keeps its shape as α scales it). Deterministic: a smooth function of (n, v, α).
vec3 envmap_fitted_specular(vec3 n, vec3 r, float mu, float alpha, vec3 ng) {
    vec2 size = vec2(textureSize(envmap_lobe_table, 0).xy); // the table's θ_v and α cells
    float shrink = min(alpha / envmap_lobe_grid.x, 1.0);
    float fa = clamp((alpha - envmap_lobe_grid.x) * envmap_lobe_grid.y, 0.0, size.y - 1.0);
    float ft = clamp(acos(clamp(mu, 0.0, 1.0)) * envmap_lobe_grid.z, 0.0, size.x - 1.0);
    vec2 uv = (vec2(ft, fa) + 0.5) / size;
    vec4 p = texture(envmap_lobe_table, vec3(uv, 0.0)), q = texture(envmap_lobe_table, vec3(uv, 1.0));
    // e: perpendicular to r, towards n, in the plane of incidence (any at r = n, where every t is 0)
    vec3 e = n - dot(n, r) * r;
    float el = length(e);
    e = el > 1e-7 ? e / el : vec3(0.0);
    vec3 t = vec3(p.x, p.w, q.z) * shrink, a = vec3(p.y, q.x, q.w) * shrink, w = vec3(p.z, q.y, 1.0 - p.z - q.y);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 3; k++) {
        vec3 d = cos(t[k]) * r + sin(t[k]) * e;
        sum += w[k] * envmap_specular(d, a[k]) * envmap_horizon(d, ng);
    }
    return sum;
}
#endif

#if ENVMAP_SPECULAR == ENVMAP_SPECULAR_HYBRID
// specular=hybrid: fis's correction at full weight up to α = hybrid_alpha − 0.25, fading linearly
// to none at hybrid_alpha (dominant alone above, where its lobe error is below fis's noise:
// bench/methods.sh). A material's α is one value unless a roughness map varies it, so the
// sample loop's branch is coherent across a draw.
float envmap_hybrid_beta(float alpha) { return clamp((envmap_hybrid_alpha - alpha) / 0.25, 0.0, 1.0); }
// The frame's share of the correction (set per frame from sl_frame.sample_index/count): when frames
// are averaged (a TAA still, an accumulated render), sample 0 — every frame in motion and one frame
// of each still — takes no sample (weight 0: the dominant lookup alone, its cost) and the other
// count − 1 frames weigh count/(count − 1), so the average is still albedo·c + the mean correction
// (unbiased); with nothing averaging, 1.
uniform float envmap_fis_weight;
#endif

// The split sum over the material's lobes (the lobe contract): per lobe the prefiltered chain
// (or fis) × the environment BRDF F0·A + F90·B × weight, and the diffuse albedo × E(n)/π. With
// diffuse_coupled (glTF 2.0 appendix B) the diffuse is weighted by 1 − F(v·h) of lobe 0 per light
// direction; over the cosine lobe that is exactly 1 − F0 − (F90 − F0)·C(μ), C from the LUT
// (envmap_lut.frag), split from the irradiance as Karis 2013 splits the specular. (1 − F(n·v))
// instead — Schlick at the view angle — goes to 0 at the rim where the true weight stays ≈ 0.93:
// dielectric spheres were 4 % too dark on average and 60 % at μ = 0.1 (measured, bench/terms.sh).
// A lobe with exact dielectric Fresnel (eta) is approximated by Schlick with its F0. Each lobe is
// integrated about its own normal (sl_lobe_normal, ABI 1.26: a clear coat's normal texture); the
// diffuse and the screen rays (reflections=screen) about the surface's.
vec3 envmap_split_sum(SlSurface s) {
    SlLobes L = sl_model_lobes(s);
    vec3 v = s.view;
    vec3 kd = L.diffuse, lit = vec3(0.0);
    vec4 found = envmap_scene_found(s);
    for (int k = 0; k < L.count && k < SL_MAX_LOBES; ++k) {
        SlLobe lobe = L.lobe[k];
        SlSurface sk = s;
        sk.normal = sl_lobe_normal(L, k, s);
        vec3 n = sk.normal, r = reflect(-v, n);
        float mu = clamp(dot(n, v), 1e-4, 1.0);
        // a (normal-mapped) normal facing away from the viewer is masked, G1(v) = 0: no specular,
        // as in the reference below
        float visible = dot(n, v) > 0.0 ? 1.0 : 0.0;
        float alpha = max(lobe.alpha, GGX_MIN_ALPHA);
        vec3 abc = envmap_brdf(mu, alpha);
        if (k == 0 && L.diffuse_coupled) kd *= 1.0 - lobe.f0 - (lobe.f90 - lobe.f0) * abc.z;
        if (!(lobe.weight > 0.0)) continue;
        vec3 albedo = lobe.f0 * abc.x + lobe.f90 * abc.y;
        vec3 spec = albedo;
        if (envmap_multiscatter) // Fdez-Agüera 2019: the energy single scattering loses, F0-tinted
            spec *= 1.0 + lobe.f0 * (1.0 / max(abc.x + abc.y, 1e-3) - 1.0);
#if defined(SL_ENVIRONMENT_CONSTANT)
        // a uniform environment: every mode's answer, the lobe's albedo × the radiance
        vec3 d = envmap_lookup_dir(n, r, alpha);
        vec3 specular = spec * ENVMAP_CONSTANT_RADIANCE * envmap_horizon(d, s.geometric_normal);
#elif ENVMAP_SPECULAR == ENVMAP_SPECULAR_FILTERED
        // the dominant lookup alone from α = filtered_alpha (1: rough lobes, where it measured
        // closer to Cycles than the samples and costs one lookup), the samples alone up to
        // filtered_alpha − 0.25, blended between; the branch is uniform per material unless a
        // roughness map varies α. The filtered lobe estimates the single-scattering specular
        // (albedo inside); multiscatter scales it as it scales the split sum's
        float beta = clamp((envmap_filtered_alpha - alpha) / 0.25, 0.0, 1.0);
        vec3 specular = vec3(0.0);
        if (beta < 1.0) {
            vec3 d = envmap_lookup_dir(n, r, alpha);
            specular = spec * envmap_specular(d, alpha) * envmap_horizon(d, s.geometric_normal);
        }
        if (beta > 0.0)
            specular = mix(specular, envmap_filtered_specular(sk, alpha, lobe.f0, lobe.f90, albedo) * (spec / max(albedo, vec3(1e-6))), beta);
#elif ENVMAP_SPECULAR == ENVMAP_SPECULAR_FITTED
        vec3 d = envmap_lookup_dir(n, r, alpha);
        vec3 specular = spec * (sl_lobe_blinn_phong(L, k) ? envmap_specular_blinn(d, alpha, mu) * envmap_horizon(d, s.geometric_normal)
                                                           : envmap_fitted_specular(n, r, mu, alpha, s.geometric_normal));
#elif ENVMAP_SPECULAR == ENVMAP_SPECULAR_FIS || ENVMAP_SPECULAR == ENVMAP_SPECULAR_HYBRID
#if ENVMAP_SPECULAR == ENVMAP_SPECULAR_HYBRID
        float beta = envmap_hybrid_beta(alpha) * envmap_fis_weight;
#else
        float beta = 1.0;
#endif
        // fis estimates the single-scattering specular itself (albedo inside); multiscatter
        // scales it as it scales the split sum's
        vec3 specular = envmap_fis_specular(sk, alpha, r, lobe.f0, lobe.f90, albedo, beta) * (spec / max(albedo, vec3(1e-6)));
#else
        vec3 d = envmap_lookup_dir(n, r, alpha);
        vec3 specular = spec * (sl_lobe_blinn_phong(L, k) ? envmap_specular_blinn(d, alpha, mu) : envmap_specular(d, alpha)) *
                        envmap_horizon(d, s.geometric_normal);
#endif
#ifdef ENVMAP_SCREEN_RAYS
        // every mode: the scene where this pixel's ray met it, for the smooth lobes (the radiance
        // the ray found stands for the lobe's: times the same albedo)
        specular = mix(specular, spec * found.rgb / max(found.a, 1e-6), envmap_scene_weight(found, alpha));
#endif
        lit += lobe.weight * visible * envmap_specular_occlusion(mu, s.ao, alpha) * specular;
    }
    return kd * envmap_diffuse(s.normal) * s.ao + lit;
}

// Environment importance sampling (a lat-long source; em_env_distribution in cube.c builds the
// arrays, its C twin em_env_distribution_sample is tested against this): a row from the marginal
// CDF, a cell from the row's conditional CDF (binary searches), a point uniform in (φ, cos θ)
// inside the cell, so the density over solid angle is the cell's constant pdf.
uniform sampler2D envmap_dist;     // RG32F, (conditional CDF, pdf) per cell
uniform sampler2D envmap_marginal; // R32F, h × 1: the CDF over rows
uniform bool envmap_has_dist;      // false: a cube source or a black map (BRDF sampling alone)
uniform ivec2 envmap_dist_size;
int envmap_cdf_row(float xi) {
    int lo = 0, hi = envmap_dist_size.y - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (texelFetch(envmap_marginal, ivec2(mid, 0), 0).r > xi) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}
int envmap_cdf_cell(int y, float xi) {
    int lo = 0, hi = envmap_dist_size.x - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (texelFetch(envmap_dist, ivec2(mid, y), 0).r > xi) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}
// A world direction distributed as the map's luminance; pdf over solid angle out.
vec3 envmap_env_sample(vec2 xi, out float pdf) {
    int y = envmap_cdf_row(xi.x);
    float m0 = y > 0 ? texelFetch(envmap_marginal, ivec2(y - 1, 0), 0).r : 0.0;
    float m1 = texelFetch(envmap_marginal, ivec2(y, 0), 0).r;
    float t = m1 > m0 ? clamp((xi.x - m0) / (m1 - m0), 0.0, 1.0) : 0.5;
    int x = envmap_cdf_cell(y, xi.y);
    float c0 = x > 0 ? texelFetch(envmap_dist, ivec2(x - 1, y), 0).r : 0.0;
    vec2 cell = texelFetch(envmap_dist, ivec2(x, y), 0).rg;
    float sx = cell.r > c0 ? clamp((xi.y - c0) / (cell.r - c0), 0.0, 1.0) : 0.5;
    vec2 size = vec2(envmap_dist_size);
    float ct0 = cos(ENVMAP_PI * float(y) / size.y), ct1 = cos(ENVMAP_PI * float(y + 1) / size.y);
    float ct = mix(ct0, ct1, t);
    pdf = cell.g;
    vec3 m = envmap_latlong_dir(vec2((float(x) + sx) / size.x, acos(clamp(ct, -1.0, 1.0)) / ENVMAP_PI));
    return transpose(envmap_rot) * m; // map → world
}
// The density envmap_env_sample gives world direction d (0 without a distribution).
float envmap_env_pdf(vec3 d) {
    if (!envmap_has_dist) return 0.0;
    vec2 uv = envmap_dir_latlong(envmap_rot * d);
    ivec2 c = min(ivec2(uv * vec2(envmap_dist_size)), envmap_dist_size - 1);
    return texelFetch(envmap_dist, c, 0).g;
}
// The reference: Monte Carlo with the model's own f (sl_shading_model, no lobe approximation).
// Each iteration takes one direction per strategy: cosine-distributed when the model has a
// diffuse albedo (or no lobe), and GGX visible normals (Heitz 2018; pdf(l) = G1(v) D(h)/(4 n·v))
// per lobe of non-zero weight, and (a lat-long source, issue 42) one drawn from the environment's
// luminance (envmap_env_sample), weighted by the balance heuristic (Veach 1997, one sample per
// strategy: f L cos / Σ_j pdf_j(l)), so any f is integrated without bias — GGX lobes and the
// cosine lobe each cover the hemisphere — and the lobes and the map only steer the samples; the
// environment strategy finds a small bright sun that BRDF sampling hits by chance. With a metal's
// single lobe this is visible-normal sampling alone, f cos/pdf = F G(v,l)/G1(v) ≤ 1. pdf and f
// take h = normalize(l + v) in world space alike (D at α → 0 is too steep for two roundings).
// The source map is read at full resolution; light from under the geometric surface (normal
// maps) is blocked for all but the contract's diffuse term (as the split sum's irradiance);
// s.ao scales the result. A lobe with its own normal (sl_lobe_normal) is sampled about it.
float envmap_reference_pdf(vec3 l, SlSurface s, SlLobes L, int lobes, bool cosine) {
    float ndl = dot(s.normal, l);
    float pdf = (cosine ? max(ndl, 0.0) * SL_INV_PI : 0.0) + envmap_env_pdf(l);
    vec3 h = normalize(l + s.view);
    for (int j = 0; j < lobes; ++j) {
        vec3 nj = sl_lobe_normal(L, j, s);
        float a = max(L.lobe[j].alpha, GGX_MIN_ALPHA), ndh = dot(nj, h), ndv = dot(nj, s.view);
        if (L.lobe[j].weight > 0.0 && ndh > 0.0 && ndv > 0.0) pdf += envmap_smith_g1(ndv, a) * ggx_D(ndh, a) / (4.0 * ndv);
    }
    return pdf;
}
// The contract's diffuse term alone, f_d(l) cos (common.glsl): diffuse/π, under 1 − F of lobe 0
// with diffuse_coupled.
vec3 envmap_lobes_diffuse(SlLobes L, vec3 l, SlSurface s) {
    vec3 d = L.diffuse * SL_INV_PI * max(dot(s.normal, l), 0.0);
    if (L.diffuse_coupled && L.count > 0) d *= 1.0 - envmap_schlick(dot(l, normalize(l + s.view)), L.lobe[0].f0, L.lobe[0].f90);
    return d;
}
vec3 envmap_reference(SlSurface s) {
    SlLobes L = sl_model_lobes(s);
    vec3 n = s.normal, v = s.view;
    vec3 t, b;
    envmap_frame(n, t, b);
    vec3 vl = vec3(dot(v, t), dot(v, b), dot(v, n));
    int lobes = vl.z > 0.0 ? min(L.count, SL_MAX_LOBES) : 0;
    // each lobe's frame about its own normal (where it has none, the surface's)
    vec3 lt[SL_MAX_LOBES], lb[SL_MAX_LOBES], ln[SL_MAX_LOBES], lv[SL_MAX_LOBES];
    for (int k = 0; k < SL_MAX_LOBES; ++k) {
        ln[k] = sl_lobe_normal(L, k, s);
        envmap_frame(ln[k], lt[k], lb[k]);
        lv[k] = vec3(dot(v, lt[k]), dot(v, lb[k]), dot(v, ln[k]));
    }
    bool any_lobe = false;
    for (int k = 0; k < lobes; ++k) any_lobe = any_lobe || L.lobe[k].weight > 0.0;
    bool cosine = max(L.diffuse.r, max(L.diffuse.g, L.diffuse.b)) > 0.0 || !any_lobe;
    vec2 rot = envmap_reference_rotation();
    vec3 sum = vec3(0.0);
    int i = 0; // a do-while (reference_samples >= 1), as the fis loop above
    do {
        vec2 xi = envmap_xi(uint(i), rot);
        for (int k = -2; k < lobes; ++k) {
            vec3 ll;
            if (k == -2) { // the environment's own strategy
                if (!envmap_has_dist) continue;
                float pe;
                vec3 le = envmap_env_sample(fract(xi + vec2(0.25, 0.75)), pe);
                ll = vec3(dot(le, t), dot(le, b), dot(le, n));
            } else if (k < 0) {
                if (!cosine) continue;
                ll = envmap_sample_cosine(fract(xi + vec2(0.5, 0.25)));
            } else {
                if (!(L.lobe[k].weight > 0.0) || lv[k].z <= 0.0) continue;
                vec3 hl = envmap_sample_vndf(lv[k], max(L.lobe[k].alpha, GGX_MIN_ALPHA), fract(xi + vec2(0.375, 0.625) * float(k)));
                hl = 2.0 * dot(lv[k], hl) * hl - lv[k]; // the direction, in the lobe's frame
                vec3 lw = lt[k] * hl.x + lb[k] * hl.y + ln[k] * hl.z;
                if (dot(lw, ln[k]) <= 0.0) continue; // below the lobe's own horizon
                ll = vec3(dot(lw, t), dot(lw, b), dot(lw, n));
            }
            if (ll.z <= 0.0) continue;
            vec3 l = t * ll.x + b * ll.y + n * ll.z;
            vec3 Li = envmap_source(l, 0.0);
            vec3 f = sl_shading_model(s, l, Li), fd = envmap_lobes_diffuse(L, l, s) * Li;
            f = fd + (f - fd) * envmap_above(l, s.geometric_normal);
            sum += f / envmap_reference_pdf(l, s, L, lobes, cosine);
        }
    } while (++i < envmap_reference_samples);
    return s.ao * sum / float(envmap_reference_samples);
}

// The lobe contract's SL_LOBES_MODEL_AT_DOMINANT_LIGHT (common.glsl): the environment as one
// directional light and the rest. Per channel the irradiance's order-1 SH term is
// π (c_x, c_y, c_z)·m (envmap_sh, map space); a directional light of irradiance E_d from d has the
// order-1 term E_d/2 (n·d) (the clamped cosine's projection, beside E_d/4 in order 0), so d is the
// direction of that term (luminance) and E_d = 2π (c·d). The diffuse albedo takes the rest,
// max(E(n) − E_d max(0, n·d), 0) with E(n) as `irradiance` computes it: a Lambert f gives the
// split sum's diffuse exactly. s.ao scales both, as it scales the split sum.
vec3 envmap_at_dominant_light(SlSurface s, SlLobes L) {
    const vec3 luminance = vec3(0.2126, 0.7152, 0.0722);
    vec3 cx = envmap_sh[3], cy = envmap_sh[1], cz = envmap_sh[2];
    vec3 dm = vec3(dot(cx, luminance), dot(cy, luminance), dot(cz, luminance));
    vec3 d = s.normal, Ed = vec3(0.0);
    if (length(dm) > 1e-8) {
        dm = normalize(dm);
        Ed = max(2.0 * SL_PI * (cx * dm.x + cy * dm.y + cz * dm.z), vec3(0.0)) * envmap_scale;
        d = transpose(envmap_rot) * dm; // map → world
    }
    vec3 rest = max(SL_PI * envmap_diffuse(s.normal) - Ed * max(dot(s.normal, d), 0.0), vec3(0.0));
    return s.ao * (sl_shading_model(s, d, Ed) + L.diffuse * SL_INV_PI * rest);
}

vec3 envmap_tint(SlSurface s) {
#if defined(SL_MAT_HAS_BASE_COLOR) || defined(SL_MAT_HAS_BASE_COLOR_MAP)
    return s.base_color;
#else
    return vec3(1.0);
#endif
}

// The per-light part of "mirror" and "environment": a perfect mirror sees a punctual light only
// as a delta, and "environment" shows the map along n; neither reacts to lights.
vec3 envmap_model_none(SlSurface s, vec3 l, vec3 E) { return vec3(0.0); }
// Their lobes (the SDK's lobe contract, for other integrators such as area lights): "mirror" is
// one lobe of the smallest α with Fresnel 1 tinted like its environment reflection;
// "environment" shows the map and ignores every light: none.
SlLobes envmap_mirror_lobes(SlSurface s) {
    SlLobes L = sl_lobes_none();
    L.count = 1;
    L.lobe[0] = SlLobe(envmap_tint(s), envmap_tint(s), GGX_MIN_ALPHA, 1.0, 0.0);
    return L;
}
SlLobes envmap_environment_lobes(SlSurface s) { return sl_lobes_none(); }

#if defined(SL_MODEL_MIRROR) || defined(SL_MODEL_ENVIRONMENT)
// The procedural sky's sun where it is a light of its own (sun_light): the source's texels leave
// the disk out, so what shows it along one direction adds it here (a light is a delta to these).
// Filtered over the lookup's footprint (a cone `footprint` radians wide, as the texels' level is):
// the disk spreads to a radius s of at least half the footprint, and its edge ramps linearly over
// one footprint f about s, so a sub-pixel reflection of it is a soft spot, not one sample's spark.
// The ramp's solid angle is π(s² + f²/12) (the flat disk's ∫ 2πρ cover dρ), which the radiance
// divides to keep the disk's energy πr²·L (over πs² alone: 4/3 of it where s = f/2, a sun seen in a
// mirror whose pixel is wider than the disk; test_envmap_render, "mirror floor").
// A still's jittered frames each cover 1/n of the pixel (aa's taa_lod_bias for textures): their
// footprint is 2/√n as wide, two samples' spacing, so the still's mean is close to the pixel's
// box filter of the disk and a sub-pixel reflection of it is not one sample's hit or miss.
uniform vec3 envmap_sun_dir;      // towards the sun, map frame
uniform float envmap_sun_radius;  // the disk's angular radius, radians
uniform vec3 envmap_sun_radiance; // E/Ω × colour × the environment's intensity; 0: in the texels
uniform float envmap_sun_footprint; // 1, or 2/√n in the jittered frames of an n-frame still
vec3 envmap_sun_disk(vec3 d, float footprint) {
    if (envmap_sun_radiance.r <= 0.0) return vec3(0.0); // the disk is in the texels (uniform: skipped)
    footprint *= envmap_sun_footprint;
    float angle = acos(clamp(dot(envmap_rot * d, envmap_sun_dir), -1.0, 1.0));
    float r = envmap_sun_radius, spread = max(r, 0.5 * footprint);
    float cover = clamp((spread - angle) / max(footprint, 1e-6) + 0.5, 0.0, 1.0);
    return envmap_sun_radiance * (r * r / (spread * spread + footprint * footprint / 12.0)) * cover;
}
#endif

vec3 envmap_ambient(SlSurface s) {
    // screen-space footprint of the lookup direction, before any branch (derivatives)
#if defined(SL_MODEL_MIRROR)
    vec3 d = reflect(-s.view, s.normal);
#else
    vec3 d = s.normal;
#endif
    float footprint = max(length(dFdx(d)), length(dFdy(d)));
#if defined(SL_MODEL_MIRROR) || defined(SL_MODEL_ENVIRONMENT)
    vec3 env = envmap_source(d, envmap_source_lod(footprint)) + envmap_sun_disk(d, footprint);
#if defined(SL_MODEL_MIRROR)
    env = envmap_with_scene(envmap_scene_found(s), 0.0, env);
#endif
    return envmap_tint(s) * env;
#else
    SlLobes lobes = sl_model_lobes(s);
    // a model lit at the dominant light is defined by that evaluation: every mode gives it
    if ((lobes.flags & SL_LOBES_MODEL_AT_DOMINANT_LIGHT) != 0) return envmap_at_dominant_light(s, lobes);
#if ENVMAP_MODE == ENVMAP_MODE_REFERENCE
    return envmap_reference(s);
#else
    return envmap_split_sum(s);
#endif
#endif
}
