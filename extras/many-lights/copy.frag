// many-lights: copies the forward pass's colour into the deferred pass's output (pixels no
// material covers keep it; each material's lighting pass then writes its own pixels).
uniform sampler2D many_lights_color;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(many_lights_color, ivec2(gl_FragCoord.xy), 0); }
