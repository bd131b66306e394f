// The core's light types (LIGHT hooks). E is irradiance at normal incidence.
// A directional light's disk: angular_radius (radians in direction.w) for the specular lobes.
bool sl_light_directional(SlLight L, SlSurface s, out vec3 l, out vec3 E) {
    l = -L.direction.xyz;
    E = L.color.rgb;
    sl_light_spread = L.direction.w;
    return true;
}

bool sl_light_point(SlLight L, SlSurface s, out vec3 l, out vec3 E) {
    vec3 d = L.position.xyz - s.position;
    float d2 = max(dot(d, d), 1e-8); // a light inside the surface stays finite
    l = d * inversesqrt(d2);
    E = L.color.rgb / d2;
    return true;
}
