// Test plugin post pass: colour × gain.
#include "sl:common.glsl"
uniform sampler2D tp_src;
uniform float tp_gain;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(tp_src, ivec2(gl_FragCoord.xy), 0) * tp_gain; }
