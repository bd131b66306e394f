// refraction back-face pass: rgb = the back face's outward world normal, a = its distance from the
// camera (0 where no back face was drawn: the clear value).
uniform mat4 sl_view;
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_back;
void main() {
    vec3 camera = inverse(sl_view)[3].xyz;
    o_back = vec4(normalize(v_normal), max(length(v_world - camera), 1e-6));
}
