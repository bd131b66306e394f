// voronoi-tiles: SURFACE hook for materials carrying the key voronoi_tiles (voronoi_tiles.c).
// Tile colour and gloss from the nearest seed's hash, the seam's normal and ambient occlusion
// from its distance (voronoi_cells.glsl). voronoi_tiles.samples² sub-pixel positions inside the
// pixel's footprint in uv (screen derivatives) are averaged (normal, AO, colour, α): the seam's
// normal changes over a fraction of a cell, so one sample aliases at a distance.
#include "voronoi_cells.glsl"

void voronoi_tiles_sample(vec2 x, out vec3 n_t, out float ao, out vec3 color, out float alpha) {
    ivec2 c1;
    vec3 r = voronoi_tiles_search(x, c1);
    n_t = voronoi_tiles_normal(r.x, r.yz);
    ao = 0.5 + 0.5 * n_t.z;
    uvec3 h = voronoi_tiles_hash(c1);
    float tc = float(h.z & 65535u) * (1.0 / 65535.0), tg = float(h.z >> 16u) * (1.0 / 65535.0);
    color = mix(voronoi_tiles_color_a, voronoi_tiles_color_b, tc);
    alpha = mix(voronoi_tiles_alpha_min, voronoi_tiles_alpha_max, tg);
}

void voronoi_tiles_surface(inout SlSurface s) {
    vec2 x = s.uv * voronoi_tiles_scale;
    vec2 dx = dFdx(x), dy = dFdy(x);
    int k = max(voronoi_tiles_samples, 1);
    vec3 n = vec3(0.0), col = vec3(0.0);
    float ao = 0.0, alpha = 0.0;
    // do-whiles (k >= 1): llvmpipe runs a for loop's body once more, every lane masked, after
    // its last iteration (the test is at the top), and nested ones multiply: k = 1 evaluated
    // the Voronoi search 4 times (docs/design-notes.md, "Loops on llvmpipe")
    int j = 0;
    do {
        int i = 0;
        do {
            vec2 o = (vec2(i, j) + 0.5) / float(k) - 0.5; // stratified over the pixel footprint
            vec3 n1, c1;
            float a1, al1;
            voronoi_tiles_sample(k == 1 ? x : x + o.x * dx + o.y * dy, n1, a1, c1, al1);
            n += n1, ao += a1, col += c1, alpha += al1;
        } while (++i < k);
    } while (++j < k);
    float inv = 1.0 / float(k * k);
    vec3 nt = n * inv;
    float len = length(nt);
    nt = len > 1e-6 ? nt / len : vec3(0.0, 0.0, 1.0);
    // uv axes → the surface's tangent frame (u along s.tangent, v along s.bitangent)
    s.normal = normalize(nt.x * s.tangent + nt.y * s.bitangent + nt.z * s.normal);
    s.ao *= ao * inv;
    s.base_color *= col * inv;
    s.alpha = alpha * inv;
}

// debug view: seam distance in cells (r), the analytic AO (g), the nearest cell's colour hash (b)
vec3 voronoi_tiles_view(SlSurface s) {
    ivec2 c1;
    vec3 r = voronoi_tiles_search(s.uv * voronoi_tiles_scale, c1);
    return vec3(r.x, voronoi_tiles_ao(r.x), float(voronoi_tiles_hash(c1).z & 65535u) * (1.0 / 65535.0));
}
