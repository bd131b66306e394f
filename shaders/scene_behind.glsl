// The opaque scene behind a surface (ABI 1.17, shader.h "The scene behind"), in the programs of
// materials with a SCENE_BEHIND hook: the core's forward-behind pass copies "color" after every
// opaque pass into this mip chain (level 0 the viewport's pixels, each level a 2×2 box filter of
// the one below) and binds it here before drawing those materials.
layout(binding = 65) uniform sampler2D sl_scene_behind; // host.h: SL_TEXTURE_UNIT_CORE + 1
uniform float sl_scene_behind_levels;                    // its mip count − 1: log2 of its larger side

// Where the world point p lands in sl_scene_behind (and on the screen): [0, 1]², through the
// frame's sl_view_proj (jitter included, as the capture was drawn). Outside [0, 1]² off screen.
vec2 sl_screen_uv(vec3 p) {
    vec4 c = sl_view_proj * vec4(p, 1.0);
    return c.xy / c.w * 0.5 + 0.5;
}
