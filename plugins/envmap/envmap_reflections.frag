// envmap-reflections-trace (reflections=screen): per texel of the scene's image that
// envmap-reflections drew (envmap_scene.frag), a ray from the surface along the lookup direction of
// its smoothest lobe, stepped through the image's depth; where it goes from in front of a surface to
// behind it, bisected to the crossing and kept if the ray meets the surface there, not where it
// passes behind an object's silhouette. Writes (radiance × weight, weight), weight 0 where the ray
// found nothing, left the image or the lobe is too rough: the forward pass then keeps the
// environment (envmap_shading.glsl, envmap_reflected). Deterministic: the same steps everywhere.
#include "envmap_common.glsl"
in vec2 v_uv;
uniform sampler2D envmap_refl_color; // the scene's image, with mips
uniform sampler2D envmap_refl_depth; // its window depth
uniform sampler2D envmap_refl_lobe;  // its smoothest lobe: lookup direction (world), GGX alpha
uniform mat4 envmap_refl_view_proj, envmap_refl_inv_view_proj; // the view it was drawn with
uniform vec4 envmap_refl_depth_lin;  // view distance from NDC z (envmap_view_distance)
uniform vec2 envmap_refl_texel;      // a texel's world size: x times (y > 0: the view distance; else 1)
uniform float envmap_refl_alpha;     // lobes this rough or rougher: not traced
uniform float envmap_refl_length;    // the longest ray, world units (the scene's diagonal)
uniform int envmap_refl_steps;
layout(location = 0) out vec4 o_found;

float envmap_refl_distance(float ndc_z) { return envmap_view_distance(envmap_refl_depth_lin, ndc_z); }
float envmap_refl_scene(vec2 ndc) { // the view distance of the scene's surface at an NDC point
    ivec2 size = textureSize(envmap_refl_depth, 0);
    ivec2 at = clamp(ivec2((ndc * 0.5 + 0.5) * vec2(size)), ivec2(0), size - 1);
    return envmap_refl_distance(texelFetch(envmap_refl_depth, at, 0).r * 2.0 - 1.0);
}
// (radiance × weight, weight) where the ray from p along d meets the scene's image; weight 0: no hit
vec4 envmap_screen_ray(vec3 p, vec3 d, float alpha) {
    float weight = 1.0;
    vec4 c0 = envmap_refl_view_proj * vec4(p, 1.0), c1 = envmap_refl_view_proj * vec4(p + d * envmap_refl_length, 1.0);
    const float w_min = 1e-3; // in front of a perspective camera (an orthographic one has w = 1)
    if (c0.w < w_min) return vec4(0.0);
    float len = envmap_refl_length;
    if (c1.w < w_min) {
        float u = (c0.w - w_min) / (c0.w - c1.w);
        c1 = mix(c0, c1, u), len *= u;
    }
    // NDC along the segment: a + t (b − a), NDC z affine in t; cut where it leaves the view volume
    vec3 a = c0.xyz / c0.w, ab = c1.xyz / c1.w - a;
    float t_end = 1.0;
    for (int i = 0; i < 3; i++)
        if (abs(ab[i]) > 1e-9) t_end = min(t_end, ((ab[i] > 0.0 ? 1.0 : -1.0) - a[i]) / ab[i]);
    vec2 size = vec2(textureSize(envmap_refl_depth, 0));
    if (t_end <= 0.0 || length(ab.xy * t_end * 0.5 * size) < 1.0) return vec4(0.0);
    // steps closer together near the surface (contact); where the ray goes from in front of the
    // image's surface to behind it, bisect to the crossing and keep it if the ray meets the
    // surface there (within what one texel and the last step span), not where it passes behind
    // an object's silhouette
    // The first two texels are the surface's own (its depth quantised to texels): not looked at.
    float span_px = length(ab.xy * 0.5 * size), t_start = min(2.0 / span_px, t_end);
    float t_lo = t_start, t_hit = -1.0;
    bool front = true;
    for (int i = 1; i <= envmap_refl_steps && t_hit < 0.0; i++) {
        float f = float(i) / float(envmap_refl_steps), t = t_start + (t_end - t_start) * f * sqrt(f);
        bool behind = envmap_refl_distance(a.z + ab.z * t) > envmap_refl_scene(a.xy + ab.xy * t);
        if (behind && front) {
            float lo = t_lo, hi = t;
            for (int k = 0; k < 6; k++) {
                float m = 0.5 * (lo + hi);
                if (envmap_refl_distance(a.z + ab.z * m) > envmap_refl_scene(a.xy + ab.xy * m)) hi = m; else lo = m;
            }
            float ray = envmap_refl_distance(a.z + ab.z * hi), scene = envmap_refl_scene(a.xy + ab.xy * hi);
            vec2 texel_step = normalize(ab.xy * size + 1e-9) * 2.0 / size; // one texel on along the ray, NDC
            float slope = abs(envmap_refl_scene(a.xy + ab.xy * hi + texel_step) - scene);
            float span = abs(ray - envmap_refl_distance(a.z + ab.z * lo));
            if (ray - scene <= 0.03 * scene + 2.0 * slope + span) t_hit = hi;
        }
        front = !behind, t_lo = t;
    }
    if (t_hit < 0.0) return vec4(0.0);
    float t_hi = t_hit;
    vec3 q = a + ab * t_hi;
    vec2 uv = q.xy * 0.5 + 0.5, edge = min(uv, 1.0 - uv);
    weight *= smoothstep(0.0, 0.05, min(edge.x, edge.y)); // fade out at the image's border
    // the world distance travelled (the clip-space fraction of the NDC one), the lobe's footprint
    // there (GGX's reflected lobe ≈ 1.3 α radians each side) over a texel's size
    float u = t_hi * c0.w / ((1.0 - t_hi) * c1.w + t_hi * c0.w);
    float scene = envmap_refl_distance(q.z), texel = envmap_refl_texel.x * (envmap_refl_texel.y > 0.0 ? scene : 1.0);
    float lod = log2(max(2.6 * alpha * u * len / max(texel, 1e-9), 1.0));
    return vec4(textureLod(envmap_refl_color, uv, lod).rgb * weight, weight);
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(envmap_refl_depth, px, 0).r;
    vec4 lobe = texelFetch(envmap_refl_lobe, px, 0);
    o_found = vec4(0.0);
    if (depth >= 1.0 || dot(lobe.xyz, lobe.xyz) < 0.25 || lobe.w >= envmap_refl_alpha) return;
    vec4 p = envmap_refl_inv_view_proj * vec4(v_uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    o_found = envmap_screen_ray(p.xyz / p.w, normalize(lobe.xyz), lobe.w);
}
