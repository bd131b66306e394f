// The tone-mapping post pass: "color" (linear HDR) → tone-mapped linear display values.
#include "sl:common.glsl"
#include "tonemap_ops.glsl"
uniform sampler2D tonemap_src;
uniform int tonemap_op;
uniform float tonemap_exposure_ev;
uniform float tonemap_white_point;
uniform bool tonemap_dither_on;
uniform bool tonemap_false_color_on;
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
    vec3 c = tonemap_false_color_on ? tonemap_false_color(src.rgb, tonemap_exposure_ev)
                                    : tonemap_apply(src.rgb, tonemap_op, tonemap_exposure_ev, tonemap_white_point);
    if (tonemap_dither_on) c = tonemap_dither(c, tonemap_noise(uvec2(gl_FragCoord.xy)));
    o_color = vec4(c, 1.0);
}
