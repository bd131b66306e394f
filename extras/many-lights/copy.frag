// many-lights: first step of the deferred pass. Copies the forward pass's colour into the pass's
// output (pixels no material covers keep it) and writes each pixel's material as window depth
// (index + 1) / 1024 (0 where nothing was drawn): the per-material lighting triangles lie at
// that depth (draw_scene fullscreen, ABI 1.7) and, drawn with GL_EQUAL, reach only their pixels.
uniform sampler2D many_lights_color, many_lights_g0;
layout(location = 0) out vec4 o_color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    o_color = texelFetch(many_lights_color, p, 0);
    gl_FragDepth = floor(texelFetch(many_lights_g0, p, 0).w + 0.5) / 1024.0;
}
