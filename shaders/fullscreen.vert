// One triangle covering the viewport; v_uv in [0,1] over the screen.
out vec2 v_uv;
#ifdef SL_FULLSCREEN_MATERIAL
uniform int sl_material_index;
#endif
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    v_uv = p;
#ifdef SL_FULLSCREEN_MATERIAL
    // a full-screen material pass (draw_scene fullscreen, ABI 1.7): window depth (index + 1) / 1024,
    // so a pass that wrote that value per pixel into its depth output can select a material's
    // pixels with glDepthFunc(GL_EQUAL) before any shading
    gl_Position = vec4(p * 2.0 - 1.0, float(sl_material_index + 1) / 512.0 - 1.0, 1.0);
#else
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
#endif
}
