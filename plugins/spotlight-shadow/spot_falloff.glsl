// spotlight-shadow: spot-light fall-off and animation, pure functions (no uniforms) so that the
// GLSL unit tests evaluate exactly this code. Conventions (sdk conventions, issue 7):
// cone_angle is the half-angle from the axis to the edge.

// `linear`: full up to 90% of the cone angle, zero at 110%, linear in the angle between.
// theta: angle between the spot axis and the direction to the point (radians).
float spotlight_shadow_falloff_linear(float theta, float cone) {
    return clamp((1.1 * cone - theta) / max(0.2 * cone, 1e-6), 0.0, 1.0);
}

// `gltf` (KHR_lights_punctual): scale = 1/max(0.001, cos(inner) − cos(outer)),
// offset = −cos(outer)·scale, attenuation = clamp(cosθ·scale + offset, 0, 1)².
float spotlight_shadow_falloff_gltf(float cos_theta, float inner, float outer) {
    float scale = 1.0 / max(0.001, cos(inner) - cos(outer));
    float offset = -cos(outer) * scale;
    float a = clamp(cos_theta * scale + offset, 0.0, 1.0);
    return a * a;
}

// The fall-off a spot light's keys select: mode 0 = linear, 1 = gltf; angles in radians.
// to_point: unit vector from the light to the point; axis: unit spot axis. The angle comes from
// atan(|a × b|, a·b), which keeps its precision near the axis where acos(a·b) does not.
float spotlight_shadow_falloff(vec3 to_point, vec3 axis, float cone, float inner, float mode) {
    float c = dot(to_point, axis);
    if (mode > 0.5) return spotlight_shadow_falloff_gltf(c, inner, cone);
    return spotlight_shadow_falloff_linear(atan(length(cross(to_point, axis)), c), cone);
}
