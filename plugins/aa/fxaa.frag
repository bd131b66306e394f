// aa: FXAA, after T. Lottes, "FXAA", NVIDIA white paper (2009) and the FXAA 3.11 quality
// algorithm it describes: written here from the description, not copied.
//   1. Luma of the 4-neighbourhood; when its contrast is below max(threshold_min, threshold · the
//      brightest luma) the pixel is returned exactly as it was (flat regions are untouched).
//   2. Sub-pixel aliasing: how much the pixel differs from its 3x3 low-pass, relative to the
//      contrast, gives a blend amount (single-pixel features).
//   3. Edge orientation from the 3x3 second differences; the side of the edge with the steeper
//      gradient; a walk along the edge in both directions (sampling half-way between the two rows
//      with bilinear filtering) until the luma pair leaves the edge; the pixel's position along
//      the span gives how far towards the other side to sample.
// Luma is that of the display encoding (sRGB of the clamped colour, Rec. 709 weights), where the
// eye sees the steps; the colour that is blended is the stored one (linear, maybe HDR), so the
// blend averages radiance like supersampling does.
#include "sl:common.glsl"
in vec2 v_uv;
uniform sampler2D aa_src;           // bilinear, clamp to edge
uniform float aa_edge_threshold;     // relative contrast needed (Lottes: 1/8 high quality)
uniform float aa_edge_threshold_min; // absolute contrast needed in dark areas (Lottes: 1/16..1/12)
uniform float aa_subpix;             // sub-pixel blend strength (Lottes: 0.75)
layout(location = 0) out vec4 o_color;

float aa_luma(vec3 c) {
    return dot(sl_srgb_encode(mix(c, vec3(0.0), bvec3(isnan(c)))), vec3(0.2126, 0.7152, 0.0722));
}
float aa_luma_at(vec2 uv) { return aa_luma(textureLod(aa_src, uv, 0.0).rgb); }
float aa_luma_px(ivec2 p) {
    ivec2 size = textureSize(aa_src, 0);
    return aa_luma(texelFetch(aa_src, clamp(p, ivec2(0), size - 1), 0).rgb);
}

// Step lengths of the edge walk, in pixels (coarser the farther it goes): 12 steps, 38.5 pixels.
const int AA_STEPS = 12;
const float aa_step[12] = float[12](1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0);

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 centre = texelFetch(aa_src, p, 0);
    vec2 texel = 1.0 / vec2(textureSize(aa_src, 0));
    vec2 uv = (vec2(p) + 0.5) * texel;

    float m = aa_luma(centre.rgb);
    float n = aa_luma_px(p + ivec2(0, 1)), s = aa_luma_px(p + ivec2(0, -1));
    float e = aa_luma_px(p + ivec2(1, 0)), w = aa_luma_px(p + ivec2(-1, 0));
    float lo = min(m, min(min(n, s), min(e, w))), hi = max(m, max(max(n, s), max(e, w)));
    float range = hi - lo;
    if (range < max(aa_edge_threshold_min, hi * aa_edge_threshold)) {
        o_color = centre; // 1: no visible edge here
        return;
    }
    float ne = aa_luma_px(p + ivec2(1, 1)), nw = aa_luma_px(p + ivec2(-1, 1));
    float se = aa_luma_px(p + ivec2(1, -1)), sw = aa_luma_px(p + ivec2(-1, -1));

    // 2: sub-pixel blend from the 3x3 low-pass (weights 2 for the 4-neighbours, 1 corners)
    float lowpass = (2.0 * (n + s + e + w) + ne + nw + se + sw) / 12.0;
    float sub = clamp(abs(lowpass - m) / range, 0.0, 1.0);
    sub = smoothstep(0.0, 1.0, sub);
    float sub_offset = sub * sub * aa_subpix;

    // 3: orientation. A horizontal edge (luma changes along y) has large vertical differences.
    float horiz = abs(nw - 2.0 * w + sw) + 2.0 * abs(n - 2.0 * m + s) + abs(ne - 2.0 * e + se);
    float vert = abs(nw - 2.0 * n + ne) + 2.0 * abs(w - 2.0 * m + e) + abs(sw - 2.0 * s + se);
    bool horizontal = horiz >= vert;
    // the two neighbours across the edge: negative side (s or w) and positive side (n or e)
    float l_neg = horizontal ? s : w, l_pos = horizontal ? n : e;
    float g_neg = abs(l_neg - m), g_pos = abs(l_pos - m);
    bool towards_neg = g_neg >= g_pos;
    float l_other = towards_neg ? l_neg : l_pos;
    float gradient = max(g_neg, g_pos);
    vec2 across = horizontal ? vec2(0.0, texel.y) : vec2(texel.x, 0.0);
    if (towards_neg) across = -across;
    vec2 along = horizontal ? vec2(texel.x, 0.0) : vec2(0.0, texel.y);

    // walk along the edge, half a pixel towards the other side (bilinear mean of the pair)
    vec2 start = uv + 0.5 * across;
    float pair = 0.5 * (m + l_other);
    float limit = 0.25 * gradient;
    vec2 uv_a = start, uv_b = start;
    float end_a = 0.0, end_b = 0.0;
    bool done_a = false, done_b = false;
    for (int i = 0; i < AA_STEPS && !(done_a && done_b); ++i) {
        if (!done_a) {
            uv_a -= aa_step[i] * along;
            end_a = aa_luma_at(uv_a) - pair;
            done_a = abs(end_a) >= limit;
        }
        if (!done_b) {
            uv_b += aa_step[i] * along;
            end_b = aa_luma_at(uv_b) - pair;
            done_b = abs(end_b) >= limit;
        }
    }
    float dist_a = horizontal ? uv.x - uv_a.x : uv.y - uv_a.y;
    float dist_b = horizontal ? uv_b.x - uv.x : uv_b.y - uv.y;
    bool a_closer = dist_a < dist_b;
    float closest = min(dist_a, dist_b);
    float span = dist_a + dist_b;
    // Only blend when the nearer end turns the same way as this pixel: the centre darker than the
    // pair means the edge's end must be brighter than the pair there (else this side is not the
    // one the staircase steps into).
    bool centre_darker = m - pair < 0.0;
    bool end_turns = ((a_closer ? end_a : end_b) < 0.0) != centre_darker;
    float edge_offset = end_turns ? 0.5 - closest / span : 0.0;

    float offset = max(edge_offset, sub_offset);
    o_color = vec4(textureLod(aa_src, uv + offset * across, 0.0).rgb, centre.a);
}
