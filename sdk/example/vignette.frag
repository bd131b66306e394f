// POST pass of the SDK example: scales the linear HDR radiance in "color" by 1 - strength·r²/2,
// r = distance from the image centre in [-1,1]² units (0 in the middle, √2 in the corners).
// Vertex stage: the core's sl:fullscreen.vert (one triangle, v_uv in [0,1]).
in vec2 v_uv;
uniform sampler2D u_color;
uniform float u_strength;
layout(location = 0) out vec4 o_color;

void main() {
    vec4 c = texelFetch(u_color, ivec2(gl_FragCoord.xy), 0);
    vec2 d = v_uv * 2.0 - 1.0;
    float k = max(0.0, 1.0 - 0.5 * u_strength * dot(d, d));
    o_color = vec4(c.rgb * k, c.a);
}
