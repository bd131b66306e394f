// displacement: DISPLACEMENT hook (SDK 1.7, sdk shader.h) of materials carrying `displace`: the
// core tessellates their triangles in every pass and moves each generated vertex by the height
// returned here; the edge level comes from the edge's length on screen (displacement.edge_px).
#include "displacement_height.glsl"

float displacement_height(SlVertex v) { return displacement_h(v.uv, sl_mat_displace); }

// about one generated segment per `edge_px` pixels of the edge seen from the camera
float displacement_edge_level(vec3 a, vec3 b) { return sl_tess_screen_level(a, b, displacement_edge_px); }
