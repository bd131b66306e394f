// Supersampling resolve: box filter of sl_factor × sl_factor samples of the forward pass,
// in linear HDR radiance (so references and error metrics see the physically averaged value).
#include "common.glsl"
uniform sampler2D sl_src;
uniform int sl_factor;
layout(location = 0) out vec4 o_color;
void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * sl_factor;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < sl_factor; ++j)
        for (int i = 0; i < sl_factor; ++i) sum += texelFetch(sl_src, base + ivec2(i, j), 0);
    o_color = sum / float(sl_factor * sl_factor);
}
