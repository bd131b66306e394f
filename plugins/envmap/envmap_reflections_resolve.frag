// envmap-reflections-resolve (reflections=screen): what the rays found (envmap-reflections-trace),
// filtered over each texel's 3×3 neighbours on its own surface. A ray decides hit or miss once, and
// on a convex mirror, where neighbouring texels' rays diverge, the edge of a reflected object was a
// speckle of hits and misses. Here the weight is the neighbours' mean under a tent (4 at the texel,
// 2 beside it, 1 diagonally: the share of them whose ray hit), the radiance the texel's own where
// its ray hit (a hit keeps its detail) and its neighbours' mean where it missed: a speckle becomes a
// partial weight. Neighbours on another surface (view distance more than 3 % apart: the silhouette
// of the object the texel is on) are left out. Five taps (the texel and its four neighbours) cost
// half as much and left a faint speckle.
#include "envmap_common.glsl"
in vec2 v_uv;
uniform sampler2D envmap_refl_found; // (radiance × weight, weight) per texel, the trace's
uniform sampler2D envmap_refl_depth; // the scene image's window depth
uniform vec4 envmap_refl_depth_lin;  // view distance from NDC z (envmap_view_distance)
layout(location = 0) out vec4 o_found;

float envmap_refl_distance_at(ivec2 p) {
    return envmap_view_distance(envmap_refl_depth_lin, texelFetch(envmap_refl_depth, p, 0).r * 2.0 - 1.0);
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy), last = textureSize(envmap_refl_found, 0) - 1;
    vec4 own = texelFetch(envmap_refl_found, px, 0);
    float d = envmap_refl_distance_at(px);
    vec4 sum = vec4(0.0);
    float count = 0.0;
    for (int y = -1; y <= 1; y++)
        for (int x = -1; x <= 1; x++) {
            ivec2 q = clamp(px + ivec2(x, y), ivec2(0), last);
            if (abs(envmap_refl_distance_at(q) - d) > 0.03 * d) continue;
            float k = float((2 - abs(x)) * (2 - abs(y))); // a tent: 4 at the texel, 2 beside, 1 diagonally
            sum += k * texelFetch(envmap_refl_found, q, 0);
            count += k;
        }
    float weight = sum.a / max(count, 1.0);
    vec3 radiance = own.a > 0.0 ? own.rgb / own.a : sum.rgb / max(sum.a, 1e-6);
    o_found = vec4(radiance * weight, weight);
}
