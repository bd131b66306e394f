/* The envmap tests' program loader for the prefilter's GL steps (em_*_gl take a loader): each
 * program is built from the plugin's GLSL directory with the core's composer, kept, and freed by
 * free_programs() at the end of the test. */
#ifndef ENVMAP_TESTS_PROGRAM_LOADER_H
#define ENVMAP_TESTS_PROGRAM_LOADER_H
#include "render/composer.h"
#include <stdio.h>

static sl_program *programs[8];
static int program_count;
static unsigned loader(void *user, const char *frag, const char *defines) {
    (void)user;
    char err[16384] = "";
    sl_program *p = sl_program_from_files(ENVMAP_GLSL_DIR, "sl:fullscreen.vert", frag, defines, err, sizeof err);
    if (!p->id) fprintf(stderr, "%s\n", err);
    if (program_count < 8) programs[program_count++] = p;
    return p->id;
}
static void free_programs(void) {
    for (int i = 0; i < program_count; i++) sl_program_free(programs[i]);
    program_count = 0;
}
#endif
