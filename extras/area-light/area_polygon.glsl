// area-light: pure polygon functions (no uniforms), shared by the light hook and the GLSL unit
// tests. The C twin of each is in ltc.h; the tests compare them.
//
// Lambert (1760): the vector irradiance of a polygon of unit radiance, seen from the origin,
//   Φ = ½ Σ_i γ_i (v_i × v_{i+1}) / |v_i × v_{i+1}|,  v_i unit directions to the vertices,
//   γ_i = the angle between v_i and v_{i+1}; ∫_P cosθ dω = Φ·n.
// Heitz, Dupuy, Hill, Neubelt (2016): the integral of a linearly transformed cosine over a
//   polygon is this form factor of the polygon transformed by M⁻¹ (over π), after clipping the
//   transformed polygon to the upper hemisphere.

const int AREA_LIGHT_MAX_VERTS = 64;

// A light polygon: a rectangle (width along ex, height along ey, centred at c) or a disk (ellipse
// of diameters w, h) drawn as a regular polygon of n vertices with the disk's area: the radius is
// scaled by √(2π / (N sin(2π/N))). Vertices are made on the fly (no arrays: llvmpipe spills
// them to memory).
struct AreaLightPolygon {
    vec3 c, ex, ey; // centre (relative to the shading point) and the half axes
    bool disk;
    int n;
};

AreaLightPolygon area_light_make_polygon(vec3 c, vec3 ex, vec3 ey, float w, float h, bool disk, int segments) {
    AreaLightPolygon p;
    p.disk = disk;
    p.n = disk ? clamp(segments, 3, AREA_LIGHT_MAX_VERTS) : 4;
    float k = disk ? sqrt(2.0 * SL_PI / (float(p.n) * sin(2.0 * SL_PI / float(p.n)))) : 1.0;
    p.c = c;
    p.ex = ex * (0.5 * w * k);
    p.ey = ey * (0.5 * h * k);
    return p;
}

// Vertex i (0..n-1, counter-clockwise about ex × ey): rectangle corners (−,−) (+,−) (+,+) (−,+).
vec3 area_light_vertex(AreaLightPolygon p, int i) {
    vec2 q;
    if (p.disk) {
        float a = 2.0 * SL_PI * float(i) / float(p.n);
        q = vec2(cos(a), sin(a));
    } else {
        q = vec2(i == 1 || i == 2 ? 1.0 : -1.0, i >= 2 ? 1.0 : -1.0);
    }
    return p.c + p.ex * q.x + p.ey * q.y;
}

// One edge's term of Lambert's formula for unit a, b: γ (a × b)/|a × b|, with γ = atan(|a×b|, a·b)
// (not acos(a·b), which loses precision for short edges).
vec3 area_light_edge(vec3 a, vec3 b) {
    vec3 c = cross(a, b);
    float s = length(c);
    return s > 0.0 ? c * (atan(s, dot(a, b)) / s) : vec3(0.0);
}

void area_light_emit(vec3 q, inout vec3 first, inout vec3 last, inout int count, inout vec3 sum) {
    float len = length(q);
    if (!(len > 0.0)) return; // a vertex at the shading point subtends nothing
    q /= len;
    if (count == 0) first = q;
    else sum += area_light_edge(last, q);
    last = q;
    count++;
}

// Vector form factor ×π (the vector irradiance of unit radiance) of the polygon (relative to the
// shading point) after the linear map m (world → local frame, z = normal, possibly followed by an
// LTC's M⁻¹), clipped to z >= 0 (Sutherland–Hodgman, streamed: the clipped polygon's edges are
// summed as they are produced). Oriented so that z >= 0; z = ∫ cos dω.
vec3 area_light_vector_irradiance(AreaLightPolygon p, mat3 m) {
    vec3 first = vec3(0.0), last = vec3(0.0), sum = vec3(0.0);
    int count = 0;
    vec3 v0 = m * area_light_vertex(p, 0), a = v0;
    // a do-while (n >= 3): llvmpipe runs a for loop's body once more, every lane masked, after
    // its last iteration (a rectangle's 4 edges cost 5)
    int i = 0;
    do {
        vec3 b = i + 1 < p.n ? m * area_light_vertex(p, i + 1) : v0;
        bool ain = a.z >= 0.0, bin = b.z >= 0.0;
        if (ain) area_light_emit(a, first, last, count, sum);
        if (ain != bin) {
            vec3 q = mix(a, b, a.z / (a.z - b.z));
            q.z = 0.0;
            area_light_emit(q, first, last, count, sum);
        }
        a = b;
    } while (++i < p.n);
    if (count < 3) return vec3(0.0);
    sum += area_light_edge(last, first);
    return 0.5 * (sum.z < 0.0 ? -sum : sum);
}

// A frame around the normal n with x along the tangent part of v (LTC tables are fitted in it):
// rows of the returned matrix are (t1, t2, n), so m * world = local.
mat3 area_light_frame(vec3 n, vec3 v) {
    vec3 t1 = v - n * dot(n, v);
    float l = length(t1);
    if (l < 1e-6) t1 = abs(n.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n);
    t1 = normalize(t1);
    vec3 t2 = cross(n, t1);
    return transpose(mat3(t1, t2, n));
}

// The light's in-plane axes: ex along `axis` made orthogonal to the unit normal nl (any
// perpendicular when axis is parallel to it), ey = nl × ex.
void area_light_axes(vec3 nl, vec3 axis, out vec3 ex, out vec3 ey) {
    ex = axis - nl * dot(axis, nl);
    if (length(ex) < 1e-6) ex = abs(nl.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), nl) : cross(vec3(1.0, 0.0, 0.0), nl);
    ex = normalize(ex);
    ey = cross(nl, ex);
}

// The vector irradiance (×π form factor, see above) of a rectangle or disk light of centre c
// (relative to the shading point), normal nl, width axis `axis`, after the map m.
vec3 area_light_polygon_irradiance(vec3 c, vec3 nl, vec3 axis, float w, float h, bool disk, int segments, mat3 m) {
    vec3 ex, ey;
    area_light_axes(normalize(nl), axis, ex, ey);
    return area_light_vector_irradiance(area_light_make_polygon(c, ex, ey, w, h, disk, segments), m);
}
