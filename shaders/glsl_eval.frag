// GLSL unit tests: evaluates SL_EVAL_EXPRESSION for every texel of the input grids.
// in0/in1 are the inputs at this texel; the result goes to an RGBA32F target.
uniform sampler2D sl_eval_in0;
uniform sampler2D sl_eval_in1;
layout(location = 0) out vec4 o_result;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 in0 = texelFetch(sl_eval_in0, p, 0);
    vec4 in1 = texelFetch(sl_eval_in1, p, 0);
    o_result = vec4(SL_EVAL_EXPRESSION);
}
