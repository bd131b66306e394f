// sss texture space: after the blurs, extends the summed result one texel beyond every UV chart
// edge by linear extrapolation, 2·c(+1) − c(+2) towards each covered neighbour (averaged; clamped
// at 0). The final pass looks the result up bilinearly at the surface's uv: at a chart edge or a
// seam that look-up then continues the gradient up to the edge instead of holding the last
// texel's value, so the two sides of a seam meet. Covered texels pass through unchanged.
uniform sampler2D sss_src;   // premultiplied, coverage in alpha

layout(location = 0) out vec4 o_color;

vec4 sss_fetch(ivec2 q) {
    ivec2 size = textureSize(sss_src, 0);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return vec4(0.0);
    return texelFetch(sss_src, q, 0);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 c = sss_fetch(p);
    if (c.a > 0.0) { o_color = c; return; }
    const ivec2 dirs[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    vec3 sum = vec3(0.0);
    float n = 0.0;
    for (int k = 0; k < 4; ++k) {
        vec4 c1 = sss_fetch(p + dirs[k]);
        if (c1.a <= 0.0) continue;
        vec4 c2 = sss_fetch(p + 2 * dirs[k]);
        vec3 v1 = c1.rgb / c1.a;
        sum += c2.a > 0.0 ? max(2.0 * v1 - c2.rgb / c2.a, vec3(0.0)) : v1;
        n += 1.0;
    }
    o_color = n > 0.0 ? vec4(sum / n, 1.0) : vec4(0.0);
}
