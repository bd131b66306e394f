// One level of a cube's mip chain from the level above: each texel is the solid-angle-weighted
// mean of its 2×2 children (glGenerateMipmap weighs them equally, which moves radiance towards
// face corners, where texels are small, and biases coarse levels' means by percents).
#include "envmap_common.glsl"
uniform samplerCube envmap_incube;
uniform float envmap_src_level;
uniform int envmap_face;
uniform float envmap_size; // face size of the level written
layout(location = 0) out vec4 o_color;

void main() {
    vec2 p = floor(gl_FragCoord.xy);
    float fine = 2.0 * envmap_size;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            vec2 st = (2.0 * p + vec2(i, j) + 0.5) / fine;
            float o = envmap_texel_solid_angle_exact(2.0 * p + vec2(i, j), fine);
            // bilinear at a texel centre reads exactly that texel
            sum += textureLod(envmap_incube, envmap_cube_dir(envmap_face, st), envmap_src_level).rgb * o;
            weight += o;
        }
    o_color = vec4(sum / weight, 1.0);
}
