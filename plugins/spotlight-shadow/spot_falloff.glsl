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

// Rotates v about the unit axis a by angle t (Rodrigues).
vec3 spotlight_shadow_rotate(vec3 v, vec3 a, float t) {
    float c = cos(t), s = sin(t);
    return v * c + cross(a, v) * s + a * dot(a, v) * (1.0 - c);
}

// Animation (the C side in spotlight_shadow.c computes the same for the shadow maps):
// mode 1 orbit: position and direction turn about the world Y axis at `speed` rad/s;
// mode 2 wobble: the direction swings by ±amount degrees about the horizontal axis
// perpendicular to it, angle = amount·sin(speed·t).
void spotlight_shadow_animate(inout vec3 pos, inout vec3 dir, float mode, float speed, float amount_deg, float t) {
    if (mode > 0.5 && mode < 1.5) {
        float a = speed * t;
        pos = spotlight_shadow_rotate(pos, vec3(0.0, 1.0, 0.0), a);
        dir = spotlight_shadow_rotate(dir, vec3(0.0, 1.0, 0.0), a);
    } else if (mode > 1.5) {
        vec3 axis = cross(dir, vec3(0.0, 1.0, 0.0));
        float len = length(axis);
        axis = len > 1e-4 ? axis / len : vec3(1.0, 0.0, 0.0);
        dir = normalize(spotlight_shadow_rotate(dir, axis, radians(amount_deg) * sin(speed * t)));
    }
}
