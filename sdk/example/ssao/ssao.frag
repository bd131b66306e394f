// Screen-space ambient occlusion (the ssao example's pass): for each pixel, the fraction of a
// cosine-weighted hemisphere of sample points around the surface (radius ssao.radius, oriented by
// the core's "normal") that the depth buffer shows behind other geometry: Crytek's screen-space AO
// (Mittring 2007) with normal-oriented hemispheres (Bavoil & Sainz, "Screen Space Ambient
// Occlusion", 2008). Cosine weighting makes the result the occluded share of ambient irradiance:
// 1/2 at the crease of a 90° corner. Writes ambient visibility 1 − strength × occluded share.
in vec2 v_uv;
uniform sampler2D ssao_depth;   // the core's "depth" (window depth, cleared to 1)
uniform sampler2D ssao_normal;  // the core's "normal" (view space)
uniform mat4 ssao_proj, ssao_inv_proj;
uniform float ssao_radius_world, ssao_strength_value;
uniform int ssao_sample_count;
layout(location = 0) out vec4 o_ao;

vec3 ssao_view_position(vec2 uv, float depth) {
    vec4 p = ssao_inv_proj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

float ssao_depth_at(vec2 uv) {
    ivec2 size = textureSize(ssao_depth, 0);
    return texelFetch(ssao_depth, clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1), 0).r;
}

void main() {
    float depth = ssao_depth_at(v_uv);
    if (depth >= 1.0) { // nothing drawn here
        o_ao = vec4(1.0);
        return;
    }
    vec3 p = ssao_view_position(v_uv, depth);
    ivec2 nsize = textureSize(ssao_normal, 0);
    vec3 n = texelFetch(ssao_normal, clamp(ivec2(v_uv * vec2(nsize)), ivec2(0), nsize - 1), 0).xyz;
    float nlen = length(n);
    n = nlen > 1e-6 ? n / nlen : vec3(0.0, 0.0, 1.0);
    vec3 t = abs(n.z) < 0.999 ? normalize(cross(vec3(0.0, 0.0, 1.0), n)) : vec3(1.0, 0.0, 0.0);
    vec3 b = cross(n, t);
    float occluded = 0.0;
    const float golden_angle = 2.39996323;
    for (int i = 0; i < ssao_sample_count; i++) {
        // Malley's method over a Fibonacci spiral: cosine-weighted directions, evenly spread
        float u = (float(i) + 0.5) / float(ssao_sample_count);
        float r = sqrt(u), phi = float(i) * golden_angle;
        vec3 dir = r * cos(phi) * t + r * sin(phi) * b + sqrt(1.0 - u) * n;
        // distances over (0.2, 1] R, a second low-discrepancy sequence (the R1 sequence)
        float dist = ssao_radius_world * (0.2 + 0.8 * fract((float(i) + 0.5) * 0.618034));
        vec3 q = p + dist * dir;
        vec4 c = ssao_proj * vec4(q, 1.0);
        vec2 uv = c.xy / c.w * 0.5 + 0.5;
        if (c.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue; // off screen: open
        float scene_depth = ssao_depth_at(uv);
        if (scene_depth >= 1.0) continue;
        float scene_z = ssao_view_position(uv, scene_depth).z;
        // the depth buffer's surface lies in front of the sample point (view z grows towards the
        // camera), within the radius of p: geometry closes this direction
        float bias = 0.02 * ssao_radius_world;
        if (scene_z > q.z + bias && abs(scene_z - p.z) < ssao_radius_world) occluded += 1.0;
    }
    float visibility = 1.0 - ssao_strength_value * occluded / float(max(ssao_sample_count, 1));
    o_ao = vec4(visibility, visibility, visibility, 1.0);
}
