// The depth pre-pass's main (pass.h, ABI 1.13), composed into each opaque material's program in
// place of the core's (SL_CUSTOM_MAIN): the material's surface hooks run, so "normal" holds the
// normal-mapped shading normal, exactly what the forward pass would write; no lighting is computed.
layout(location = 0) out vec4 o_normal;

void main() {
    SlSurface s = sl_surface_from_varyings();
#ifdef SL_MAT_HAS_ALPHA_CUTOFF
    if (sl_coverage(s) < sl_mat_alpha_cutoff) discard; // glTF alphaMode MASK, as the forward pass
#endif
    sl_run_surface_hooks(s);
    o_normal = sl_normal_target(s);
}
