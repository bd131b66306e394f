// The core's display transform: clamp to [0,1] and sRGB-encode (IEC 61966-2-1). Tone mapping,
// when a plugin provides it, has already run at stage POST. Non-finite values display black.
#include "common.glsl"
in vec2 v_uv;
uniform sampler2D sl_color;
layout(location = 0) out vec4 o_color;
void main() {
    vec3 c = texelFetch(sl_color, ivec2(gl_FragCoord.xy), 0).rgb;
    bvec3 bad = bvec3(isnan(c.r) || isinf(c.r), isnan(c.g) || isinf(c.g), isnan(c.b) || isinf(c.b));
    c = mix(c, vec3(0.0), bvec3(bad));
    o_color = vec4(sl_srgb_encode(c), 1.0);
}
