// aa: temporal antialiasing after B. Karis, "High Quality Temporal Supersampling", SIGGRAPH 2014
// course Advances in Real-Time Rendering (written here from the talk's description):
//   - the core renders every frame with a sub-pixel jitter (Halton 2,3, set in aa.c);
//   - the history is reprojected with the core's motion vectors, taken from the nearest surface of
//     the 3x3 neighbourhood (so silhouettes of moving objects carry their own motion);
//   - the history is clipped to the axis-aligned box of the current 3x3 neighbourhood in YCoCg
//     (neighbourhood clamping: what the history shows must be plausible now: no ghosts);
//   - disocclusion: the history is dropped where it falls outside the last frame or where the
//     surface the last frame saw there (its depth, reconstructed to world space) is not this one;
//   - blend: the first taa_frames frames of a pixel's history are averaged equally (a still is the
//     exact mean of taa_frames jittered frames, the box filter the reference computes), later
//     frames have weight 1/taa_frames. Blended in linear radiance; Karis's luminance weighting
//     against HDR flicker is left out because it biases the mean away from the box filter.
// Outputs, in one draw: the new history (rgb, and the number of frames in it in alpha) and the
// pass's "color" output, through the pointwise passes fused into TAA's pass (tone mapping:
// sl_pointwise_epilogue, ext/post.h). A frame without a history (the first, or after a cut) does
// not run this program: taa_copy.frag copies the frame as it is into both.
// AA_STILL 1: the program of a still (nothing moved since the history began, so the history at
// this pixel is this pixel's own earlier frames: no reprojection, neighbourhood or rejection),
// the running mean alone; its value equals the resolve's without clip and rejection, where the
// motion is 0.
#include "sl:common.glsl"
in vec2 v_uv;
uniform sampler2D aa_color;       // this frame, jittered (nearest)
uniform sampler2D aa_depth;       // this frame's depth (maybe supersampled; nearest)
uniform sampler2D aa_motion;      // "motion": uv now - uv before
uniform sampler2D aa_history;     // bilinear, clamp to edge; alpha = frames in it
uniform sampler2D aa_prev_depth;  // the last frame's depth (nearest)
uniform mat4 aa_inv_view_proj, aa_prev_inv_view_proj;
uniform vec3 aa_camera_pos;
uniform int aa_frames;
// AA_CLAMP, AA_REJECT (0 or 1): the neighbourhood clip and the disocclusion test, a permutation
// (aa.c): a still runs neither, and on llvmpipe a uniform switch would run both under a mask.
layout(location = 0) out vec4 o_color;   // the pass's "color" output
layout(location = 1) out vec4 o_history; // the new history

void aa_write(vec3 c, float frames) {
    o_history = vec4(c, frames);
    o_color = vec4(sl_pointwise_epilogue(c, ivec2(gl_FragCoord.xy)), 1.0);
}

#if defined(AA_STILL)
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(aa_color, p, 0).rgb;
    if (any(isnan(c))) { // a shading bug stays visible, not averaged away (the next frame drops it)
        aa_write(c, 0.0);
        return;
    }
    vec4 hist = texelFetch(aa_history, p, 0);
    bool bad = any(isnan(hist));
    float n = min((bad ? 0.0 : hist.a) + 1.0, float(aa_frames));
    aa_write(mix(bad ? c : hist.rgb, c, 1.0 / n), n);
}
#else
vec3 aa_ycocg(vec3 c) {
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 aa_rgb(vec3 y) { return vec3(y.x + y.y - y.z, y.x + y.z, y.x - y.y - y.z); }

vec3 aa_world(mat4 inv_vp, vec2 uv, float depth) {
    vec4 p = inv_vp * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

// Clip towards the box centre (Karis: clipping keeps the history's hue better than clamping).
vec3 aa_clip(vec3 h, vec3 lo, vec3 hi) {
    vec3 centre = 0.5 * (hi + lo), extent = 0.5 * (hi - lo) + 1e-6;
    vec3 d = h - centre;
    vec3 t = abs(d / extent);
    float m = max(t.x, max(t.y, t.z));
    return m > 1.0 ? centre + d / m : h;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(aa_color, 0);
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    vec3 c = texelFetch(aa_color, p, 0).rgb;
    if (any(isnan(c))) { // a shading bug stays visible, not averaged away (the next frame drops it)
        aa_write(c, 0.0);
        return;
    }

    // 3x3 neighbourhood: colour box (YCoCg) and the nearest surface
    ivec2 dsize = textureSize(aa_depth, 0);
    vec2 dscale = vec2(dsize) / vec2(size);
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    float nearest = 2.0;
    ivec2 nearest_at = p;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 q = clamp(p + ivec2(i, j), ivec2(0), size - 1);
            vec3 n = texelFetch(aa_color, q, 0).rgb;
            n = aa_ycocg(mix(n, vec3(0.0), bvec3(isnan(n))));
            lo = min(lo, n);
            hi = max(hi, n);
            float d = texelFetch(aa_depth, ivec2((vec2(q) + 0.5) * dscale), 0).r;
            if (d < nearest) { nearest = d; nearest_at = q; }
        }
    vec2 motion = texelFetch(aa_motion, ivec2((vec2(nearest_at) + 0.5) * dscale), 0).rg;
    vec2 uv_prev = uv - motion;

    float frames = 0.0;
    vec3 h = c;
    bool keep = all(greaterThanEqual(uv_prev, vec2(0.0))) && all(lessThanEqual(uv_prev, vec2(1.0)));
#if AA_REJECT
    if (keep) {
        // The surface the history shows (the last frame's depth where this pixel came from,
        // reconstructed to world space) must still be visible in this pixel's 3x3 neighbourhood
        // now, within 5 % of the view distance; otherwise it was occluded or has moved away and
        // the history is dropped (disocclusion). The neighbourhood, not the pixel alone: with the
        // jitter an edge pixel sees either side from frame to frame, and both belong to it.
        ivec2 psize = textureSize(aa_prev_depth, 0);
        ivec2 pc = clamp(ivec2(floor(uv_prev * vec2(psize))), ivec2(0), psize - 1);
        vec3 was = aa_world(aa_prev_inv_view_proj, (vec2(pc) + 0.5) / vec2(psize), texelFetch(aa_prev_depth, pc, 0).r);
        float best = 1e30;
        for (int j = -1; j <= 1; ++j)
            for (int i = -1; i <= 1; ++i) {
                ivec2 q = clamp(p + ivec2(i, j), ivec2(0), size - 1);
                ivec2 dq = ivec2((vec2(q) + 0.5) * dscale);
                vec3 w = aa_world(aa_inv_view_proj, (vec2(dq) + 0.5) / vec2(dsize), texelFetch(aa_depth, dq, 0).r);
                best = min(best, distance(w, was));
            }
        keep = best <= 0.05 * distance(was, aa_camera_pos);
    }
#endif
    if (keep) {
        vec4 hist = textureLod(aa_history, uv_prev, 0.0);
        frames = any(isnan(hist)) ? 0.0 : hist.a;
        h = any(isnan(hist)) ? c : hist.rgb;
#if AA_CLAMP
        h = aa_rgb(aa_clip(aa_ycocg(h), lo, hi));
#endif
    }
    float n = min(frames + 1.0, float(aa_frames));
    aa_write(mix(h, c, 1.0 / n), n);
}
#endif
