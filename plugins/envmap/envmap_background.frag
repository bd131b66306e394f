// The environment as background: after the forward pass, pixels the geometry did not cover
// (depth still at the cleared 1.0) show the source map along the view ray. ENVMAP_IN_PLACE: drawn
// into the forward pass's targets with a depth test that only those pixels pass (envmap.c). With SSAA the depth
// is k× larger than "color": a pixel whose k×k samples are partly background had the core's
// constant clear colour resolved into it, which is swapped for the sky in proportion.
#include "envmap_common.glsl"
uniform sampler2D envmap_color;
uniform sampler2D envmap_depth;
uniform vec2 envmap_src_size;
uniform mat3 envmap_rot;
uniform float envmap_scale;
uniform vec3 envmap_clear;        // what the core cleared "color" to
uniform mat4 envmap_inv_view_proj;
uniform vec2 envmap_viewport;
uniform float envmap_pixel_angle; // radians per pixel at the centre of the view
uniform vec2 envmap_jitter;       // the frame's projection offset (sl_frame.jitter), pixels
vec2 envmap_to_centre;            // from this fragment's sample to its pixel's centre (main)
// ENVMAP_SOURCE_CUBE: the source is a cube; ENVMAP_SOURCE_SKY: the procedural sky, evaluated here
// per pixel (cube.c, em_sky_radiance: the same terms), with its sun disk box-filtered over the
// pixel in closed form; else a lat-long (a permutation: see envmap_to_cube.frag)
#if defined(ENVMAP_SOURCE_CUBE)
uniform samplerCube envmap_srccube;
#elif defined(ENVMAP_SOURCE_SKY)
uniform vec3 envmap_sky_sun;          // unit, towards the sun (map frame)
uniform float envmap_sky_sun_radius;  // radians
uniform vec3 envmap_sky_sun_radiance; // E / Ω times the sun's colour (ENVMAP_SKY_SUN: not 0)
uniform vec3 envmap_sky_ground;       // below the horizon
// The sky without its sun disk.
vec3 envmap_sky(vec3 d) {
    const vec3 zenith = vec3(0.16, 0.30, 0.72), horizon = vec3(0.70, 0.78, 0.92);
    float y = d.y;
    float angle = acos(clamp(dot(d, envmap_sky_sun), -1.0, 1.0));
    vec3 sky = y >= 0.0 ? mix(zenith, horizon, pow(1.0 - y, 4.0)) : mix(envmap_sky_ground, horizon, exp(y * 25.0));
    float halo = (y > -0.05 ? 1.0 : 0.0) * (0.6 * exp(-angle * 8.0) + 0.15 * exp(-angle * 1.5));
    return sky + halo * vec3(1.0, 0.9, 0.75);
}
// Share of a unit square (side 1, centred) on the inner side of a line at signed distance s from
// its centre, with unit normal n: the box filter of a straight edge, exact (linear in the middle,
// quadratic where the line cuts a corner).
float envmap_square_share(float s, vec2 n) {
    float p = max(abs(n.x), abs(n.y)), q = min(abs(n.x), abs(n.y));
    float h = 0.5 * (p + q), k = 0.5 * (p - q), corner = 2.0 * p * max(q, 1e-6);
    if (s <= -h) return 0.0;
    if (s < -k) return (s + h) * (s + h) / corner;
    if (s <= k) return 0.5 + s / p;
    if (s < h) return 1.0 - (h - s) * (h - s) / corner;
    return 1.0;
}
// Share of this pixel covered by the sun's disk, d the (jittered) ray of this fragment, dx and dy
// its change per pixel. The disk is box-filtered over the pixel of the unjittered view, so every
// frame of a TAA still, and a frame in motion, gives the value a path tracer's pixel converges to
// (16 jittered point samples left 1/16 steps along the edge). The chord c = |d − sun| is linear
// across the pixel: its gradient g (pixels) moves it from the jittered sample to the pixel's centre
// (envmap_to_centre), and the disk's edge is a straight line at distance (c_r − c)/|g|; a
// disk under about a pixel across is an axis-aligned square of the same area instead (two 1-D
// overlaps: it keeps the sun's energy where the straight edge would fill whole pixels).
float envmap_sun_share(vec3 d, vec3 dx, vec3 dy) {
    float cr = 2.0 * sin(0.5 * envmap_sky_sun_radius);
    vec3 e = d - envmap_sky_sun;
    float c = length(e);
    vec2 g = vec2(dot(e, dx), dot(e, dy)) / max(c, 1e-9);
    c += dot(g, envmap_to_centre);
    float gl = length(g);
    if (!(gl > 1e-9)) return c < cr ? 1.0 : 0.0;
    vec2 n = g / gl;
    float r = cr / gl; // the disk's radius in pixels
    // the circle bends away from its tangent by t²/2r at t along it: 1/24r on average over the pixel
    float edge = envmap_square_share((cr - c) / gl - 1.0 / (24.0 * r), n);
    vec2 o = -n * (c / gl), side = vec2(1.7724539 * r); // √π r: the square of the disk's area
    vec2 ov = clamp(min(o + 0.5 * side, 0.5) - max(o - 0.5 * side, -0.5), 0.0, 1.0);
    return mix(ov.x * ov.y, edge, smoothstep(0.75, 1.5, r));
}
#else
uniform sampler2D envmap_src2d;
#endif
layout(location = 0) out vec4 o_color;

void main() {
    vec2 at = gl_FragCoord.xy;
#ifndef ENVMAP_IN_PLACE
    ivec2 p = ivec2(gl_FragCoord.xy);
    int k = max(textureSize(envmap_depth, 0).x / max(textureSize(envmap_color, 0).x, 1), 1);
    // Under core.ssaa = k the frame's jitter is a TAA's request over k (each of the forward pass's
    // k × k samples stays in its cell); this pass samples once per pixel, so it moves its sample
    // k times as far: over a still's frames it sweeps the whole pixel, the box filter.
    at -= float(k - 1) * envmap_jitter;
    envmap_to_centre = float(k) * envmap_jitter;
#else
    envmap_to_centre = envmap_jitter;
#endif
    vec2 ndc = at / envmap_viewport * 2.0 - 1.0;
    vec4 a = envmap_inv_view_proj * vec4(ndc, -1.0, 1.0), b = envmap_inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 d = envmap_rot * normalize(b.xyz / b.w - a.xyz / a.w);
#if defined(ENVMAP_SKY_SUN)
    float sun = envmap_sun_share(d, dFdx(d), dFdy(d)); // derivatives before any return
#endif
#ifndef ENVMAP_IN_PLACE
    vec4 c = texelFetch(envmap_color, p, 0);
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
    vec3 sky;
#if defined(ENVMAP_SOURCE_CUBE)
    float lod = max(0.0, log2(envmap_pixel_angle / (0.5 * ENVMAP_PI / envmap_src_size.x)));
    sky = textureLod(envmap_srccube, d, lod).rgb;
#elif defined(ENVMAP_SOURCE_SKY)
    sky = envmap_sky(d);
#if defined(ENVMAP_SKY_SUN)
    sky += sun * envmap_sky_sun_radiance;
#endif
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
