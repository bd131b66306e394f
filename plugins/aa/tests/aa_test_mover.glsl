// aa-test-mover: object-space translation along +x at sl_mat_aa_test_speed units per second.
void aa_test_move(inout SlVertex v) { v.position.x += sl_mat_aa_test_speed * sl_time; }
