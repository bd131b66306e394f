// many-lights: the light loop of the forward programs (LIGHT_LOOP hook, ABI 1.7) and the
// "many-lights-count" debug view. The lights stay in the core's storage buffer sl_lights; this
// plugin adds three (bindings 3-5) filled by its C side every frame (ml_cull.h):
//   many_lights_r2[i]     range² of light i (ε cut-off, README "Range"); < 0: no range (directional,
//                         area and other types: always evaluated, listed first in many_lights_index)
//   many_lights_cells[c]  (first, count) of cell c's list in many_lights_index
//   many_lights_index[]   [0, many_lights_global): the lights without range; then the cell lists,
//                         each in ascending light order (the brute-force loop's order)
layout(std430, binding = 3) readonly buffer ManyLightsRange { float many_lights_r2[]; };
layout(std430, binding = 4) readonly buffer ManyLightsCells { uvec2 many_lights_cells[]; };
layout(std430, binding = 5) readonly buffer ManyLightsIndex { uint many_lights_index[]; };
uniform int many_lights_mode;    // 0: no direct light here (deferred methods' forward pass), 1: every
                                 // light with the cut-off, 2: froxel lists, 3: tile lists
uniform int many_lights_global;  // lights without range at the start of many_lights_index
uniform int many_lights_count;   // lights in sl_lights
uniform ivec2 many_lights_grid;  // cells along x, y
uniform ivec2 many_lights_grid_zt; // cells along z (slices), tile size in pixels
uniform vec2 many_lights_slices; // froxels: near distance, S / log(far / near)
uniform int many_lights_use_prepass;   // froxels: skip fragments behind the depth pre-pass
uniform sampler2D many_lights_prepass_depth;

int many_lights_cell(SlSurface s) {
    ivec2 t = min(ivec2(gl_FragCoord.xy) / many_lights_grid_zt.y, many_lights_grid - 1);
    int k = 0;
    if (many_lights_mode == 2) {
        float d = -(sl_view * vec4(s.position, 1.0)).z;
        k = clamp(int(floor(log(max(d, 1e-30) / many_lights_slices.x) * many_lights_slices.y)), 0,
                  many_lights_grid_zt.x - 1);
    }
    return (k * many_lights_grid.y + t.y) * many_lights_grid.x + t.x;
}

// The cut-off, the same in every method: inside the range the light is exact, beyond it nothing.
bool many_lights_in_range(int i, SlSurface s) {
    vec3 d = sl_lights[i].position.xyz - s.position;
    return dot(d, d) < many_lights_r2[i];
}

vec3 many_lights_loop(SlSurface s) {
    vec3 Lo = vec3(0.0);
    if (many_lights_mode == 0) return Lo;
    // depth pre-pass: a fragment behind the nearest surface is overwritten anyway
    if (many_lights_use_prepass != 0 &&
        gl_FragCoord.z > texelFetch(many_lights_prepass_depth, ivec2(gl_FragCoord.xy), 0).r + 1e-6) return Lo;
    for (int k = 0; k < many_lights_global; ++k) Lo += sl_light_radiance(int(many_lights_index[k]), s);
    if (many_lights_mode == 1) {
        for (int i = 0; i < many_lights_count; ++i)
            if (many_lights_r2[i] >= 0.0 && many_lights_in_range(i, s)) Lo += sl_light_radiance(i, s);
    } else {
        uvec2 c = many_lights_cells[many_lights_cell(s)];
        for (uint k = c.x; k < c.x + c.y; ++k) {
            int i = int(many_lights_index[k]);
            if (many_lights_in_range(i, s)) Lo += sl_light_radiance(i, s);
        }
    }
    return Lo;
}

// Debug view: (lights in this pixel's list, lights within range here, ranged lights in the scene)
vec3 many_lights_count_view(SlSurface s) {
    int inrange = 0, listed = 0, ranged = 0;
    for (int i = 0; i < many_lights_count; ++i)
        if (many_lights_r2[i] >= 0.0) {
            ranged++;
            if (many_lights_in_range(i, s)) inrange++;
        }
    if (many_lights_mode >= 2) listed = int(many_lights_cells[many_lights_cell(s)].y);
    else listed = ranged;
    return vec3(float(listed), float(inrange), float(ranged));
}
