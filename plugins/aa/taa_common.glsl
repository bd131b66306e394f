// aa: what TAA's resolve (taa.frag) and its upsampler (taau.frag) share: their inputs, outputs and
// the steps of Karis 2014 both take (see taa.frag's header).
uniform sampler2D aa_color;       // this frame, jittered (nearest), at the render size
uniform sampler2D aa_depth;       // this frame's depth (maybe supersampled; nearest)
uniform sampler2D aa_motion;      // "motion": uv now - uv before
uniform sampler2D aa_history;     // bilinear, clamp to edge; alpha = frames (weight) in it
uniform sampler2D aa_prev_depth;  // the last frame's depth (nearest)
uniform mat4 aa_inv_view_proj, aa_prev_inv_view_proj;
uniform vec3 aa_camera_pos;
uniform int aa_frames;
layout(location = 0) out vec4 o_color;   // the pass's "color" output
#if defined(AA_FBFETCH)
// a still where EXT_shader_framebuffer_fetch exists (aa.c): the history is updated in place, read
// as it stands in the target (no texture fetch, no second history)
layout(location = 1) inout vec4 o_history;
#else
layout(location = 1) out vec4 o_history; // the new history
#endif

void aa_write(vec3 c, float frames) {
    o_history = vec4(c, frames);
    o_color = vec4(sl_pointwise_epilogue(c, ivec2(gl_FragCoord.xy)), 1.0);
}

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

// Disocclusion: the surface the history shows (the last frame's depth where it came from, uv_prev,
// reconstructed to world space) must still be visible in the 3x3 neighbourhood of texel p of
// "color" (size) now, within 5 % of the view distance; otherwise it was occluded or has moved away
// and the history is dropped. The neighbourhood, not the pixel alone: with the jitter an edge pixel
// sees either side from frame to frame, and both belong to it. z: the neighbourhood's depths, row
// by row from (-1, -1), as aa_depth_at reads them.
vec2 aa_depth_scale(ivec2 size) { return vec2(textureSize(aa_depth, 0)) / vec2(size); }
ivec2 aa_depth_texel(ivec2 q, ivec2 size) { return ivec2((vec2(q) + 0.5) * aa_depth_scale(size)); }
bool aa_history_visible(vec2 uv_prev, ivec2 p, ivec2 size, float z[9]) {
    vec2 dsize = vec2(textureSize(aa_depth, 0));
    ivec2 psize = textureSize(aa_prev_depth, 0);
    ivec2 pc = clamp(ivec2(floor(uv_prev * vec2(psize))), ivec2(0), psize - 1);
    vec3 was = aa_world(aa_prev_inv_view_proj, (vec2(pc) + 0.5) / vec2(psize), texelFetch(aa_prev_depth, pc, 0).r);
    float best = 1e30;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 dq = aa_depth_texel(clamp(p + ivec2(i, j), ivec2(0), size - 1), size);
            vec3 w = aa_world(aa_inv_view_proj, (vec2(dq) + 0.5) / dsize, z[(j + 1) * 3 + i + 1]);
            best = min(best, distance(w, was));
        }
    return best <= 0.05 * distance(was, aa_camera_pos);
}
