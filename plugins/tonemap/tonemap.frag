// The tone-mapping post pass: "color" (linear HDR) → tone-mapped linear display values, the
// per-pixel map of tonemap_point.glsl (which the pass before it may run in its own draw instead).
#include "tonemap_point.glsl"
uniform sampler2D tonemap_src;
layout(location = 0) out vec4 o_color;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    o_color = vec4(tonemap_point(texelFetch(tonemap_src, p, 0).rgb, p), 1.0);
}
