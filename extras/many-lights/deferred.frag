// many-lights: the deferred lighting pass, one full-screen triangle per material (draw_scene
// `fragment` + `fullscreen`, ABI 1.7) composed with that material's model code: the SlSurface
// comes from the G-buffer (gbuffer.frag) and sl_direct_lighting() is the same composed light
// loop (many_lights_loop → sl_light_radiance → the material's model) as the forward programs.
// The forward pass already holds everything but the direct light (ambient, emission): add it.
uniform sampler2D many_lights_g0, many_lights_g1, many_lights_g2, many_lights_g3, many_lights_g4, many_lights_color;
layout(location = 0) out vec4 many_lights_out;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 g0 = texelFetch(many_lights_g0, p, 0), g1 = texelFetch(many_lights_g1, p, 0);
    if (int(g0.w + 0.5) != sl_material_index + 1) discard;
    sl_normal_footprint = texelFetch(many_lights_g4, p, 0).r; // the forward pass's own (gbuffer.frag)
    vec4 g2 = texelFetch(many_lights_g2, p, 0), g3 = texelFetch(many_lights_g3, p, 0);
    SlSurface s;
    s.position = g0.xyz;
    s.normal = normalize(g1.xyz);
    s.geometric_normal = s.normal;
    s.view = normalize(sl_camera_pos - s.position);
    s.tangent = abs(s.normal.y) < 0.999 ? normalize(cross(vec3(0.0, 1.0, 0.0), s.normal))
                                        : normalize(cross(vec3(1.0, 0.0, 0.0), s.normal));
    s.bitangent = cross(s.normal, s.tangent);
    s.uv = vec2(0.0);
    s.uv1 = vec2(0.0);
    s.metallic = g3.a;
    s.base_color = g2.rgb;
    s.alpha = g2.a;
    s.specular = g3.r;
    s.ao = g1.a;
    s.opacity = g3.g;
    s.lod_bias = g3.b;
    s.object_position = s.position;
    vec3 c = texelFetch(many_lights_color, p, 0).rgb;
#if defined(SL_DEBUG_VIEW_MANY_LIGHTS_COUNT)
    c = sl_shade_surface(s);
#elif !defined(SL_DEBUG_VIEW_REPLACES_OUTPUT)
    c += sl_direct_lighting(s);
#endif
    many_lights_out = vec4(mix(c, vec3(SL_MAX_RADIANCE), greaterThan(c, vec3(SL_MAX_RADIANCE))), 1.0);
}
