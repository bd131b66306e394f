// refraction back-face pass (refraction.c, method = two-interface): the back faces of materials
// carrying `ior`, drawn with front faces culled. The core binds attributes 0 position, 1 normal
// and sets sl_model, sl_normal_matrix and the camera uniforms (declared here: a pass program gets
// no core library).
uniform mat4 sl_model, sl_view_proj, sl_view;
uniform mat3 sl_normal_matrix;
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
out vec3 v_world;
out vec3 v_normal;
flat out vec3 v_camera;
void main() {
    vec4 w = sl_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = sl_normal_matrix * a_normal;
    v_camera = inverse(sl_view)[3].xyz;
    gl_Position = sl_view_proj * w;
}
