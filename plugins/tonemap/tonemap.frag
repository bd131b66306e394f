// The tone-mapping post pass: "color" (linear HDR) → tone-mapped linear display values.
// The operator, the false-colour view and the dither are the program's permutation (tonemap.c:
// TONEMAP_OPERATOR, TONEMAP_FALSE_COLOR, TONEMAP_DITHER), not uniforms: on llvmpipe every side of a
// branch runs under a mask, so a uniform choice paid for all six curves at every pixel.
#include "sl:common.glsl"
#include "tonemap_ops.glsl"
uniform sampler2D tonemap_src;
uniform float tonemap_exposure_ev;
uniform float tonemap_white_point;
uniform int tonemap_frame;
layout(location = 0) out vec4 o_color;

vec2 tonemap_noise(uvec2 p) {
    uvec3 v = uvec3(p, uint(tonemap_frame)) * uvec3(1664525u, 1013904223u, 2654435761u);
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z; v.y += v.z * v.x;
    return vec2(v.xy) * 2.3283064365386963e-10;
}

void main() {
    vec4 src = texelFetch(tonemap_src, ivec2(gl_FragCoord.xy), 0);
#if TONEMAP_FALSE_COLOR
    vec3 c = tonemap_false_color(src.rgb, tonemap_exposure_ev);
#else
    // a constant operator: the compiler keeps only its curve
    vec3 c = tonemap_apply(src.rgb, TONEMAP_OPERATOR, tonemap_exposure_ev, tonemap_white_point);
#endif
#if TONEMAP_DITHER
    c = tonemap_dither(c, tonemap_noise(uvec2(gl_FragCoord.xy)));
#endif
    o_color = vec4(c, 1.0);
}
