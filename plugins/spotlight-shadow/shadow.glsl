// spotlight-shadow: the SHADOW hook (sdk shader.h): visibility of light sl_lights[i] at a surface,
// from the shadow maps the "shadow-maps" pass rendered (spotlight_shadow.c). The light loop
// multiplies E by it. Filters are permutations of spotlight-shadow.filter.
//
// Table (RGBA32F, texelFetch): row i < spotlight_shadow_view_base is light sl_lights[i]:
//   texel 0 (first view, view count: 0 none / 1 / 6 cube faces, -, -), texel 1 (position, -)
// row spotlight_shadow_view_base + v is view v:
//   texels 0..3 world → clip matrix columns, 4 (layer, near, far, texel size at depth 1 or
//   absolute), 5 (eye position, 1 = orthographic), 6 (view axis, light size: radius in m or
//   tan of the angular radius), 7 (provided views: split_near, split_far, blend, -).
// A light row's texel 0 .w = 1: its views come from a view provider (cascades, picked by
// camera depth).
// Biases, all in texels of the map at the receiver (world size tw): the lookup point moves
// normal_offset·tw along the normal and (bias_constant + bias_slope·tanθ)·tw towards the
// light; with receiver_plane every tap compares against the receiver's tangent plane at that
// tap (computed from the geometric normal, exact for both projections) instead of one depth.
// Beyond tanθ = spotlight_shadow_tan_ungated both slope terms are gated (see the view's
// visibility below).

uniform sampler2DArrayShadow spotlight_shadow_cmp_map; // hardware comparison, bilinear
uniform sampler2DArray spotlight_shadow_depth_map;     // raw depths, nearest
uniform sampler2D spotlight_shadow_table;
uniform int spotlight_shadow_view_base;
uniform float spotlight_shadow_texels;                 // map size in texels
#define spotlight_shadow_pcf_step float(SPOTLIGHT_SHADOW_PCF_STEP) // a permutation (the gathered PCF)
// Up to this tanθ (84°) the slope terms apply in full; beyond it only where the receiver point is
// lit without them (the gate in spotlight_shadow_view_visibility).
const float spotlight_shadow_tan_ungated = 10.0;

// Progressive Poisson disk (Mitchell's best candidate): every prefix is well spread.
const vec2 spotlight_shadow_disk[64] = vec2[64](
    vec2(-0.35233, -0.69830),
    vec2(0.63856, 0.72797),
    vec2(-0.85855, 0.48178),
    vec2(0.84015, -0.48597),
    vec2(-0.15986, 0.16525),
    vec2(-0.17930, 0.89595),
    vec2(-0.87597, -0.22423),
    vec2(0.96043, 0.12731),
    vec2(0.31306, -0.89989),
    vec2(0.37904, -0.11014),
    vec2(0.27959, 0.38242),
    vec2(-0.03407, -0.32522),
    vec2(-0.58788, 0.10969),
    vec2(0.27315, 0.93690),
    vec2(-0.46696, 0.58224),
    vec2(-0.48487, -0.28948),
    vec2(0.43499, -0.51252),
    vec2(-0.77742, -0.60007),
    vec2(-0.08535, -0.97346),
    vec2(0.64223, 0.32728),
    vec2(-0.95422, 0.13443),
    vec2(-0.09899, 0.53971),
    vec2(0.74879, -0.13599),
    vec2(0.65515, -0.74998),
    vec2(0.09207, -0.63864),
    vec2(0.12500, 0.08432),
    vec2(0.17821, 0.66415),
    vec2(-0.50846, 0.85992),
    vec2(0.82599, 0.53684),
    vec2(-0.22910, -0.10814),
    vec2(-0.42432, 0.31445),
    vec2(0.51765, 0.09896),
    vec2(0.23673, -0.33545),
    vec2(-0.70129, 0.68934),
    vec2(-0.59948, -0.79074),
    vec2(-0.14353, -0.55319),
    vec2(0.42232, 0.58651),
    vec2(-0.53189, -0.53136),
    vec2(0.03955, 0.32976),
    vec2(0.95812, -0.26764),
    vec2(0.59451, -0.32122),
    vec2(-0.64013, -0.12095),
    vec2(-0.63898, 0.43976),
    vec2(0.04394, 0.99013),
    vec2(-0.25427, -0.34506),
    vec2(-0.70809, -0.37232),
    vec2(-0.30553, -0.92105),
    vec2(0.90902, 0.33683),
    vec2(0.09691, -0.14444),
    vec2(-0.36358, 0.08065),
    vec2(-0.77974, 0.26811),
    vec2(-0.28078, 0.70445),
    vec2(0.08599, -0.85149),
    vec2(0.73428, 0.09728),
    vec2(-0.15518, -0.77845),
    vec2(0.43607, -0.71934),
    vec2(-0.00984, 0.76343),
    vec2(-0.21633, 0.36849),
    vec2(0.31626, 0.17432),
    vec2(0.46320, 0.83862),
    vec2(-0.80321, -0.00651),
    vec2(0.64379, -0.52083),
    vec2(0.95788, -0.06834),
    vec2(-0.89303, -0.44619)
);

struct SpotlightShadowView {
    mat4 vp;
    float layer, near, far, texel;
    vec3 pos;
    float ortho;
    vec3 axis;
    float size;
};

SpotlightShadowView spotlight_shadow_view(int v) {
    int r = spotlight_shadow_view_base + v;
    SpotlightShadowView V;
    V.vp = mat4(texelFetch(spotlight_shadow_table, ivec2(0, r), 0), texelFetch(spotlight_shadow_table, ivec2(1, r), 0),
                texelFetch(spotlight_shadow_table, ivec2(2, r), 0), texelFetch(spotlight_shadow_table, ivec2(3, r), 0));
    vec4 a = texelFetch(spotlight_shadow_table, ivec2(4, r), 0);
    vec4 b = texelFetch(spotlight_shadow_table, ivec2(5, r), 0);
    vec4 c = texelFetch(spotlight_shadow_table, ivec2(6, r), 0);
    V.layer = a.x; V.near = a.y; V.far = a.z; V.texel = a.w;
    V.pos = b.xyz; V.ortho = b.w;
    V.axis = c.xyz; V.size = c.w;
    return V;
}

// Map coordinates (u, v, window depth) of a clip-space point; w <= 0 behind a perspective light.
vec4 spotlight_shadow_window(vec4 c) {
    float w = c.w;
    return vec4(c.xyz / (abs(w) > 1e-20 ? w : 1e-20) * 0.5 + 0.5, w);
}

// Map coordinates of a world point.
vec4 spotlight_shadow_project(SpotlightShadowView V, vec3 p) { return spotlight_shadow_window(V.vp * vec4(p, 1.0)); }

// Behind the light, outside the map or in front of its near plane: nothing can shadow it.
bool spotlight_shadow_outside(vec4 c) {
    return c.w <= 0.0 || any(lessThan(c.xyz, vec3(0.0))) || any(greaterThan(c.xyz, vec3(1.0)));
}

// Window depth → metres along the view axis (sdk ext/shadow_maps.h).
float spotlight_shadow_linear_depth(SpotlightShadowView V, float d) {
    if (V.ortho > 0.5) return V.near + d * (V.far - V.near);
    return 2.0 * V.near * V.far / (V.far + V.near - (2.0 * d - 1.0) * (V.far - V.near));
}

// The receiver plane extrapolated past the end of the geometry can pass the far plane: a
// reference of 1 still compares lit against the cleared depth (32F references are not clamped).
float spotlight_shadow_compare(float layer, vec3 sc, vec2 o, vec2 g) {
    return texture(spotlight_shadow_cmp_map, vec4(sc.xy + o / spotlight_shadow_texels, layer, min(sc.z + dot(g, o), 1.0)));
}

mat2 spotlight_shadow_rotation() {
    float a = 0.0;
    if (spotlight_shadow_poisson_rotate) // interleaved gradient noise (Jimenez 2014)
        a = 6.28318531 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    float c = cos(a), s = sin(a);
    return mat2(c, s, -s, c);
}

float spotlight_shadow_poisson(float layer, vec3 sc, vec2 g, float radius, int taps) {
    mat2 R = spotlight_shadow_rotation();
    float sum = 0.0;
    for (int k = 0; k < taps; ++k) sum += spotlight_shadow_compare(layer, sc, R * spotlight_shadow_disk[k] * radius, g);
    return sum / float(taps);
}

#if SPOTLIGHT_SHADOW_SHADOWS
// Visibility of s through view v (bias, then the filter).
float spotlight_shadow_view_visibility(int v, SlSurface s, vec3 l) {
    SpotlightShadowView V = spotlight_shadow_view(v);
    vec3 n = s.geometric_normal;
    if (dot(n, l) < 0.0) n = -n; // offsets go to the lit side
    float cos_t = clamp(dot(n, l), 0.0, 1.0);
    float sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
    float tan_t = min(sin_t / max(cos_t, 1e-4), 1000.0); // 89.94°: beyond, the light is edge-on
    float z_r = dot(s.position - V.pos, V.axis);
    float tw = V.texel * (V.ortho > 0.5 ? 1.0 : max(z_r, 1e-4));
    float tan_near = min(tan_t, spotlight_shadow_tan_ungated);
    vec3 pb = s.position + n * (spotlight_shadow_normal_offset * tw) +
              l * (tw * (spotlight_shadow_bias_constant + spotlight_shadow_bias_slope * tan_near));
    vec4 clip_near = V.vp * vec4(pb, 1.0), c = spotlight_shadow_window(clip_near);
    if (spotlight_shadow_outside(c)) return 1.0;
    float layer = V.layer, S = spotlight_shadow_texels;
    // The receiver plane at this point, before the gate's share of the slope bias: the same plane
    // up to tanθ = 10, its slope at a slightly larger depth beyond (computed here, the filter's
    // texels are not held through it: cheaper on llvmpipe).
    vec2 g = vec2(0.0); // receiver plane: window depth change per texel of offset
    float dl = 0.0;     // window depth change per texel width along l
    if (spotlight_shadow_receiver_plane) {
        vec3 t1 = normalize(abs(n.y) < 0.9 ? cross(n, vec3(0.0, 1.0, 0.0)) : cross(n, vec3(1.0, 0.0, 0.0)));
        vec3 t2 = cross(n, t1);
        vec3 a = spotlight_shadow_project(V, pb + t1 * tw).xyz - c.xyz;
        vec3 b = spotlight_shadow_project(V, pb + t2 * tw).xyz - c.xyz;
        a.xy *= S;
        b.xy *= S;
        float det = a.x * b.y - a.y * b.x;
        if (abs(det) > 1e-3) g = vec2(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det;
        dl = abs(c.z - spotlight_shadow_project(V, pb + l * tw).z);
    }
    // the rest of the slope bias, in clip space (added below as far as the gate lets it)
    vec4 clip_rest = V.vp * vec4(l * (tw * spotlight_shadow_bias_slope * (tan_t - tan_near)), 0.0);
    // The gate. At grazing incidence the slope bias and the receiver plane reach tanθ texel widths
    // towards the light per texel of offset (up to 1000): exact on a plane, but on a curved
    // receiver (a cheek) they reach past an occluder of the point itself (the nose), and lit
    // triangles appear in its shadow. So beyond tanθ = 10 they grow only as far as the point with
    // the terms capped at 10 is lit (its bilinear comparison, free where the filter gathers those
    // texels anyway). On planes and convex receivers that point is lit at any angle: the normal
    // offset puts it a texel off the surface, in front of every texel the comparison reads (the
    // texels diagonal to it carry under 9% of the weight). Where it is shadowed the terms stay
    // capped: the taps reach (10 + 10 per texel of kernel radius) texel widths past the receiver.
    // Moving the point along l keeps its texel (the map's rays meet at the light), so every filter
    // reads at c.xy (for the reference's maps, rendered from points on the light, the bias then
    // acts in depth only).
    float lit0;
#if SPOTLIGHT_SHADOW_FILTER == SPOTLIGHT_SHADOW_FILTER_HARD
    vec2 texel = clamp(floor(c.xy * S), vec2(0.0), vec2(S - 1.0));
    float stored = texelFetch(spotlight_shadow_depth_map, ivec3(texel, int(layer + 0.5)), 0).r;
    lit0 = c.z <= stored ? 1.0 : 0.0;
#elif SPOTLIGHT_SHADOW_FILTER == SPOTLIGHT_SHADOW_FILTER_PCF
    const int K = SPOTLIGHT_SHADOW_PCF_SIZE;
    const bool gathered = float(SPOTLIGHT_SHADOW_PCF_STEP) == 1.0; // a constant: one side is compiled
    float h = 0.5 * float(K - 1);
    // Taps one texel apart (the default): tap (x, y) is the bilinear comparison of the 2×2
    // texels from b + (x, y), all with the same fractions f, so the K×K taps read (K+1)² texels.
    // They are fetched once each, 2×2 at a time (textureGather, ⌈(K+1)/2⌉² fetches instead of
    // K² filtered ones: 9 for 25 at K = 5, the fetches being most of the cost on llvmpipe),
    // and every texel is compared against the reference of each tap that reads it, weighted
    // as the hardware's bilinear comparison weights it: the same filter, per-tap receiver
    // plane included. For odd K the middle tap is the gate's comparison.
    const int M = K + 1, G = (K + 2) / 2;
    vec2 q = c.xy * S - h - 0.5;
    vec2 b = floor(q), f = q - b;
    vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    float d[M * M];
    if (gathered)
        for (int gy = 0; gy < G; ++gy)
            for (int gx = 0; gx < G; ++gx) {
                // at the corner shared by texels b + (2gx, 2gy) .. + (1, 1): x = (i0, j1), y = (i1, j1),
                // z = (i1, j0), w = (i0, j0); clamp-to-edge as the comparison sampler
                vec4 t = textureGather(spotlight_shadow_depth_map, vec3((b + vec2(2 * gx, 2 * gy) + 1.0) / S, layer));
                int i = 2 * gy * M + 2 * gx;
                if (2 * gx < M && 2 * gy < M) d[i] = t.w;
                if (2 * gx + 1 < M && 2 * gy < M) d[i + 1] = t.z;
                if (2 * gx < M && 2 * gy + 1 < M) d[i + M] = t.x;
                if (2 * gx + 1 < M && 2 * gy + 1 < M) d[i + M + 1] = t.y;
            }
    if (gathered && K % 2 == 1) {
        int i = (K / 2) * (M + 1);
        lit0 = dot(w, vec4(c.z <= d[i] ? 1.0 : 0.0, c.z <= d[i + 1] ? 1.0 : 0.0, c.z <= d[i + M] ? 1.0 : 0.0,
                           c.z <= d[i + M + 1] ? 1.0 : 0.0));
    } else {
        lit0 = texture(spotlight_shadow_cmp_map, vec4(c.xy, layer, c.z));
    }
#else
    lit0 = texture(spotlight_shadow_cmp_map, vec4(c.xy, layer, c.z));
#endif
    float trust = smoothstep(0.25, 0.75, lit0);
    vec2 uv = c.xy; // the texel stays (above); rounding moved it by ~10⁻⁴ texel at grazing
    c = spotlight_shadow_window(clip_near + trust * clip_rest);
    if (spotlight_shadow_outside(c)) return 1.0;
    vec3 sc = vec3(uv, c.z);
    // no steeper than tanθ = 1000 (89.94°), as the slope bias (at a silhouette the plane is edge-on
    // and the taps would extrapolate it without bound), and than tanθ = 10 where the gate is shut
    float gmax = mix(spotlight_shadow_tan_ungated, 1000.0, trust) * dl, glen = length(g);
    if (glen > gmax) g *= gmax / glen;
#if SPOTLIGHT_SHADOW_FILTER == SPOTLIGHT_SHADOW_FILTER_HARD
    return min(sc.z + dot(g, texel + 0.5 - sc.xy * S), 1.0) <= stored ? 1.0 : 0.0;
#elif SPOTLIGHT_SHADOW_FILTER == SPOTLIGHT_SHADOW_FILTER_PCF
    float sum = 0.0;
    if (gathered) {
        for (int y = 0; y < K; ++y)
            for (int x = 0; x < K; ++x) {
                float ref = min(sc.z + dot(g, vec2(x, y) - h), 1.0);
                int i = y * M + x;
                sum += dot(w, vec4(ref <= d[i] ? 1.0 : 0.0, ref <= d[i + 1] ? 1.0 : 0.0, ref <= d[i + M] ? 1.0 : 0.0,
                                   ref <= d[i + M + 1] ? 1.0 : 0.0));
            }
    } else {
        for (int y = 0; y < K; ++y)
            for (int x = 0; x < K; ++x) sum += spotlight_shadow_compare(layer, sc, (vec2(x, y) - h) * spotlight_shadow_pcf_step, g);
    }
    return sum / float(K * K);
#elif SPOTLIGHT_SHADOW_FILTER == SPOTLIGHT_SHADOW_FILTER_POISSON
    return spotlight_shadow_poisson(layer, sc, g, spotlight_shadow_poisson_radius, SPOTLIGHT_SHADOW_POISSON_TAPS);
#elif SPOTLIGHT_SHADOW_FILTER == SPOTLIGHT_SHADOW_FILTER_PCSS
    // 1. blocker search over the cone from the receiver to the light, cut at the near plane
    bool ortho = V.ortho > 0.5;
    float reach = V.size * max(z_r - V.near, 0.0);
    float search = ortho ? reach / V.texel : reach / max(z_r, 1e-4) / (V.texel * V.near);
    search = clamp(search, 1.0, spotlight_shadow_pcss_max_radius);
    mat2 R = spotlight_shadow_rotation();
    float zb = 0.0;
    int nb = 0;
    for (int k = 0; k < SPOTLIGHT_SHADOW_PCSS_BLOCKER_TAPS; ++k) {
        vec2 o = R * spotlight_shadow_disk[k] * search;
        float d = texture(spotlight_shadow_depth_map, vec3(sc.xy + o / S, layer)).r;
        if (d < min(sc.z + dot(g, o), 1.0)) {
            zb += spotlight_shadow_linear_depth(V, d);
            nb++;
        }
    }
    if (nb == 0) return 1.0;
    zb /= float(nb);
    // 2. penumbra width from similar triangles, 3. filter over it
    float w = ortho ? V.size * max(z_r - zb, 0.0) : V.size * max(z_r - zb, 0.0) / max(zb, 1e-4);
    float r = clamp(w / tw, 0.5, spotlight_shadow_pcss_max_radius);
    return spotlight_shadow_poisson(layer, sc, g, r, SPOTLIGHT_SHADOW_PCSS_FILTER_TAPS);
#else // reference: one bilinear comparison of a high-resolution map rendered from a point
      // sampled on the light (the frames are averaged by the core)
    return spotlight_shadow_compare(layer, sc, vec2(0.0), g);
#endif
}
#endif

float spotlight_shadow_visibility(int i, SlLight L, SlSurface s, vec3 l) {
#if !SPOTLIGHT_SHADOW_SHADOWS
    return 1.0;
#else
    vec4 info = texelFetch(spotlight_shadow_table, ivec2(0, i), 0);
    int count = int(info.y + 0.5);
    if (count <= 0) return 1.0;
    int v = int(info.x + 0.5);
    // The views to filter: n (0, 1 or 2) from v on, the second mixed in by t. One call site of
    // spotlight_shadow_view_visibility, in a loop the compiler does not unroll (n is not a
    // constant): Mesa inlines every call, and each copy of the filter was ~60 ms of llvmpipe's
    // compile per forward program (issue 19).
    int n = 1;
    float t = 0.0;
    if (info.w > 0.5) { // views supplied by a view provider (cascades): picked by camera depth;
        // texel 7 of a view row = (split_near, split_far, blend); over the last `blend` metres
        // before split_far the visibility fades into the next view's, so the image is continuous
        // at the split (sdk ext/shadow_maps.h, revision 2)
        float z = -(sl_view * vec4(s.position, 1.0)).z;
        n = 0; // beyond the last split: not covered
        for (int k = 0; k < count; ++k) {
            vec4 sel = texelFetch(spotlight_shadow_table, ivec2(7, spotlight_shadow_view_base + v + k), 0);
            if (z >= sel.y) continue;
            t = sel.z > 0.0 ? (z - (sel.y - sel.z)) / sel.z : -1.0;
            n = t > 0.0 && k + 1 < count ? 2 : 1;
            v += k;
            break;
        }
    } else if (count == 6) { // point light: the cube face of the major axis
        vec3 d = s.position - texelFetch(spotlight_shadow_table, ivec2(1, i), 0).xyz;
        vec3 a = abs(d);
        v += a.x >= a.y && a.x >= a.z ? (d.x > 0.0 ? 0 : 1) : a.y >= a.z ? (d.y > 0.0 ? 2 : 3) : (d.z > 0.0 ? 4 : 5);
    }
    // A do-while: llvmpipe runs a loop's body under a mask of the lanes still in it, and a for
    // loop's test at the top ran the filter once more, every lane masked, at full cost.
    float vis = 1.0;
    int j = 0;
    do {
        float x = spotlight_shadow_view_visibility(v + j, s, l);
        vis = j == 0 ? x : mix(vis, x, t);
        ++j;
    } while (j < n);
    return n > 0 ? vis : 1.0;
#endif
}
