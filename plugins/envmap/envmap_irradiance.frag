// Diffuse irradiance by brute force: E(n)/π = (1/π) Σ L(ω_i) max(0, n·ω_i) Ω_i over every texel
// of one (small) mip of the base cube. Deterministic (no noise); the texel solid angles are
// renormalised so they sum to exactly 4π.
#include "envmap_common.glsl"
uniform samplerCube envmap_incube;
uniform float envmap_src_level; // mip level read
uniform int envmap_src_size;    // its face size
uniform int envmap_face;
uniform float envmap_size;      // output face size
layout(location = 0) out vec4 o_color;

void main() {
    vec3 n = normalize(envmap_cube_dir(envmap_face, gl_FragCoord.xy / envmap_size));
    float s = float(envmap_src_size);
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int f = 0; f < 6; f++)
        for (int y = 0; y < envmap_src_size; y++)
            for (int x = 0; x < envmap_src_size; x++) {
                vec2 st = (vec2(x, y) + 0.5) / s;
                vec3 d = normalize(envmap_cube_dir(f, st));
                float omega = envmap_texel_solid_angle(2.0 * st - 1.0, s);
                total += omega;
                float c = dot(n, d);
                if (c > 0.0) sum += textureLod(envmap_incube, d, envmap_src_level).rgb * (c * omega);
            }
    o_color = vec4(envmap_finite(sum * (4.0 / total)), 1.0); // (4π/total)/π
}
