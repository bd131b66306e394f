/* A dependency library that the "missing dependency" variant links against; the test runs
 * with it out of the loader's reach. */
int tp_dependency_value(void) { return 42; }
