// spotlight-shadow: the "spot" light type (LIGHT hook). Packed keys (light_slot):
//   params[0] = (cone_angle°, inner_cone_angle°, falloff 0 linear / 1 gltf, radius m)
// Position and direction arrive animated by the core (light keys animate, animate_speed, animate_amount).
// E = I/d² · fall-off; shadows are applied by the SHADOW hook (shadow.glsl), not here.
#include "spot_falloff.glsl"

bool spotlight_shadow_spot(SlLight L, SlSurface s, out vec3 l, out vec3 E) {
    vec3 pos = L.position.xyz, axis = L.direction.xyz;
    vec3 d = pos - s.position;
    float d2 = max(dot(d, d), 1e-8); // a light on the surface stays finite
    l = d * inversesqrt(d2);
    float f = spotlight_shadow_falloff(-l, axis, radians(L.params[0].x), radians(L.params[0].y), L.params[0].z);
    E = L.color.rgb * (f / d2);
    return f > 0.0;
}
