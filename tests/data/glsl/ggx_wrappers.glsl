// Test wrapper: ggx_DG_over_4 with its out parameter, for expression evaluation.
float test_ggx_dg(vec3 l, vec3 v, float alpha) {
    vec3 h;
    return ggx_DG_over_4(vec3(0.0, 0.0, 1.0), l, v, alpha, h);
}
