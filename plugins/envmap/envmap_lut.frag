// Environment-BRDF LUT (split sum, second factor): texel (i, j) holds (A, B) for n·v = i/(n−1)
// and perceptual roughness r = j/(n−1), α = r², such that ∫ f_s(v,l) cos θ_l dl = F0·A + B
// with Schlick's Fresnel. Sampled with GGX visible normals, whose f·cos/pdf is
// G(v,l)/G1(v) (times F): the G is the ggx plugin's own (ggx_G1 · ggx_G1).
// Third channel, the diffuse weight: C(μ) = ∫ (1 − v·h)^5 cos θ_l/π dl, h = normalize(l + v),
// so that the glTF metallic-roughness diffuse (Khronos glTF 2.0 spec, appendix B: f_diffuse =
// (1 − F(v·h)) c_diff/π, F Schlick's) integrates to (1 − F0)(1 − C(μ)) c_diff — the split sum
// (Karis 2013) applied to the diffuse lobe: ∫ L (1 − F) cos/π ≈ E/π · ∫ (1 − F) cos/π. It does
// not depend on α (h is not sampled from D); cosine-sampled on the same Hammersley set.
#include "sl:common.glsl"
#include "envmap_common.glsl"
#include "sl:ggx_brdf.glsl"
uniform float envmap_size;
uniform int envmap_samples;
layout(location = 0) out vec4 o_color;

vec2 envmap_brdf_integral(float mu, float alpha, int samples) {
    mu = max(mu, 1e-3);
    alpha = max(alpha, GGX_MIN_ALPHA);
    vec3 n = vec3(0.0, 0.0, 1.0), v = vec3(sqrt(1.0 - mu * mu), 0.0, mu);
    float g1v = envmap_smith_g1(mu, alpha);
    vec2 ab = vec2(0.0);
    uint count = uint(samples);
    for (uint i = 0u; i < count; i++) {
        vec3 h = envmap_sample_vndf(v, alpha, envmap_hammersley(i, count));
        vec3 l = 2.0 * dot(v, h) * h - v;
        if (l.z <= 0.0) continue;
        float w = ggx_G1(v, n, h, alpha) * ggx_G1(l, n, h, alpha) / g1v;
        float fc = pow(1.0 - clamp(dot(v, h), 0.0, 1.0), 5.0);
        ab += vec2(1.0 - fc, fc) * w;
    }
    return ab / float(count);
}

float envmap_diffuse_fresnel(float mu, int samples) {
    mu = max(mu, 1e-3);
    vec3 v = vec3(sqrt(1.0 - mu * mu), 0.0, mu);
    float c = 0.0;
    uint count = uint(samples);
    for (uint i = 0u; i < count; i++) {
        vec3 l = envmap_sample_cosine(envmap_hammersley(i, count));
        c += pow(1.0 - clamp(dot(v, normalize(l + v)), 0.0, 1.0), 5.0);
    }
    return c / float(count);
}

void main() {
    vec2 ij = floor(gl_FragCoord.xy);
    float r = ij.y / (envmap_size - 1.0);
    float mu = ij.x / (envmap_size - 1.0);
    o_color = vec4(envmap_brdf_integral(mu, r * r, envmap_samples), envmap_diffuse_fresnel(mu, envmap_samples), 1.0);
}
