// aa: TAA's copies, one texel each: the new history into the pass's "color" output (alpha 1: the
// history keeps its frame count in alpha), and a first frame (no history yet) into both the
// history and the output, which is what taa.frag gives without a history. A program of its own:
// a copy costs a texel fetch, not the whole resolve, and a first frame compiles no resolve.
#include "sl:common.glsl"
uniform sampler2D aa_src;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(texelFetch(aa_src, ivec2(gl_FragCoord.xy), 0).rgb, 1.0); }
