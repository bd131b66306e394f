// Resamples a lat-long or cube source into one face of a cube map: each output texel is the
// mean of K×K sub-samples, each read at the source mip level that matches its footprint (so the
// mean radiance is kept and a small bright sun is neither missed nor counted twice).
// ENVMAP_IN_CUBE: the source is a cube, else a lat-long. A permutation, not a uniform branch: on
// llvmpipe both sides of a branch run (under a mask), and the cube lookup a lat-long source never
// takes made the conversion 1.4× as long (256² faces from courtyard.exr: 103 → 72 ms).
#include "envmap_common.glsl"
#ifdef ENVMAP_IN_CUBE
uniform samplerCube envmap_incube;
#else
uniform sampler2D envmap_in2d;
#endif
uniform vec2 envmap_in_size;   // lat-long (w, h), or (face size, face size)
uniform int envmap_face;
uniform float envmap_size;     // output face size
uniform int envmap_subsamples; // K
layout(location = 0) out vec4 o_color;

void main() {
    float k = float(envmap_subsamples);
    vec3 sum = vec3(0.0);
    // do-whiles (K >= 1): llvmpipe ran a for loop's body once more after the last pass, every lane
    // masked, at full cost (25 lookups for 16)
    int j = 0;
    do {
        int i = 0;
        do {
            vec2 st = (floor(gl_FragCoord.xy) + (vec2(i, j) + 0.5) / k) / envmap_size;
            vec3 d = normalize(envmap_cube_dir(envmap_face, st));
            float omega = envmap_texel_solid_angle(2.0 * st - 1.0, envmap_size * k);
            vec3 c;
#ifdef ENVMAP_IN_CUBE
            float omega_src = envmap_texel_solid_angle(2.0 * st - 1.0, envmap_in_size.x);
            c = textureLod(envmap_incube, d, max(0.5 * log2(omega / omega_src), 0.0)).rgb;
#else
            vec2 uv = envmap_dir_latlong(d);
            float texel_v = ENVMAP_PI / envmap_in_size.y;
            float omega_src = (2.0 * ENVMAP_PI / envmap_in_size.x) * texel_v * max(sin(uv.y * ENVMAP_PI), 1e-6);
            // the area rule, capped by the v extent: near the poles a lat-long texel is thin
            // in u only, and a mip level wide in v would blur across latitudes
            float lod = min(0.5 * log2(omega / omega_src), log2(sqrt(omega) / texel_v));
            c = textureLod(envmap_in2d, uv, max(lod, 0.0)).rgb;
#endif
            sum += c;
        } while (++i < envmap_subsamples);
    } while (++j < envmap_subsamples);
    o_color = vec4(envmap_finite(sum / (k * k)), 1.0);
}
