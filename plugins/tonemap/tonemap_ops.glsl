// Tone-mapping operators on linear HDR radiance (scene-referred, after exposure) → linear
// display values in [0,1] (the core's display pass then applies the sRGB encoding). Pure
// functions: the plugin's post pass, its curve plotter and the tests all evaluate these.
//
//   0 linear             identity (the display clamps)
//   1 reinhard           x/(1+x) per channel (Reinhard et al. 2002)
//   2 reinhard-extended  x(1 + x/w²)/(1+x): white point w maps to 1
//   3 aces               Stephen Hill's fit of the ACES RRT+ODT (sRGB display), with its
//                        input/output matrices (BakingLab, 2016)
//   4 agx                Troy Sobotka's AgX, Benjamin Wrensch's polynomial fit of the default
//                        contrast (2023); the fit's 2.2 display gamma is undone to linear
//   5 pbr-neutral        Khronos PBR Neutral (2024): identity up to a small toe offset below its
//                        start of compression, hue-preserving roll-off above

const int TONEMAP_LINEAR = 0;
const int TONEMAP_REINHARD = 1;
const int TONEMAP_REINHARD_EXTENDED = 2;
const int TONEMAP_ACES = 3;
const int TONEMAP_AGX = 4;
const int TONEMAP_PBR_NEUTRAL = 5;

// NaN → 0, +Inf → the half-float limit, negatives → 0: every operator sees finite input.
vec3 tonemap_finite(vec3 c) {
    c = mix(c, vec3(0.0), bvec3(isnan(c.r), isnan(c.g), isnan(c.b)));
    return clamp(c, vec3(0.0), vec3(65504.0));
}

vec3 tonemap_reinhard(vec3 x) { return x / (1.0 + x); }

vec3 tonemap_reinhard_extended(vec3 x, float white) {
    return x * (1.0 + x / (white * white)) / (1.0 + x);
}

vec3 tonemap_aces(vec3 c) {
    const mat3 to_aces = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
    const mat3 from_aces = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
    vec3 v = to_aces * c;
    vec3 a = v * (v + 0.0245786) - 0.000090537;
    vec3 b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return clamp(from_aces * (a / b), 0.0, 1.0);
}

vec3 tonemap_agx_contrast(vec3 x) {
    vec3 x2 = x * x, x4 = x2 * x2;
    return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
}
vec3 tonemap_agx(vec3 c) {
    const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051, 0.0784335999999992,
                            0.878468636469772, 0.0784336, 0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438, -0.0980208811401368,
                             1.15190312990417, -0.0980434501171241, -0.0990297440797205, -0.0989611768448433,
                             1.15107367264116);
    const float min_ev = -12.47393, max_ev = 4.026069;
    vec3 v = inset * c;
    v = clamp(log2(max(v, vec3(1e-10))), min_ev, max_ev);
    v = (v - min_ev) / (max_ev - min_ev);
    v = tonemap_agx_contrast(v);
    v = outset * v;
    return pow(clamp(v, 0.0, 1.0), vec3(2.2));
}

vec3 tonemap_pbr_neutral(vec3 color) {
    const float start = 0.8 - 0.04, desaturation = 0.15;
    float x = min(color.r, min(color.g, color.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    float peak = max(color.r, max(color.g, color.b));
    if (peak < start) return color;
    const float d = 1.0 - start;
    float new_peak = 1.0 - d * d / (peak + d - start);
    color *= new_peak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(color, vec3(new_peak), g);
}

// exposure in stops (×2^E before the operator); white: reinhard-extended's white point.
vec3 tonemap_apply(vec3 hdr, int op, float exposure, float white) {
    vec3 c = tonemap_finite(hdr) * exp2(exposure);
    if (op == TONEMAP_REINHARD) return tonemap_reinhard(c);
    if (op == TONEMAP_REINHARD_EXTENDED) return tonemap_reinhard_extended(c, white);
    if (op == TONEMAP_ACES) return tonemap_aces(c);
    if (op == TONEMAP_AGX) return tonemap_agx(c);
    if (op == TONEMAP_PBR_NEUTRAL) return tonemap_pbr_neutral(c);
    return c;
}

// False-colour exposure view: the luminance (after exposure) in stops from middle grey 0.18,
// as bands: < -6 purple, -6..-4 blue, -4..-2 cyan, -2..-0.5 dark grey, ±0.5 green (middle
// grey), 0.5..2 light grey, 2..3.5 yellow, 3.5..5 orange, ≥ 5 red.
vec3 tonemap_false_color(vec3 hdr, float exposure) {
    float y = dot(tonemap_finite(hdr) * exp2(exposure), vec3(0.2126, 0.7152, 0.0722));
    float stops = log2(max(y, 1e-12) / 0.18);
    if (stops < -6.0) return vec3(0.10, 0.00, 0.20);
    if (stops < -4.0) return vec3(0.00, 0.05, 0.70);
    if (stops < -2.0) return vec3(0.00, 0.45, 0.55);
    if (stops < -0.5) return vec3(0.12);
    if (stops < 0.5) return vec3(0.05, 0.65, 0.05);
    if (stops < 2.0) return vec3(0.40);
    if (stops < 3.5) return vec3(0.85, 0.75, 0.05);
    if (stops < 5.0) return vec3(1.00, 0.35, 0.00);
    return vec3(1.0, 0.0, 0.0);
}

// Triangular-PDF dither of ±1 code value of the 8-bit sRGB display, applied in linear light
// (encode, add, decode), so the display pass's quantisation does not band smooth gradients.
vec3 tonemap_dither(vec3 c, vec2 noise) {
    vec3 e = clamp(c, 0.0, 1.0);
    e = mix(12.92 * e, 1.055 * pow(e, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), e));
    e += (noise.x + noise.y - 1.0) / 255.0;
    e = clamp(e, 0.0, 1.0);
    return mix(e / 12.92, pow((e + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), e));
}
