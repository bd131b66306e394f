// aa: TAA that upsamples (TAAU): the frame is rendered at the render size (core.render_scale of
// the output) and the history is kept at the output size, reconstructed from the jittered frames.
// Karis 2014 (taa.frag) for everything but the reconstruction: jitter, reprojection by the motion
// of the nearest surface, clipping to the YCoCg box of the 3x3 render-size neighbourhood,
// disocclusion rejection. The reconstruction follows Yang et al. 2009 ("Amortized supersampling",
// SIGGRAPH Asia 2009): each new sample enters an output pixel's history with a weight given by its
// distance to the pixel's centre, so a pixel that a jittered sample falls close to takes it in
// fully and one it falls far from barely changes; over the frames the jitter sweeps every output
// pixel (written here from the papers' descriptions):
//   - the samples: the 3x3 render texels around the one whose jittered sample lies nearest; texel
//     q was sampled at (q + 0.5 - jitter) render pixels, unjittered;
//   - their weights: w = exp(-2.29 d^2), d the distance in output pixels: a Gaussian fit to a
//     Blackman-Harris window (the filter Karis 2014 gives the current frame's samples); 1 for a
//     sample at the pixel's centre, as a TAA frame's sample is to its pixel. At render scale s a
//     frame brings an output pixel 1.37 s^2 of weight on average (pi / 2.29 per sample, s^2
//     samples per output pixel): a still gathers over 1 / s^2 more frames (aa.c lengthens the
//     jitter sequence and the still to match);
//   - the blend: history h of weight N (alpha), new samples' sum S of weight W:
//     (N h + S) / (N + W); in motion N + W is capped at taa_frames frames' worth of samples
//     (aa_cap = 1.37 s^2 taa_frames, aa.c), so the new samples' share is 1 / taa_frames on average,
//     as in TAA: the history follows motion as fast, and is as short, as TAA's;
//   - the history is read through a Catmull-Rom spline (below) and clipped to the box of the 3x3
//     render-size neighbourhood (Karis 2014);
//   - without a history (the first frame, disocclusion, off the last frame): h = the bilinear
//     interpolation of this frame at the pixel with a weight of 0.5 (half a sample), so a pixel
//     that no sample lies near shows the bilinear scale-up, and samples replace it as they come.
// AA_STILL 1: a still's frames (nothing moved: no reprojection, clip or rejection; no cap, so the
// still is the weighted mean of all its frames); AA_FIRST 1: a frame without a history.
#include "sl:common.glsl"
in vec2 v_uv;
// AA_CLAMP, AA_REJECT (0 or 1) as in taa.frag
#include "taa_common.glsl"
uniform vec2 aa_jitter; // this frame's jitter in render pixels (sl_frame.jitter)
uniform float aa_cap;   // in motion: the largest weight of history and new samples together

const float AA_BILINEAR_WEIGHT = 0.5;

// The history at uv through a Catmull-Rom spline instead of bilinearly: resampling the history
// every frame blurs it by the bilinear tent each time (Yang et al. 2009 analyse this blur), and
// it builds up over the frames a history lasts. The 4x4 texel spline as bilinear taps (the middle
// two weights of each axis share one tap at their weighted position), the four corner taps left
// out (their weights, products of two outer weights, are 0.0055 at most in size) and the rest
// renormalised; the frames (alpha) from the middle tap. Clamped at 0 (the spline overshoots).
vec4 aa_history_at(vec2 uv) {
    vec2 size = vec2(textureSize(aa_history, 0));
    vec2 t = uv * size - 0.5, i = floor(t), f = t - i;
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    vec2 w12 = w1 + w2;
    vec2 at0 = (i - 0.5) / size, at12 = (i + 0.5 + w2 / w12) / size, at3 = (i + 2.5) / size;
    vec4 mid = textureLod(aa_history, at12, 0.0);
    float wm = w12.x * w12.y, wl = w0.x * w12.y, wr = w3.x * w12.y, wb = w12.x * w0.y, wt = w12.x * w3.y;
    vec3 c = mid.rgb * wm + textureLod(aa_history, vec2(at0.x, at12.y), 0.0).rgb * wl +
             textureLod(aa_history, vec2(at3.x, at12.y), 0.0).rgb * wr +
             textureLod(aa_history, vec2(at12.x, at0.y), 0.0).rgb * wb +
             textureLod(aa_history, vec2(at12.x, at3.y), 0.0).rgb * wt;
    return vec4(max(c / (wm + wl + wr + wb + wt), vec3(0.0)), mid.a);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 osize = textureSize(aa_history, 0), size = textureSize(aa_color, 0);
    vec2 ratio = vec2(size) / vec2(osize); // render pixels per output pixel (the render scale)
    vec2 uv = (vec2(p) + 0.5) / vec2(osize);
    vec2 at = uv * vec2(size);             // the pixel's centre in render pixels, unjittered
    ivec2 centre = clamp(ivec2(floor(at + aa_jitter)), ivec2(0), size - 1);
    vec2 base = floor(at + aa_jitter - 0.5); // the bilinear footprint's lower texel
    vec2 f = at + aa_jitter - 0.5 - base;

    vec3 lo = vec3(1e30), hi = vec3(-1e30), sum = vec3(0.0), bilinear = vec3(0.0);
    float weight = 0.0, nearest = 2.0;
    ivec2 nearest_at = centre;
    float z[9];
    bool bad = false;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 q = centre + ivec2(i, j);
            bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
            q = clamp(q, ivec2(0), size - 1);
            vec3 c = texelFetch(aa_color, q, 0).rgb;
            bad = bad || (i == 0 && j == 0 && any(isnan(c)));
            c = mix(c, vec3(0.0), bvec3(isnan(c)));
            vec2 d = (vec2(q) + 0.5 - aa_jitter - at) / ratio;
            float w = inside ? exp(-2.29 * dot(d, d)) : 0.0;
            sum += w * c;
            weight += w;
            // bilinear at the pixel's (jittered) position: the 2x2 texels from base
            vec2 t = vec2(centre + ivec2(i, j)) - base;
            if (all(greaterThanEqual(t, vec2(0.0))) && all(lessThanEqual(t, vec2(1.0))))
                bilinear += c * mix(1.0 - f.x, f.x, t.x) * mix(1.0 - f.y, f.y, t.y);
#if !defined(AA_STILL) && !defined(AA_FIRST)
            vec3 y = aa_ycocg(c);
            lo = min(lo, y);
            hi = max(hi, y);
            float depth = texelFetch(aa_depth, aa_depth_texel(q, size), 0).r;
            z[(j + 1) * 3 + i + 1] = depth;
            if (depth < nearest) { nearest = depth; nearest_at = q; }
#endif
        }
    if (bad) { // a shading bug stays visible, not averaged away (as taa.frag)
        aa_write(vec3(texelFetch(aa_color, centre, 0).rgb), 0.0);
        return;
    }

    vec3 h = bilinear;
    float frames = AA_BILINEAR_WEIGHT, cap = aa_cap;
#if defined(AA_STILL)
    vec4 hist = texelFetch(aa_history, p, 0);
    if (!any(isnan(hist))) h = hist.rgb, frames = hist.a;
    cap = 1e30;
#elif !defined(AA_FIRST)
    vec2 motion = texelFetch(aa_motion, aa_depth_texel(nearest_at, size), 0).rg;
    vec2 uv_prev = uv - motion;
    bool keep = all(greaterThanEqual(uv_prev, vec2(0.0))) && all(lessThanEqual(uv_prev, vec2(1.0)));
#if AA_REJECT
    keep = keep && aa_history_visible(uv_prev, centre, size, z);
#endif
    if (keep) {
        vec4 hist = aa_history_at(uv_prev);
        if (!any(isnan(hist))) {
            h = hist.rgb, frames = max(hist.a, AA_BILINEAR_WEIGHT);
#if AA_CLAMP
            h = aa_rgb(aa_clip(aa_ycocg(h), lo, hi));
#endif
        }
    }
#endif
    float n = max(min(frames + weight, cap), weight);
    aa_write(h + (sum - weight * h) / n, n);
}
