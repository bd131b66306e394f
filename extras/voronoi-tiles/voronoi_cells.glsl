// voronoi-tiles: the cell search and the seam profile, as pure functions (tests evaluate them).
// Cell space: x = uv · voronoi_tiles_scale; cell c = floor(x) holds one seed
//   s(c) = c + 0.5 + jitter · (h.xy / 2³² − 0.5),  h = pcg3d(c, seed)
// pcg3d: Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020.
// The nearest seed s1 gives the tile (colour, gloss from its hash); the seam distance is the
// distance from x to the nearer of the bisectors between s1 and the second and third nearest
// seeds s2, s3:  d_k = ((s1 + s_k)/2 − x)·e_k, e_k = (s_k − s1)/|s_k − s1|.
// Search (VORONOI_TILES_SEARCH): 3x3 cells (9 seeds), radius (seeds within √3.25 cells of x,
// from the 5x5 block: the assignment's rule), exact (7x7: every seed that can be among the three
// nearest, since those lie within 2√2 of x and a seed outside the 7x7 block is ≥ 3 away).

uvec3 voronoi_tiles_pcg3d(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    return v;
}

uvec3 voronoi_tiles_hash(ivec2 c) { return voronoi_tiles_pcg3d(uvec3(uvec2(c), uint(voronoi_tiles_seed))); }

vec2 voronoi_tiles_seed_of(ivec2 c) {
    uvec3 h = voronoi_tiles_hash(c);
    return vec2(c) + 0.5 + voronoi_tiles_jitter * (vec2(h.xy >> 8u) * (1.0 / 16777216.0) - 0.5);
}

#if VORONOI_TILES_SEARCH == VORONOI_TILES_SEARCH_3X3
const int VORONOI_TILES_R = 1;
#elif VORONOI_TILES_SEARCH == VORONOI_TILES_SEARCH_RADIUS
const int VORONOI_TILES_R = 2;
#else
const int VORONOI_TILES_R = 3;
#endif

// The cell search at x (cell space). Returns the seam distance d (cells) in .x and the unit
// direction e from s1 toward the seam's other seed in .yz (∇d = −e); cell1 = the nearest seed's cell.
vec3 voronoi_tiles_search(vec2 x, out ivec2 cell1) {
    ivec2 c0 = ivec2(floor(x));
    float d1 = 1e30, d2 = 1e30, d3 = 1e30;
    vec2 s1 = vec2(0.0), s2 = vec2(0.0), s3 = vec2(0.0);
    cell1 = c0;
    for (int j = -VORONOI_TILES_R; j <= VORONOI_TILES_R; j++)
        for (int i = -VORONOI_TILES_R; i <= VORONOI_TILES_R; i++) {
            ivec2 c = c0 + ivec2(i, j);
            vec2 s = voronoi_tiles_seed_of(c);
            vec2 dv = s - x;
            float dd = dot(dv, dv);
#if VORONOI_TILES_SEARCH == VORONOI_TILES_SEARCH_RADIUS
            if (dd > 3.25) continue; // the assignment's search radius √3.25 cells
#endif
            if (dd < d1) { d3 = d2; s3 = s2; d2 = d1; s2 = s1; d1 = dd; s1 = s; cell1 = c; }
            else if (dd < d2) { d3 = d2; s3 = s2; d2 = dd; s2 = s; }
            else if (dd < d3) { d3 = dd; s3 = s; }
        }
    float best = 1e30;
    vec2 e = vec2(1.0, 0.0);
    if (d2 < 1e29) {
        vec2 e2 = normalize(s2 - s1);
        best = dot(0.5 * (s1 + s2) - x, e2), e = e2;
    }
    if (d3 < 1e29) {
        vec2 e3 = normalize(s3 - s1);
        float b3 = dot(0.5 * (s1 + s3) - x, e3);
        if (b3 < best) best = b3, e = e3;
    }
    return vec3(max(best, 0.0), e);
}

// Seam profile: the tile's edge is a quarter circle of radius w = half the seam width, from the
// tile top (d ≥ w: height w, normal up) down to the base at the bisector (d = 0: a vertical
// wall). With s = (w − d)/w in [0, 1]: tangent-space normal (s·e, √(1 − s²)) (tilting toward
// the bisector) and normalised height √(1 − s²) = n.z.
// Ambient occlusion (analytic, the assignment's blend): 1 in the open (tile top), 0.5 against a
// vertical wall (the cosine-weighted sky a point at the foot of an infinite wall sees):
//   ao = 0.5 + 0.5 · height = 0.5 + 0.5 · n.z.
vec3 voronoi_tiles_normal(float d, vec2 e) {
    float w = 0.5 * voronoi_tiles_seam_width;
    if (w <= 0.0 || d >= w) return vec3(0.0, 0.0, 1.0);
    float s = (w - d) / w;
    return vec3(s * e, sqrt(max(0.0, 1.0 - s * s)));
}
float voronoi_tiles_ao(float d) { return 0.5 + 0.5 * voronoi_tiles_normal(d, vec2(1.0, 0.0)).z; }

// conveniences (debug view, tests)
float voronoi_tiles_seam_distance(vec2 x) { ivec2 c; return voronoi_tiles_search(x, c).x; }
vec2 voronoi_tiles_cell_of(vec2 x) { ivec2 c; voronoi_tiles_search(x, c); return vec2(c); }
