// refraction (extras/refraction/README.md): a smooth dielectric lit by the environment.
// Reflection and refraction weighted by the exact dielectric Fresnel term of the SDK's shader
// library (ggx_fresnel_exact, Walter et al. 2007 eq. 22: its eta is n_incident / n_transmitted).
// Method single: one interface; two-interface: Wyman 2005 with a back-face pass (refraction.c).
#include "sl:ggx_brdf.glsl"

uniform samplerCube refraction_env;   // "shadelab.environment/1" (envmap): the environment cube
uniform bool refraction_env_ok;       // false: no environment (then it is black)
uniform mat3 refraction_env_rot;      // world → cube lookup direction
uniform float refraction_env_scale;   // intensity
uniform float refraction_env_size;    // face size of level 0
uniform float refraction_env_lod_max; // its coarsest level
#if REFRACTION_METHOD == REFRACTION_METHOD_TWO_INTERFACE
uniform sampler2D refraction_back;    // back faces: outward normal (rgb), distance from the camera (a)
#endif

vec3 refraction_env_at(vec3 d, float lod) {
    if (!refraction_env_ok || dot(d, d) < 1e-12) return vec3(0.0);
    return textureLod(refraction_env, refraction_env_rot * d, clamp(lod, 0.0, refraction_env_lod_max)).rgb *
           refraction_env_scale;
}

// Mip level for a lookup direction's screen footprint (a cube texel spans about ½π/size rad).
// Called in uniform control flow (derivatives).
float refraction_lod(vec3 d) {
    float a = max(length(dFdx(d)), length(dFdy(d)));
    return refraction_filter ? max(0.0, log2(max(a, 1e-8) * refraction_env_size / (0.5 * SL_PI))) : 0.0;
}

// Radiance carried back along −t1 by a ray that entered at p with direction t1 (η = ior inside).
vec3 refraction_inside(vec3 p, vec3 t1, float ior) {
#if REFRACTION_METHOD == REFRACTION_METHOD_TWO_INTERFACE
    vec3 cam = sl_camera_pos;
    vec4 c = sl_view_proj * vec4(p, 1.0);
    vec4 back = texture(refraction_back, c.xy / c.w * 0.5 + 0.5);
    // Wyman's d_V: front-to-back distance along the view ray, then `steps` refinements: the back
    // face seen through the current exit estimate, projected on the refracted ray
    float d = back.a - length(p - cam);
    bool ok = back.a > 0.0 && d > 0.0;
    d = max(d, 0.0);
    for (int i = 0; i < REFRACTION_STEPS; i++) {
        vec3 q = p + d * t1;
        vec4 cq = sl_view_proj * vec4(q, 1.0);
        vec4 bq = texture(refraction_back, cq.xy / cq.w * 0.5 + 0.5);
        vec3 hit = cam + normalize(q - cam) * bq.a;
        float dn = dot(hit - p, t1);
        if (bq.a > 0.0 && dn > 0.0) d = dn;
    }
    vec3 q = p + d * t1;
    vec4 cq = sl_view_proj * vec4(q, 1.0);
    vec4 bq = texture(refraction_back, cq.xy / cq.w * 0.5 + 0.5);
    ok = ok && bq.a > 0.0;
    vec3 n2 = ok ? normalize(bq.rgb) : -t1;      // outward normal of the back face
    float c2 = max(dot(t1, n2), 0.0);
    float F2 = ggx_fresnel_exact(c2, ior);        // from inside: n_incident / n_transmitted = ior
    vec3 t2 = refract(t1, -n2, ior);              // vec3(0) beyond the critical angle (F2 = 1)
    vec3 r2 = reflect(t1, -n2);                   // looked up as if it then escaped (approximation)
    float lod_t = refraction_lod(t2), lod_r = refraction_lod(r2);
    return (1.0 - F2) * refraction_env_at(t2, lod_t) + F2 * refraction_env_at(r2, lod_r);
#else
    return refraction_env_at(t1, refraction_lod(t1));
#endif
}

vec3 refraction_ambient(SlSurface s, vec3 ambient_irradiance) {
    vec3 v = s.view, n = s.normal;
    float nv = dot(n, v);
    if (nv < 1e-4) n = normalize(n + v * (1e-4 - nv)); // an interpolated normal facing away: grazing
    float c = dot(n, v);
    vec3 r = reflect(-v, n);
    vec3 refl = refraction_env_at(r, refraction_lod(r));
#if defined(SL_MAT_HAS_IOR_RGB) && REFRACTION_DISPERSION
    vec3 L;
    for (int k = 0; k < 3; k++) {
        float ior = sl_mat_ior_rgb[k];
        float F = ggx_fresnel_exact(c, 1.0 / ior);
        vec3 t = refract(-v, n, 1.0 / ior);
        L[k] = F * refl[k] + (1.0 - F) * sl_mat_transmittance[k] * refraction_inside(s.position, t, ior)[k];
    }
    return L;
#else
#if defined(SL_MAT_HAS_IOR_RGB)
    float ior = sl_mat_ior_rgb.g;
#else
    float ior = sl_mat_ior;
#endif
    float F = ggx_fresnel_exact(c, 1.0 / ior);
    vec3 t = refract(-v, n, 1.0 / ior); // vec3(0) under total internal reflection (then F = 1)
    return F * refl + (1.0 - F) * sl_mat_transmittance * refraction_inside(s.position, t, ior);
#endif
}

// Lights are points or small: a smooth interface reflects them as deltas (not drawn).
vec3 refraction_model(SlSurface s, vec3 l, vec3 E) { return vec3(0.0); }

// No diffuse: other AMBIENT hooks (envmap's Lambert term for models it does not know) would add
// base_color · E/π.
void refraction_surface(inout SlSurface s) { s.base_color = vec3(0.0); }
