// tp-tagged (test plugin): a node-tag gated vertex hook and an object_position debug view.
#ifdef SL_MAT_HAS_TP_TAG_LIFT
void tp_tagged_vertex(inout SlVertex v) { v.position.y += sl_mat_tp_tag_lift; }
#endif
vec3 tp_tagged_object_position(SlSurface s) { return s.object_position; }
void tp_tagged_surface(inout SlSurface s) {}
