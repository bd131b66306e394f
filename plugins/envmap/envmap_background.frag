// The environment as background: after the forward pass, pixels the geometry did not cover
// (depth still at the cleared 1.0) show the source map along the view ray. ENVMAP_IN_PLACE: drawn
// into the forward pass's targets with a depth test that only those pixels pass (envmap.c). With SSAA the depth
// is k× larger than "color": a pixel whose k×k samples are partly background had the core's
// constant clear colour resolved into it, which is swapped for the sky in proportion.
#include "envmap_common.glsl"
uniform sampler2D envmap_color;
uniform sampler2D envmap_depth;
// ENVMAP_SOURCE_CUBE: the source is a cube; ENVMAP_SOURCE_SKY: the procedural sky, evaluated here
// per pixel (cube.c, em_sky_radiance: the same terms), so its sun disk has a sharp edge at any
// resolution; else a lat-long (a permutation: see envmap_to_cube.frag)
#if defined(ENVMAP_SOURCE_CUBE)
uniform samplerCube envmap_srccube;
#elif defined(ENVMAP_SOURCE_SKY)
uniform vec3 envmap_sky_sun;          // unit, towards the sun (map frame)
uniform float envmap_sky_sun_radius;  // radians
uniform vec3 envmap_sky_sun_radiance; // E / Ω times the sun's colour; 0: no sun
uniform vec3 envmap_sky_ground;       // below the horizon
vec3 envmap_sky(vec3 d) {
    const vec3 zenith = vec3(0.16, 0.30, 0.72), horizon = vec3(0.70, 0.78, 0.92);
    float y = d.y;
    float angle = acos(clamp(dot(d, envmap_sky_sun), -1.0, 1.0));
    vec3 sky = y >= 0.0 ? mix(zenith, horizon, pow(1.0 - y, 4.0)) : mix(envmap_sky_ground, horizon, exp(y * 25.0));
    float halo = (y > -0.05 ? 1.0 : 0.0) * (0.6 * exp(-angle * 8.0) + 0.15 * exp(-angle * 1.5));
    return sky + halo * vec3(1.0, 0.9, 0.75) + (angle < envmap_sky_sun_radius ? envmap_sky_sun_radiance : vec3(0.0));
}
#else
uniform sampler2D envmap_src2d;
#endif
uniform vec2 envmap_src_size;
uniform mat3 envmap_rot;
uniform float envmap_scale;
uniform vec3 envmap_clear;        // what the core cleared "color" to
uniform mat4 envmap_inv_view_proj;
uniform vec2 envmap_viewport;
uniform float envmap_pixel_angle; // radians per pixel at the centre of the view
layout(location = 0) out vec4 o_color;

void main() {
#ifndef ENVMAP_IN_PLACE
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 c = texelFetch(envmap_color, p, 0);
    int k = max(textureSize(envmap_depth, 0).x / max(textureSize(envmap_color, 0).x, 1), 1);
    int background = 0;
    // do-whiles (k >= 1): llvmpipe ran a for loop's body once more, every lane masked (4 fetches for 1)
    int j = 0;
    do {
        int i = 0;
        do background += texelFetch(envmap_depth, p * k + ivec2(i, j), 0).r >= 1.0 ? 1 : 0;
        while (++i < k);
    } while (++j < k);
    if (background == 0) {
        o_color = c;
        return;
    }
#endif
    vec2 ndc = gl_FragCoord.xy / envmap_viewport * 2.0 - 1.0;
    vec4 a = envmap_inv_view_proj * vec4(ndc, -1.0, 1.0), b = envmap_inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 d = envmap_rot * normalize(b.xyz / b.w - a.xyz / a.w);
    vec3 sky;
#if defined(ENVMAP_SOURCE_CUBE)
    float lod = max(0.0, log2(envmap_pixel_angle / (0.5 * ENVMAP_PI / envmap_src_size.x)));
    sky = textureLod(envmap_srccube, d, lod).rgb;
#elif defined(ENVMAP_SOURCE_SKY)
    sky = envmap_sky(normalize(d));
#else
    float lod = max(0.0, log2(envmap_pixel_angle / (ENVMAP_PI / envmap_src_size.y)));
    sky = textureLod(envmap_src2d, envmap_dir_latlong(d), lod).rgb;
#endif
    sky *= envmap_scale;
#ifdef ENVMAP_IN_PLACE
    o_color = vec4(sky, 1.0); // only background pixels reach here (the depth test, envmap.c)
    return;
#else
    float f = float(background) / float(k * k);
    o_color = vec4(f >= 1.0 ? sky : c.rgb + f * (sky - envmap_clear), c.a);
#endif
}
