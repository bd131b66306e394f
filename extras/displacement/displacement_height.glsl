// displacement: the height field H(uv) in [0, 1] of a material (displacement.c). The surface is the
// polygon pushed along its normal by  h = scale · (H − 1):  the polygon is the top of the relief
// (H = 1) and H = 0 lies `scale` below it, as parallax occlusion mapping assumes — so true
// displacement and the parallax methods describe the same surface and compare pixel for pixel.
// tests/height.h evaluates the same formulas in C for the CPU-displaced reference meshes.

float displacement_H(vec2 uv) {
#ifdef SL_MAT_HAS_HEIGHT_MAP
    return clamp(textureLod(sl_mat_height_map, uv, 0.0).r, 0.0, 1.0);
#else
    float f = sl_mat_height_frequency;
    vec2 d = uv - 0.5;
#if SL_MAT_HEIGHT_FUNCTION == SL_MAT_HEIGHT_FUNCTION_BUMP
    // a Gaussian bump at the centre of the UV square
    return exp(-dot(d, d) * f * f);
#elif SL_MAT_HEIGHT_FUNCTION == SL_MAT_HEIGHT_FUNCTION_WAVES
    return 0.5 + 0.5 * sin(2.0 * SL_PI * f * uv.x) * sin(2.0 * SL_PI * f * uv.y);
#elif SL_MAT_HEIGHT_FUNCTION == SL_MAT_HEIGHT_FUNCTION_BARK
    // bark of a trunk, u around (f grooves, periodic in u), v along the height: narrow grooves
    // that wander sideways with the height, flat ridges between them; 0 depth at the rims
    float x = f * uv.x + 0.18 * sin(2.0 * SL_PI * 2.0 * uv.y) + 0.07 * sin(2.0 * SL_PI * 7.0 * uv.y + 3.0 * floor(f * uv.x));
    float g = abs(fract(x) - 0.5) * 2.0;           // 1 mid-groove, 0 mid-ridge
    float H = 1.0 - smoothstep(0.55, 0.95, g);     // grooves 40 % of the width
    float rim = smoothstep(0.0, 0.04, uv.y) * smoothstep(0.0, 0.04, 1.0 - uv.y);
    return mix(1.0, H, rim);
#else // RINGS: growth rings of a sawn end, planar UVs, centre at (0.5, 0.5), rim at radius 0.5
    float r = 2.0 * length(d);
    float phi = atan(d.y, d.x);
    float ring = fract(f * r * (1.0 + 0.04 * sin(3.0 * phi)) + 0.1 * r);
    float H = 0.75 + 0.25 * smoothstep(0.0, 0.3, ring) * (1.0 - smoothstep(0.7, 1.0, ring));
    return mix(H, 1.0, smoothstep(0.9, 0.98, r));
#endif
#endif
}

// h = scale · (H − 1), object-space metres along the normal
float displacement_h(vec2 uv, float scale) { return scale * (displacement_H(uv) - 1.0); }
