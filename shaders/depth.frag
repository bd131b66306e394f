// Depth-only fragment stage (shadow maps): nothing to write but depth, except that a glTF
// alphaMode MASK material (alpha_cutoff) cuts out the same texels as its colour pass does, and a
// BLEND material (alpha_blend) keeps a fraction of its texels equal to its coverage a: an ordered
// dither (Bayer 1973) over 4×4 blocks of the target's pixels, so a shadow map filtered over a
// block lets 1 − a of the light through, as Blender's glTF importer sets up BLEND materials
// (shadow mode "alpha hashed"; Wyman & McGuire 2017, "Hashed Alpha Testing") without the noise.
#if defined(SL_MAT_HAS_ALPHA_CUTOFF) || defined(SL_ALPHA_BLENDED)
in vec2 v_uv;
#ifdef SL_MAT_USES_UV1
in vec2 v_uv1;
#endif
#ifdef SL_ALPHA_BLENDED
// The 4×4 Bayer matrix's threshold at pixel p, (index + ½)/16: index = 4·(2·a0 + b0) + 2·a1 + b1
// with a = x xor y, b = y (bit k of each), the recursive construction written out for 2 levels.
float sl_dither_threshold(ivec2 p) {
    int a = (p.x ^ p.y) & 3, b = p.y & 3;
    int index = 4 * (2 * (a & 1) + (b & 1)) + 2 * (a >> 1) + (b >> 1);
    return (float(index) + 0.5) / 16.0;
}
#endif
void main() {
    SlSurface s;
    s.uv = v_uv;
#ifdef SL_MAT_USES_UV1
    s.uv1 = v_uv1;
#else
    s.uv1 = v_uv;
#endif
    float a = sl_coverage(s);
#ifdef SL_MAT_HAS_ALPHA_CUTOFF
    if (a < sl_mat_alpha_cutoff) discard;
#endif
#ifdef SL_ALPHA_BLENDED
    if (a < sl_dither_threshold(ivec2(gl_FragCoord.xy))) discard;
#endif
}
#else
void main() {}
#endif
