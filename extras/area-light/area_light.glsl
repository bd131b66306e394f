// area-light: the "area" light type (LIGHT hook with SL_CHUNK_LIGHT_RADIANCE, ABI 1.6): returns the
// outgoing radiance towards s.view integrated over the light's rectangle or disk.
// Packed keys (light_slot): params[0] = (width m, height m, shape 0 rect / 1 disk, two_sided 0/1),
//                           params[1].xyz = axis (the direction of the width side).
// The light emits radiance L.color.rgb (colour × intensity, W/m²/sr) along L.direction (one-sided)
// or on both faces (two_sided).
//
//   ggx model:   diffuse by Lambert's formula, specular by the LTC fitted to the ggx plugin's BRDF
//                (ltc_fit.c; Heitz et al. 2016); Fresnel: Schlick's split for the schlick and
//                metallic-roughness modes, the exact dielectric Fresnel at the lobe's mean angle
//                for exact (see README)
//   lambert:     Lambert's formula: exact for the polygon
//   other models: the model evaluated once, at the direction of the polygon's vector irradiance
//                with its magnitude (exact for Lambertian terms; an approximation otherwise)
//   method = reference: Monte Carlo over the light's surface with the model itself (no visibility)
#include "area_polygon.glsl"
#include "sl:ggx_brdf.glsl" // the SDK's GGX terms (ggx_fresnel_exact)

uniform sampler2D area_light_ltc_m;     // M⁻¹ entries (a, b, c, d), see ltc.h
uniform sampler2D area_light_ltc_n;     // (norm, fresnel, -, -)
uniform float area_light_ltc_size;      // table size N

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

#if AREA_LIGHT_METHOD == AREA_LIGHT_METHOD_REFERENCE
// Monte Carlo over the light's surface: n×n stratified points per frame (one Cranley–Patterson
// rotation per pixel and frame), each a point source of E = L_e cosθ_light A / d², through the
// material's own model. The disk is the exact ellipse (not the polygon the LTC path uses).
vec3 area_light_reference(SlLight L, SlSurface s, vec3 c, vec3 nl, vec3 ex, vec3 ey) {
    float w = L.params[0].x, h = L.params[0].y;
    bool disk = L.params[0].z > 0.5, two_sided = L.params[0].w > 0.5;
    float area = disk ? 0.25 * SL_PI * w * h : w * h;
    const int n = AREA_LIGHT_REFERENCE_SAMPLES;
    uvec3 key = uvec3(uvec2(gl_FragCoord.xy), uint(sl_frame_index));
    vec2 rot = vec2(area_light_hash(key), area_light_hash(key + uvec3(0u, 0u, 7919u)));
    vec3 Lo = vec3(0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            vec2 u = fract((vec2(i, j) + rot) / float(n) + vec2(area_light_hash(uvec3(i, j, sl_frame_index + 1)),
                                                              area_light_hash(uvec3(j, i, sl_frame_index + 2))) / float(n));
            vec3 y;
            if (disk) {
                float r = sqrt(u.x), phi = 2.0 * SL_PI * u.y;
                y = c + ex * (0.5 * w * r * cos(phi)) + ey * (0.5 * h * r * sin(phi));
            } else {
                y = c + ex * ((u.x - 0.5) * w) + ey * ((u.y - 0.5) * h);
            }
            vec3 d = y - s.position;
            float d2 = dot(d, d);
            if (!(d2 > 1e-12)) continue;
            vec3 l = d * inversesqrt(d2);
            float cl = -dot(l, nl);
            if (two_sided) cl = abs(cl);
            if (cl <= 0.0) continue;
            Lo += sl_shading_model(s, l, L.color.rgb * (cl * area / (d2 * float(n * n))));
        }
    return Lo;
}
#endif

#ifdef SL_MODEL_GGX
// F0 of the ggx plugin's Fresnel modes, from the material keys this plugin shares with it
// (fresnel, eta, metallic): Schlick's F0 = ((1 − η)/(1 + η))², mix(0.04, base, metallic) for
// metallic-roughness.
vec3 area_light_f0(SlSurface s) {
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    return mix(vec3(0.04), s.base_color, sl_mat_metallic);
#else
    float r = (1.0 - sl_mat_eta) / (1.0 + sl_mat_eta);
    return vec3(r * r);
#endif
}
#endif

vec3 area_light_radiance(SlLight L, SlSurface s) {
    vec3 c, nl, ex, ey;
    area_light_geometry(L, c, nl, ex, ey);
    bool two_sided = L.params[0].w > 0.5;
    if (!two_sided && dot(s.position - c, nl) <= 0.0) return vec3(0.0); // behind a one-sided light
#if AREA_LIGHT_METHOD == AREA_LIGHT_METHOD_REFERENCE
    return area_light_reference(L, s, c, nl, ex, ey);
#else
    AreaLightPolygon poly = area_light_make_polygon(c - s.position, ex, ey, L.params[0].x, L.params[0].y,
                                                    L.params[0].z > 0.5, AREA_LIGHT_DISK_SEGMENTS);
    mat3 frame = area_light_frame(s.normal, s.view);
    vec3 phi = area_light_vector_irradiance(poly, frame); // local frame; phi.z = ∫ cos dω
    vec3 Le = L.color.rgb;
#if defined(SL_MODEL_GGX)
    float alpha = max(s.alpha, 2e-3), ndv = clamp(dot(s.normal, s.view), 0.0, 1.0);
    vec2 tc = (vec2(sqrt(alpha), sqrt(1.0 - ndv)) * (area_light_ltc_size - 1.0) + 0.5) / area_light_ltc_size;
    vec4 m = texture(area_light_ltc_m, tc);
    vec2 nf = texture(area_light_ltc_n, tc).xy;
    mat3 minv = mat3(vec3(m.x, 0.0, m.z), vec3(0.0, 1.0, 0.0), vec3(m.y, 0.0, m.w)); // columns
    float spec = area_light_vector_irradiance(poly, minv * frame).z * SL_INV_PI;
    vec3 f0 = area_light_f0(s);
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_SCHLICK || SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    vec3 fs = f0 * (nf.x - nf.y) + nf.y; // ∫ F f cos / ∫ D_ltc, Schlick split (exact for Schlick; see ltc.h)
#else
    // exact dielectric Fresnel at the lobe's mean Schlick argument: (1 − c)⁵ = fresnel / norm
    float c5 = clamp(nf.y / max(nf.x, 1e-8), 0.0, 1.0);
    vec3 fs = vec3(nf.x * ggx_fresnel_exact(1.0 - pow(c5, 0.2), sl_mat_eta));
#endif
    if (ndv <= 0.0) fs = vec3(0.0);      // the model's masking: no specular facing away
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    vec3 kd = (1.0 - f0) * (1.0 - sl_mat_metallic); // (1 − F) approximated by (1 − F0)
#else
    vec3 kd = vec3(1.0);
#endif
    return Le * (kd * s.base_color * SL_INV_PI * phi.z + s.specular * fs * spec);
#else
    // Lambert exactly (model(s, l̂, |Φ|) = k_d/π |Φ| n·l̂ = k_d/π Φ·n); any other model once, at
    // the vector irradiance's direction
    float e = length(phi);
    if (!(e > 0.0)) return vec3(0.0);
    return sl_shading_model(s, transpose(frame) * (phi / e), Le * e);
#endif
#endif
}
