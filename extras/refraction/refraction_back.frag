// refraction back-face pass: rgb = the back face's outward world normal, a = its distance from the
// camera (0 where no back face was drawn: the clear value).
in vec3 v_world;
in vec3 v_normal;
flat in vec3 v_camera;
layout(location = 0) out vec4 o_back;
void main() {
    o_back = vec4(normalize(v_normal), max(length(v_world - v_camera), 1e-6));
}
