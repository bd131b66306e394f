// aa: TAA's copy, one texel each: a frame without a history (the first, or after a cut) copied as
// it is into both the output and the new history (what taa.frag gives without a history), and a
// converged still's history into the output (its history is kept: only the output is bound then).
// The output goes through the pointwise passes fused into TAA's pass (tone mapping: ext/post.h).
// A program of its own: a copy costs a texel fetch, not the whole resolve, and a first frame
// compiles no resolve.
#include "sl:common.glsl"
uniform sampler2D aa_src;
layout(location = 0) out vec4 o_color;   // the pass's "color" output
layout(location = 1) out vec4 o_history; // the new history: rgb, frames in alpha
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(aa_src, p, 0).rgb;
    o_color = vec4(sl_pointwise_epilogue(c, p), 1.0);
    o_history = vec4(c, 1.0);
}
