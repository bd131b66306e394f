// The core's display transform: clamp to [0,1] and sRGB-encode (IEC 61966-2-1). Tone mapping,
// when a plugin provides it, has already run at stage POST. NaN displays black; ±Inf clamps like
// any other value (+Inf is an overflow of something very bright: white).
#include "common.glsl"
in vec2 v_uv;
uniform sampler2D sl_color;
layout(location = 0) out vec4 o_color;
void main() {
    vec3 c = texelFetch(sl_color, ivec2(gl_FragCoord.xy), 0).rgb;
    c = mix(c, vec3(0.0), bvec3(isnan(c)));
    o_color = vec4(sl_srgb_encode(c), 1.0);
}
