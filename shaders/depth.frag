// Depth-only fragment stage (shadow maps): nothing to write but depth.
void main() {}
