// Supersampling resolve: box filter of sl_factor × sl_factor samples of the forward pass,
// in linear HDR radiance (so references and error metrics see the physically averaged value).
#include "common.glsl"
uniform sampler2D sl_src;
uniform int sl_factor;
layout(location = 0) out vec4 o_color;
void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * sl_factor;
    vec4 sum = vec4(0.0);
    // do-whiles (sl_factor >= 1): llvmpipe runs a loop's body under a mask of the lanes still in
    // it, and a for loop's test at the top ran the body once more after the last pass, every
    // lane masked, at full cost ((f + 1)² fetches for f²)
    int j = 0;
    do {
        int i = 0;
        do sum += texelFetch(sl_src, base + ivec2(i, j), 0);
        while (++i < sl_factor);
    } while (++j < sl_factor);
    o_color = sum / float(sl_factor * sl_factor);
}
