// tp-upscale: the upscaler writes the render texel each output pixel falls in (nearest) and the
// render width it read; with TP_AFTER, the pass after it keeps rgb and writes its sl_frame.width.
in vec2 v_uv;
uniform sampler2D tp_color;
uniform float tp_frame_width;
layout(location = 0) out vec4 o_color;
void main() {
#if defined(TP_AFTER)
    o_color = vec4(texelFetch(tp_color, ivec2(gl_FragCoord.xy), 0).rgb, tp_frame_width);
#else
    ivec2 size = textureSize(tp_color, 0);
    o_color = vec4(floor(v_uv * vec2(size)), float(size.x), 1.0);
#endif
}
