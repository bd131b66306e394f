// Helpers of the tessellation stages of displaced materials (sdk shader.h, DISPLACEMENT, ABI 1.7).

// The frame's camera, set by the host for tessellated programs in every pass (shadow maps too): a
// level computed from it is the same in every pass, so the surface a shadow map sees is the one
// the camera sees. pixels per unit length at unit distance (perspective) or at any distance
// (orthographic).
uniform float sl_tess_pixel_scale;
uniform int sl_tess_orthographic;

// Wanted level of an edge whose world-space endpoints are a and b: its length in pixels as seen
// from the frame's camera, over target_px. The edge's length over the distance of its midpoint
// (the projected diameter of the sphere around it), not the projected endpoints: no trouble with
// edges crossing the camera plane, and it depends on nothing but the two endpoints.
float sl_tess_screen_level(vec3 a, vec3 b, float target_px) {
    float len = distance(a, b);
    float dist = sl_tess_orthographic != 0 ? 1.0 : max(distance(0.5 * (a + b), sl_camera_pos), 1e-4);
    return len * sl_tess_pixel_scale / (dist * max(target_px, 1e-3));
}
