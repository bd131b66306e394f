// The tone-mapping pass's per-pixel map: linear HDR radiance → tone-mapped linear display values.
// tonemap.frag runs it as a pass of its own; fused into the pass before it (shadelab.post/1,
// tonemap.c) it runs in that pass's draw instead. The operator, the false-colour view and the
// dither are the program's permutation (TONEMAP_OPERATOR, TONEMAP_FALSE_COLOR, TONEMAP_DITHER),
// not uniforms: on llvmpipe every side of a branch runs under a mask, so a uniform choice paid for
// all six curves at every pixel.
#include "sl:common.glsl"
#include "tonemap_ops.glsl"
uniform float tonemap_exposure_ev;
uniform float tonemap_white_point;
uniform int tonemap_frame;

vec2 tonemap_noise(uvec2 p) {
    uvec3 v = uvec3(p, uint(tonemap_frame)) * uvec3(1664525u, 1013904223u, 2654435761u);
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z; v.y += v.z * v.x;
    return vec2(v.xy) * 2.3283064365386963e-10;
}

vec3 tonemap_point(vec3 src, ivec2 pixel) {
#if TONEMAP_FALSE_COLOR
    vec3 c = tonemap_false_color(src, tonemap_exposure_ev);
#else
    // a constant operator: the compiler keeps only its curve
    vec3 c = tonemap_apply(src, TONEMAP_OPERATOR, tonemap_exposure_ev, tonemap_white_point);
#endif
#if TONEMAP_DITHER
    c = tonemap_dither(c, tonemap_noise(uvec2(pixel)));
#endif
    return c;
}
