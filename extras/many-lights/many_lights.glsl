// many-lights: the light loop of the forward programs (LIGHT_LOOP hook, ABI 1.7) and the
// "many-lights-count" debug view. The lights stay in the core's storage buffer sl_lights; this
// plugin adds three (bindings 3-5) filled by its C side every frame (many_lights.c, ml_cull.h):
//   many_lights_index[]   [0, many_lights_global): the lights without range (directional, area and
//                         other types: always evaluated); then each cell's list, then the list of
//                         every light with a range (cell many_lights_all); each list in ascending
//                         light order (the brute-force loop's order)
//   many_lights_sphere[k] beside many_lights_index[k]: its light's (world position, range²) (ε
//                         cut-off, README "Range"), so the range test reads one vec4 per entry
//   many_lights_cells[c]  (first, count) of cell c's list in many_lights_index, and the view
//                         distances [lo, hi] (float bits) it was culled for: a fragment outside
//                         them walks the list of every ranged light instead
layout(std430, binding = 3) readonly buffer ManyLightsSpheres { vec4 many_lights_sphere[]; };
layout(std430, binding = 4) readonly buffer ManyLightsCells { uvec4 many_lights_cells[]; };
layout(std430, binding = 5) readonly buffer ManyLightsIndex { uint many_lights_index[]; };
uniform int many_lights_mode;    // 0: no direct light here (deferred methods' forward pass), 1: every
                                 // light with the cut-off, 2: froxel lists, 3: tile lists
uniform int many_lights_global;  // lights without range at the start of many_lights_index
uniform int many_lights_all;     // the cell listing every light with a range (mode 1, count view)
uniform ivec2 many_lights_grid;  // cells along x, y
uniform ivec2 many_lights_grid_zt; // cells along z (slices), tile size in pixels
uniform vec2 many_lights_slices; // froxels: near distance, S / log(far / near)
uniform int many_lights_use_prepass;   // froxels: skip fragments behind the depth pre-pass
uniform sampler2D many_lights_prepass_depth;

// the list this fragment walks: its froxel's or tile's, or every ranged light (brute force,
// deferred; a fragment outside the distances its cell was culled for)
uvec2 many_lights_list(SlSurface s) {
    uvec4 all = many_lights_cells[many_lights_all];
    if (many_lights_mode < 2) return all.xy;
    ivec2 t = min(ivec2(gl_FragCoord.xy) / many_lights_grid_zt.y, many_lights_grid - 1);
    float d = -(sl_view * vec4(s.position, 1.0)).z;
    int k = 0;
    if (many_lights_mode == 2)
        k = clamp(int(floor(log(max(d, 1e-30) / many_lights_slices.x) * many_lights_slices.y)), 0,
                  many_lights_grid_zt.x - 1);
    uvec4 c = many_lights_cells[(k * many_lights_grid.y + t.y) * many_lights_grid.x + t.x];
    return d >= uintBitsToFloat(c.z) && d <= uintBitsToFloat(c.w) ? c.xy : all.xy;
}

// The cut-off, the same in every method: inside the range the light is exact, beyond it nothing.
bool many_lights_in_range(uint k, SlSurface s) {
    vec4 b = many_lights_sphere[k];
    vec3 d = b.xyz - s.position;
    return dot(d, d) < b.w;
}

vec3 many_lights_loop(SlSurface s) {
    vec3 Lo = vec3(0.0);
    if (many_lights_mode == 0) return Lo;
    // depth pre-pass: a fragment behind the nearest surface is overwritten anyway
    if (many_lights_use_prepass != 0 &&
        gl_FragCoord.z > texelFetch(many_lights_prepass_depth, ivec2(gl_FragCoord.xy), 0).r + 1e-6) return Lo;
    for (int k = 0; k < many_lights_global; ++k) Lo += sl_light_radiance(int(many_lights_index[k]), s);
    // Compacted loop: the list is walked in chunks of 32 entries; a first pass over a chunk makes
    // a bit mask of the entries within range (one vec4 read and a dot product each, the same trip
    // count for every invocation sharing the list), then sl_light_radiance runs once per set bit,
    // lowest first. A SIMD machine that runs both sides of a branch under a lane mask (llvmpipe)
    // would otherwise pay sl_light_radiance for every listed light; here it pays, per chunk, for
    // the largest in-range count among the lanes. (The earlier form, each invocation skipping ahead
    // to its next light in range inside a nested loop, measured 7 % slower at 1024 lights: its
    // inner loop ran as long as the largest gap among the lanes, once per evaluated light.) Same
    // lights in the same ascending order: the sum is bit for bit the simple loop's.
    uvec2 c = many_lights_list(s);
    uint end = c.x + c.y;
    for (uint base = c.x; base < end; base += 32u) {
        uint n = min(32u, end - base), mask = 0u;
        for (uint j = 0u; j < n; ++j)
            if (many_lights_in_range(base + j, s)) mask |= 1u << j;
        while (mask != 0u) {
            int j = findLSB(mask);
            mask &= mask - 1u;
            Lo += sl_light_radiance(int(many_lights_index[base + uint(j)]), s);
        }
    }
    return Lo;
}

// Debug view: (lights in this pixel's list, lights within range here, lights with a range)
vec3 many_lights_count_view(SlSurface s) {
    uvec2 all = many_lights_cells[many_lights_all].xy;
    int inrange = 0;
    for (uint k = all.x; k < all.x + all.y; ++k)
        if (many_lights_in_range(k, s)) inrange++;
    return vec3(float(many_lights_list(s).y), float(inrange), float(all.y));
}
