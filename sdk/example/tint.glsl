// SURFACE hook of the SDK example: void FN(inout SlSurface s), run after the core filled the
// surface record and before lighting. The host declares the plugin's global parameters as
// uniforms named <plugin>_<param> (example_tint_color, example_tint_strength); example.tint needs
// a recompile, so it arrives as the #define EXAMPLE_TINT (0 or 1) instead.
void example_tint(inout SlSurface s) {
#if EXAMPLE_TINT
    s.base_color = mix(s.base_color, s.base_color * example_tint_color, example_tint_strength);
#endif
}
