// area-light: the "area" light type (LIGHT hook with SL_CHUNK_LIGHT_RADIANCE, ABI 1.6): returns the
// outgoing radiance towards s.view integrated over the light's rectangle or disk.
// Packed keys (light_slot): params[0] = (width m, height m, shape 0 rect / 1 disk, two_sided 0/1),
//                           params[1].xyz = axis (the direction of the width side).
// The light emits radiance L.color.rgb (colour × intensity, W/m²/sr) along L.direction (one-sided)
// or on both faces (two_sided).
//
//   every model through the SDK's lobe contract (sl_model_lobes, ABI 1.14), naming none: the
//                diffuse albedo by Lambert's formula (exact for the polygon), each lobe by the LTC
//                fitted to its shape (ltc_fit.c; Heitz et al. 2016): GGX's BRDF, or (ABI 1.19,
//                SL_LOBES_BLINN_PHONG) the Blinn-Phong lobe, × its weight; Fresnel:
//                Schlick's split between F0 and F90, the exact dielectric Fresnel at the lobe's
//                mean angle for a lobe with eta (see README)
//   a model without lobes (SL_MODEL_HAS_LOBES undefined), or lit at the dominant light
//                (SL_LOBES_MODEL_AT_DOMINANT_LIGHT, ABI 1.16: a toon model's bands): the model
//                evaluated once, at the direction of the polygon's vector irradiance with its
//                magnitude (exact for Lambertian terms; an approximation otherwise)
//   method = reference: Monte Carlo over the light's surface with the model itself (no visibility)
#include "area_polygon.glsl"
#include "sl:ggx_brdf.glsl" // the SDK's GGX terms (ggx_fresnel_exact)

uniform sampler2D area_light_ltc_m;     // M⁻¹ entries (a, b, c, d) of the GGX table, see ltc.h
uniform sampler2D area_light_ltc_n;     // (norm, fresnel, -, -) of the GGX table: every lobe's magnitude
uniform float area_light_ltc_size;      // table size N
// M⁻¹ of the Blinn-Phong table (ltc_blinn_phong.txt); only programs whose model has a Blinn-Phong
// lobe read it (area_light.c makes it at the first such bind)
uniform sampler2D area_light_ltc_blinn;
uniform float area_light_ltc_blinn_size;

// Emission textures (area_light.c: the emissive_map of the material named like the light),
// prefiltered into the levels of one layer each; a light is textured when its position and
// direction equal a key (exact: both are the same floats the core packs).
uniform sampler2DArray area_light_tex;
uniform vec4 area_light_tex_key[8];     // per layer: (position, in use), (direction, -)
uniform int area_light_tex_count;
const float AREA_LIGHT_TEX_SIZE = 256.0, AREA_LIGHT_TEX_BORDER = 64.0; // as area_light.c
const float AREA_LIGHT_TEX_MAX_LOD = 8.0;
// The filter's width on the light plane, σ = AREA_LIGHT_TEX_SPREAD × the distance from the
// shading point to that plane (in the LTC's space). A clamped cosine seen on a plane at distance
// r falls to half its peak at ρ = 0.64 r (a Gaussian of σ = 0.55 r does too) but has long tails;
// 0.8 was the best of 0.3, 0.55, 0.8, 1.2 on the tests' checker light (README).
const float AREA_LIGHT_TEX_SPREAD = 0.8;

int area_light_tex_layer(SlLight L) {
    for (int i = 0; i < area_light_tex_count; ++i)
        if (area_light_tex_key[2 * i].w > 0.5 && all(equal(area_light_tex_key[2 * i].xyz, L.position.xyz)) &&
            all(equal(area_light_tex_key[2 * i + 1].xyz, L.direction.xyz)))
            return i;
    return -1;
}

// The texture at the light's own coordinates uv ∈ [0,1]² (u along the width axis, v along
// direction × axis; v = 0 is the image's first row) and level lod.
vec3 area_light_tex_at(int layer, vec2 uv, float lod) {
    vec2 st = (uv * AREA_LIGHT_TEX_SIZE + AREA_LIGHT_TEX_BORDER) / (AREA_LIGHT_TEX_SIZE + 2.0 * AREA_LIGHT_TEX_BORDER);
    return textureLod(area_light_tex, vec3(st, float(layer)), clamp(lod, 0.0, AREA_LIGHT_TEX_MAX_LOD)).rgb;
}

// The paper's prefiltered lookup (Heitz et al. 2016, §5.3): in the space where the lobe is a
// clamped cosine around z (the light mapped by m: the local frame, then M⁻¹ for the LTC), the
// light is the parallelogram C ± X ± Y (c: centre relative to the shading point, hx, hy: half
// axes). The fetch point is the orthogonal projection of the shading point (the origin) onto its
// plane, in the light's (u, v); the level makes the filter σ = SPREAD · distance / √area wide
// (a fraction of the texture's side).
vec3 area_light_tex_filtered(int layer, mat3 m, vec3 c, vec3 hx, vec3 hy) {
    vec3 C = m * c, X = m * hx, Y = m * hy, n = cross(X, Y);
    float n2 = dot(n, n), xx = dot(X, X), xy = dot(X, Y), yy = dot(Y, Y), det = xx * yy - xy * xy;
    if (!(n2 > 0.0) || !(det > 0.0)) return area_light_tex_at(layer, vec2(0.5), AREA_LIGHT_TEX_MAX_LOD);
    float cn = dot(C, n);
    vec3 q = n * (cn / n2) - C; // projection of the origin, relative to the centre
    float qa = dot(q, X), qb = dot(q, Y);
    vec2 ab = vec2(qa * yy - qb * xy, qb * xx - qa * xy) / det; // q = a X + b Y
    float dist = abs(cn) * inversesqrt(n2), side = 2.0 * sqrt(sqrt(n2)); // √(area of the parallelogram)
    float sigma = AREA_LIGHT_TEX_SPREAD * dist / side * AREA_LIGHT_TEX_SIZE; // texels of level 0
    return area_light_tex_at(layer, 0.5 + 0.5 * ab, log2(max(sigma, 0.5) / 0.5));
}

// The light's frame: centre c, unit normal nl (the direction it emits along), ex, ey in its plane.
void area_light_geometry(SlLight L, out vec3 c, out vec3 nl, out vec3 ex, out vec3 ey) {
    c = L.position.xyz;
    nl = normalize(L.direction.xyz);
    area_light_axes(nl, L.params[1].xyz, ex, ey);
}

float area_light_hash(uvec3 x) { // a PCG-style integer hash (Jarzynski & Olano 2020, "pcg3d")
    x = x * 1664525u + 1013904223u;
    x.x += x.y * x.z; x.y += x.z * x.x; x.z += x.x * x.y;
    x ^= x >> 16u;
    x.x += x.y * x.z;
    return float(x.x >> 8u) * (1.0 / 16777216.0);
}

#if AREA_LIGHT_METHOD == AREA_LIGHT_METHOD_REFERENCE && AREA_LIGHT_REFERENCE_VISIBILITY
// The reference's visibility (area_light.c, al_shadow_execute): per frame one point y on each
// light and a depth cube map from it, six 90° faces in layers 6k … 6k + 5.
uniform sampler2DArray area_light_shadow;   // raw window depth, nearest
uniform vec4 area_light_shadow_key[8];      // per slot: (position, in use), (direction, -)
uniform vec4 area_light_shadow_point[4];    // (y, near)
uniform vec4 area_light_shadow_uv[4];       // (u, v of y on the light, far, map size)
uniform int area_light_shadow_count;

int area_light_shadow_slot(SlLight L) {
    for (int i = 0; i < area_light_shadow_count; ++i)
        if (area_light_shadow_key[2 * i].w > 0.5 && all(equal(area_light_shadow_key[2 * i].xyz, L.position.xyz)) &&
            all(equal(area_light_shadow_key[2 * i + 1].xyz, L.direction.xyz)))
            return i;
    return -1;
}

// The cube face of direction d from the light point (as area_light.c: axis, up; the face's
// right = normalize(axis × up), its up = right × axis).
void area_light_face(vec3 d, out int f, out vec3 fa, out vec3 fs, out vec3 fu) {
    vec3 ad = abs(d);
    vec3 up = vec3(0.0, 1.0, 0.0);
    if (ad.x >= ad.y && ad.x >= ad.z) { f = d.x > 0.0 ? 0 : 1; fa = vec3(sign(d.x), 0.0, 0.0); }
    else if (ad.y >= ad.z) { f = d.y > 0.0 ? 2 : 3; fa = vec3(0.0, sign(d.y), 0.0); up = vec3(0.0, 0.0, 1.0); }
    else { f = d.z > 0.0 ? 4 : 5; fa = vec3(0.0, 0.0, sign(d.z)); }
    fs = normalize(cross(fa, up));
    fu = cross(fs, fa);
}

// Visibility of the light point y of slot k from the surface point p: the receiver moved along
// its geometric normal (turned to the light) by 1.5 texels and towards the light by one texel
// (texels at its distance), then compared with the nearest texel's linearised depth.
float area_light_visible(int k, vec3 p, vec3 ng) {
    vec3 y = area_light_shadow_point[k].xyz;
    float near = area_light_shadow_point[k].w, far = area_light_shadow_uv[k].z, size = area_light_shadow_uv[k].w;
    vec3 d = p - y;
    float dist = length(d);
    if (!(dist > 0.0)) return 1.0;
    vec3 l = -d / dist;
    float texel = 2.0 * dist / size;
    vec3 n = dot(ng, l) < 0.0 ? -ng : ng;
    float cosi = clamp(dot(n, l), 0.05, 1.0);
    d = (p + n * (1.5 * texel) + l * texel) - y;
    int f;
    vec3 fa, fs, fu;
    area_light_face(d, f, fa, fs, fu);
    float ze = dot(d, fa);
    if (ze >= far) return 1.0;
    vec2 st = 0.5 + 0.5 * vec2(dot(d, fs), dot(d, fu)) / ze;
    float stored = textureLod(area_light_shadow, vec3(st, float(6 * k + f)), 0.0).r;
    if (stored >= 1.0) return 1.0; // nothing drawn there
    float zb = 2.0 * near * far / (far + near - (2.0 * stored - 1.0) * (far - near));
    // slope: a texel spans texel·tanθ in depth on a receiver at incidence θ
    return ze <= zb + texel * (1.0 + sqrt(1.0 - cosi * cosi) / cosi) ? 1.0 : 0.0;
}
#endif

#if AREA_LIGHT_METHOD == AREA_LIGHT_METHOD_REFERENCE
// Monte Carlo over the light's surface: n×n stratified points per frame (one Cranley–Patterson
// rotation per pixel and frame), each a point source of E = L_e cosθ_light A / d², through the
// material's own model. The disk is the exact ellipse (not the polygon the LTC path uses).
vec3 area_light_reference(SlLight L, SlSurface s, vec3 c, vec3 nl, vec3 ex, vec3 ey) {
    float w = L.params[0].x, h = L.params[0].y;
    int layer = area_light_tex_layer(L);
    bool disk = L.params[0].z > 0.5, two_sided = L.params[0].w > 0.5;
    float area = disk ? 0.25 * SL_PI * w * h : w * h;
    vec3 blocked = vec3(0.0); // this frame's point's light that does not arrive (see below)
#if AREA_LIGHT_REFERENCE_VISIBILITY
    // ∫ f V = ∫ f − ∫ f (1 − V): the first integral by the n×n points per pixel below (as without
    // visibility), the second by this frame's point y_k on the light, the same for every pixel,
    // shadowed through its cube map. Both estimators are unbiased, so is the difference; where
    // nothing is occluded the second term is 0 and the result is the unshadowed estimate itself
    // (no structured error from one point per frame in lit regions).
    int k = area_light_shadow_slot(L);
    if (k >= 0) {
        vec2 uv = area_light_shadow_uv[k].xy;
        vec3 y = c + ex * ((uv.x - 0.5) * w) + ey * ((uv.y - 0.5) * h);
        vec3 d = y - s.position;
        float d2 = dot(d, d);
        vec3 l = d * inversesqrt(max(d2, 1e-24));
        float cl = -dot(l, nl);
        if (two_sided) cl = abs(cl);
        if (d2 > 1e-12 && cl > 0.0 && area_light_visible(k, s.position, s.geometric_normal) <= 0.0) {
            vec3 Le = layer >= 0 ? L.color.rgb * area_light_tex_at(layer, uv, 0.0) : L.color.rgb;
            blocked = sl_shading_model(s, l, Le * (cl * area / d2));
        }
    }
    // more area lights than shadow slots: unshadowed
#endif
    const int n = AREA_LIGHT_REFERENCE_SAMPLES;
    uvec3 key = uvec3(uvec2(gl_FragCoord.xy), uint(sl_frame_index));
    vec2 rot = vec2(area_light_hash(key), area_light_hash(key + uvec3(0u, 0u, 7919u)));
    vec3 Lo = vec3(0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            vec2 u = fract((vec2(i, j) + rot) / float(n) + vec2(area_light_hash(uvec3(i, j, sl_frame_index + 1)),
                                                              area_light_hash(uvec3(j, i, sl_frame_index + 2))) / float(n));
            vec3 y;
            vec2 uv = u;
            if (disk) {
                float r = sqrt(u.x), phi = 2.0 * SL_PI * u.y;
                uv = 0.5 + 0.5 * r * vec2(cos(phi), sin(phi));
            }
            y = c + ex * ((uv.x - 0.5) * w) + ey * ((uv.y - 0.5) * h);
            vec3 d = y - s.position;
            float d2 = dot(d, d);
            if (!(d2 > 1e-12)) continue;
            vec3 l = d * inversesqrt(d2);
            float cl = -dot(l, nl);
            if (two_sided) cl = abs(cl);
            if (cl <= 0.0) continue;
            vec3 Le = layer >= 0 ? L.color.rgb * area_light_tex_at(layer, uv, 0.0) : L.color.rgb; // the texture itself
            Lo += sl_shading_model(s, l, Le * (cl * area / (d2 * float(n * n))));
        }
    return Lo - blocked; // may be negative in one frame; the accumulated average is not
}
#endif

#if defined(SL_MODEL_HAS_LOBES)
// One lobe of the contract over the polygon: the LTC's integral (a fraction of the lobe) × its
// Fresnel-weighted norm (∫ F f cos / ∫ D_ltc, Schlick split: F0·(n − f) + F90·f, exact for
// Schlick; see ltc.h) × weight. A Blinn-Phong lobe takes its shape, M⁻¹, from its own table and
// its magnitude from GGX's at its α: the contract gives it the GGX lobe's albedo. Textured lights
// read the texture through the lobe's LTC.
vec3 area_light_lobe(SlLobe lobe, bool blinn_phong, AreaLightPolygon poly, mat3 frame, float ndv, int layer, vec3 rel,
                     vec3 hx, vec3 hy) {
    float alpha = max(lobe.alpha, 2e-3);
    vec2 at = vec2(sqrt(alpha), sqrt(1.0 - ndv));
    vec2 tc = (at * (area_light_ltc_size - 1.0) + 0.5) / area_light_ltc_size;
    vec4 m = blinn_phong ? texture(area_light_ltc_blinn, (at * (area_light_ltc_blinn_size - 1.0) + 0.5) / area_light_ltc_blinn_size)
                         : texture(area_light_ltc_m, tc);
    vec2 nf = texture(area_light_ltc_n, tc).xy;
    mat3 minv = mat3(vec3(m.x, 0.0, m.z), vec3(0.0, 1.0, 0.0), vec3(m.y, 0.0, m.w)); // columns
    float spec = area_light_vector_irradiance(poly, minv * frame).z * SL_INV_PI;
    vec3 Ts = layer >= 0 ? area_light_tex_filtered(layer, minv * frame, rel, hx, hy) : vec3(1.0);
    vec3 fs = lobe.f0 * (nf.x - nf.y) + lobe.f90 * nf.y;
    if (lobe.eta > 0.0) { // exact dielectric Fresnel at the lobe's mean Schlick argument: (1 − c)⁵ = fresnel / norm
        float c5 = clamp(nf.y / max(nf.x, 1e-8), 0.0, 1.0);
        fs = vec3(nf.x * ggx_fresnel_exact(1.0 - pow(c5, 0.2), lobe.eta));
    }
    return lobe.weight * fs * spec * Ts;
}
#endif

vec3 area_light_radiance(SlLight L, SlSurface s) {
    vec3 c, nl, ex, ey;
    area_light_geometry(L, c, nl, ex, ey);
    bool two_sided = L.params[0].w > 0.5;
    if (!two_sided && dot(s.position - c, nl) <= 0.0) return vec3(0.0); // behind a one-sided light
    SlLobes lobes = sl_model_lobes(s);
    // a model lit at the dominant light (ABI 1.16) is defined by that evaluation: every method gives it
    bool at_dominant = (lobes.flags & SL_LOBES_MODEL_AT_DOMINANT_LIGHT) != 0;
#if AREA_LIGHT_METHOD == AREA_LIGHT_METHOD_REFERENCE
    if (!at_dominant) return area_light_reference(L, s, c, nl, ex, ey);
#endif
    AreaLightPolygon poly = area_light_make_polygon(c - s.position, ex, ey, L.params[0].x, L.params[0].y,
                                                    L.params[0].z > 0.5, AREA_LIGHT_DISK_SEGMENTS);
    mat3 frame = area_light_frame(s.normal, s.view);
    vec3 phi = area_light_vector_irradiance(poly, frame); // local frame; phi.z = ∫ cos dω
    vec3 Le = L.color.rgb, Td = vec3(1.0);
    int layer = area_light_tex_layer(L);
    vec3 hx = ex * (0.5 * L.params[0].x), hy = ey * (0.5 * L.params[0].y);
    if (layer >= 0) Td = area_light_tex_filtered(layer, frame, c - s.position, hx, hy);
#if defined(SL_MODEL_HAS_LOBES)
    if (!at_dominant) {
        float ndv = clamp(dot(s.normal, s.view), 0.0, 1.0);
        vec3 kd = lobes.diffuse, spec = vec3(0.0);
        for (int k = 0; k < lobes.count && k < SL_MAX_LOBES; ++k) {
            // diffuse_coupled: (1 − F) of lobe 0 approximated by (1 − F0)
            if (k == 0 && lobes.diffuse_coupled) kd *= 1.0 - lobes.lobe[0].f0;
            // no specular for a normal facing away (the contract's lobes are masked there); a
            // lobe with its own normal (ABI 1.26: a clear coat's) in its own frame
            vec3 nk = sl_lobe_normal(lobes, k, s);
            if (lobes.lobe[k].weight > 0.0 && dot(nk, s.view) > 0.0) {
                bool own = nk != s.normal;
                mat3 fk = own ? area_light_frame(nk, s.view) : frame;
                float ndvk = own ? clamp(dot(nk, s.view), 0.0, 1.0) : ndv;
                spec += area_light_lobe(lobes.lobe[k], sl_lobe_blinn_phong(lobes, k), poly, fk, ndvk, layer, c - s.position,
                                        hx, hy);
            }
        }
        return Le * (kd * SL_INV_PI * phi.z * Td + spec);
    }
#endif
    // the model once, at the vector irradiance's direction with its magnitude: the dominant light
    // of SL_LOBES_MODEL_AT_DOMINANT_LIGHT, and the fallback of a model without lobes; exact for
    // Lambert (model(s, l̂, |Φ|) = k_d/π |Φ| n·l̂ = k_d/π Φ·n), nothing left over for the diffuse
    float e = length(phi);
    if (!(e > 0.0)) return vec3(0.0);
    return sl_shading_model(s, transpose(frame) * (phi / e), Le * Td * e);
}
