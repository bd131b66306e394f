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
// motion is 0. AA_FBFETCH (with AA_STILL, where the GL has EXT_shader_framebuffer_fetch): the
// history is read from the target it is written to, in place: on llvmpipe a framebuffer read of
// the RGBA32F history costs much less than a texel fetch from the other history (aa.c).
#include "sl:common.glsl"
in vec2 v_uv;
// AA_CLAMP, AA_REJECT (0 or 1): the neighbourhood clip and the disocclusion test, a permutation
// (aa.c): a still runs neither, and on llvmpipe a uniform switch would run both under a mask.
#include "taa_common.glsl"

#if defined(AA_STILL)
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(aa_color, p, 0).rgb;
    if (any(isnan(c))) { // a shading bug stays visible, not averaged away (the next frame drops it)
        aa_write(c, 0.0);
        return;
    }
#if defined(AA_FBFETCH)
    vec4 hist = o_history;
#else
    vec4 hist = texelFetch(aa_history, p, 0);
#endif
    bool bad = any(isnan(hist));
    float n = min((bad ? 0.0 : hist.a) + 1.0, float(aa_frames));
    aa_write(mix(bad ? c : hist.rgb, c, 1.0 / n), n);
}
#else
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
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    float nearest = 2.0, z[9];
    ivec2 nearest_at = p;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 q = clamp(p + ivec2(i, j), ivec2(0), size - 1);
            vec3 n = texelFetch(aa_color, q, 0).rgb;
            n = aa_ycocg(mix(n, vec3(0.0), bvec3(isnan(n))));
            lo = min(lo, n);
            hi = max(hi, n);
            float d = texelFetch(aa_depth, aa_depth_texel(q, size), 0).r;
            z[(j + 1) * 3 + i + 1] = d;
            if (d < nearest) { nearest = d; nearest_at = q; }
        }
    vec2 motion = texelFetch(aa_motion, aa_depth_texel(nearest_at, size), 0).rg;
    vec2 uv_prev = uv - motion;

    float frames = 0.0;
    vec3 h = c;
    bool keep = all(greaterThanEqual(uv_prev, vec2(0.0))) && all(lessThanEqual(uv_prev, vec2(1.0)));
#if AA_REJECT
    keep = keep && aa_history_visible(uv_prev, p, size, z);
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
