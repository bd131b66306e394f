// The split-sum specular prefilter (Karis 2013): one face of one level of the specular chain,
// n = v = r. The GGX importance samples are the same for every texel in its own frame, so the
// C side (em_prefilter_ggx) computes them once per level: a table of (l in the local frame,
// source mip level), with samples below the horizon already dropped. Each sample's level comes
// from its PDF (Křivánek & Colbert 2008): Ω_s = 1/(N·pdf), Ω_p = 4π/(6 size²),
// lod = ½ log2(Ω_s/Ω_p) + bias. Weighted by n·l as in Karis' reference code.
#include "envmap_common.glsl"
uniform samplerCube envmap_incube;
uniform sampler2D envmap_in2d; // the sample tables of every level, 1024 samples per row
uniform int envmap_row;        // this level's first row
uniform int envmap_count;
uniform int envmap_face;
uniform float envmap_size;     // face size of the level being written
layout(location = 0) out vec4 o_color;

void main() {
    vec3 n = normalize(envmap_cube_dir(envmap_face, gl_FragCoord.xy / envmap_size));
    vec3 t, b;
    envmap_frame(n, t, b);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    int i = 0; // a do-while (count >= 1): a for loop ran its body once more, every lane masked
    do {
        vec4 s = texelFetch(envmap_in2d, ivec2(i & 1023, envmap_row + (i >> 10)), 0);
        sum += textureLod(envmap_incube, t * s.x + b * s.y + n * s.z, s.w).rgb * s.z;
        weight += s.z;
    } while (++i < envmap_count);
    o_color = vec4(envmap_finite(sum / max(weight, 1e-20)), 1.0);
}
