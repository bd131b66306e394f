// Running mean of the HDR colour over accumulated sub-frames (references):
// mean_k = mean_{k-1} + (x_k - mean_{k-1}) / k.
#include "common.glsl"
in vec2 v_uv;
uniform sampler2D sl_color;
uniform sampler2D sl_previous_mean;
uniform float sl_weight; // 1/k
layout(location = 0) out vec4 o_color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 prev = texelFetch(sl_previous_mean, p, 0);
    vec4 x = texelFetch(sl_color, p, 0);
    o_color = prev + (x - prev) * sl_weight;
}
