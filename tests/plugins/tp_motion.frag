// tp-motion: the core's "motion" (UV now minus UV before) as colour.
uniform sampler2D tp_motion;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(texelFetch(tp_motion, ivec2(gl_FragCoord.xy), 0).rg, 0.0, 1.0); }
