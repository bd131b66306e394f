// Depth-only fragment stage (shadow maps): nothing to write but depth, except that a glTF
// alphaMode MASK material (alpha_cutoff) cuts out the same texels as its colour pass does.
#ifdef SL_MAT_HAS_ALPHA_CUTOFF
in vec2 v_uv;
#ifdef SL_MAT_USES_UV1
in vec2 v_uv1;
#endif
void main() {
    SlSurface s;
    s.uv = v_uv;
#ifdef SL_MAT_USES_UV1
    s.uv1 = v_uv1;
#else
    s.uv1 = v_uv;
#endif
    if (sl_coverage(s) < sl_mat_alpha_cutoff) discard;
}
#else
void main() {}
#endif
