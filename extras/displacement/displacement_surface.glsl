// displacement: SURFACE hooks.
//   displacement_parallax  materials carrying `parallax` (and not `displace`, which wins): parallax
//                          occlusion mapping (Tatarchuk 2006) or plain parallax mapping with offset
//                          limiting (Welsh 2004), on the same height field as true displacement;
//   displacement_cavity    darkens the base colour in the relief's hollows (key `cavity`), for
//                          every method, so a groove reads as one.
#include "displacement_height.glsl"

// World-space derivatives of the position with respect to u and v, from screen derivatives (the
// cotangent frame of Schüler 2013): lets a height in metres become an offset in UV.
void displacement_dpduv(SlSurface s, out vec3 dpdu, out vec3 dpdv) {
    vec3 dp1 = dFdx(s.position), dp2 = dFdy(s.position);
    vec2 du1 = dFdx(s.uv), du2 = dFdy(s.uv);
    float det = du1.x * du2.y - du1.y * du2.x;
    if (abs(det) < 1e-20) { dpdu = s.tangent; dpdv = s.bitangent; return; }
    dpdu = (dp1 * du2.y - dp2 * du1.y) / det;
    dpdv = (dp2 * du1.x - dp1 * du2.x) / det;
}

// A world-space vector in the surface plane as a UV offset (dual basis of dpdu, dpdv).
vec2 displacement_to_uv(vec3 w, vec3 dpdu, vec3 dpdv) {
    float a11 = dot(dpdu, dpdu), a12 = dot(dpdu, dpdv), a22 = dot(dpdv, dpdv);
    float det = a11 * a22 - a12 * a12;
    if (det < 1e-30) return vec2(0.0);
    float b1 = dot(w, dpdu), b2 = dot(w, dpdv);
    return vec2(a22 * b1 - a12 * b2, a11 * b2 - a12 * b1) / det;
}

// Normal of the height field at uv: normalize(n − ∇h), ∇h = scale·(H_u·dpdu* + H_v·dpdv*) with
// the dual basis (central differences over a small UV step).
vec3 displacement_relief_normal(vec2 uv, float scale, vec3 n, vec3 dpdu, vec3 dpdv) {
    const float e = 1.0 / 2048.0;
    float hu = (displacement_H(uv + vec2(e, 0.0)) - displacement_H(uv - vec2(e, 0.0))) / (2.0 * e);
    float hv = (displacement_H(uv + vec2(0.0, e)) - displacement_H(uv - vec2(0.0, e))) / (2.0 * e);
    float a11 = dot(dpdu, dpdu), a12 = dot(dpdu, dpdv), a22 = dot(dpdv, dpdv);
    float det = a11 * a22 - a12 * a12;
    if (det < 1e-30) return n;
    vec3 du = (a22 * dpdu - a12 * dpdv) / det, dv = (a11 * dpdv - a12 * dpdu) / det; // dual basis
    vec3 g = scale * (hu * du + hv * dv);
    g -= n * dot(g, n);
    return normalize(n - g);
}

void displacement_parallax(inout SlSurface s) {
#ifndef SL_MAT_HAS_DISPLACE
    float scale = sl_mat_parallax;
    vec3 n = s.normal;
    float vn = dot(s.view, n);
    if (scale <= 0.0 || vn <= 1e-4) return; // grazing or behind: the polygon as it is
    vec3 dpdu, dpdv;
    displacement_dpduv(s, dpdu, dpdv);
    // going `scale` deep along the view ray into the surface moves this much along it, in UV
    vec3 lateral = -(s.view - n * vn) / vn * scale;
    vec2 duv = displacement_to_uv(lateral, dpdu, dpdv);
    float depth = 0.0; // of the hit, in units of scale
#if DISPLACEMENT_PARALLAX == DISPLACEMENT_PARALLAX_OCCLUSION
    // Tatarchuk 2006: linear search through layers (more of them at grazing angles), then the
    // intersection of the ray with the segment between the last two samples of the height field
    int steps = int(mix(float(displacement_pom_steps), float(max(displacement_pom_steps / 4, 2)), vn));
    float layer = 1.0 / float(steps);
    float prev_gap = 0.0, t = 0.0;
    float d_map = 1.0 - displacement_H(s.uv);
    depth = 0.0;
    if (d_map > 0.0) {
        for (int i = 1; i <= steps; ++i) {
            t = float(i) * layer;
            float d_now = 1.0 - displacement_H(s.uv + duv * t);
            float gap = t - d_now; // > 0: the ray is below the surface
            if (gap >= 0.0) {
                float w = gap / max(gap - prev_gap, 1e-8); // secant between the two samples
                depth = t - w * layer;
                break;
            }
            prev_gap = gap;
            depth = 1.0;
        }
    }
#else
    // Welsh 2004: one lookup, offset limited to the height there (no division by n·v)
    float d_map = 1.0 - displacement_H(s.uv);
    duv *= vn; // offset limiting: the lateral shift is at most scale·(1 − H)
    depth = d_map;
#endif
    vec2 uv = s.uv + duv * depth;
    // The point hit, moved along the surface only: moved down to its depth it would lie behind the
    // polygon that the shadow maps hold and every light would see it shadowed by its own polygon.
    // (So the relief casts no shadows on itself: Tatarchuk's soft self-shadowing is not done.)
    s.position += dpdu * (duv.x * depth) + dpdv * (duv.y * depth);
    s.uv = uv;
    vec3 nn = displacement_relief_normal(uv, scale, n, dpdu, dpdv);
    s.normal = nn;
    vec3 t2 = s.tangent - nn * dot(nn, s.tangent);
    if (dot(t2, t2) > 1e-12) {
        float hand = dot(cross(s.normal, s.tangent), s.bitangent) < 0.0 ? -1.0 : 1.0;
        s.tangent = normalize(t2);
        s.bitangent = cross(nn, s.tangent) * hand;
    }
#endif
}

void displacement_cavity(inout SlSurface s) {
#ifdef SL_MAT_HAS_CAVITY
    s.base_color *= mix(1.0, displacement_H(s.uv), clamp(sl_mat_cavity, 0.0, 1.0));
#endif
}

// debug view "displacement-position": the world-space position of the visible surface (tests read
// it back instead of a depth buffer)
vec3 displacement_view_position(SlSurface s) { return s.position; }
