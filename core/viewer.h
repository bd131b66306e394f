/* The interactive window viewer (GLFW backend only). */
#ifndef SL_VIEWER_H
#define SL_VIEWER_H
#include "app.h"
#include <stdio.h>

/* Runs until the window closes; returns the exit code. */
int sl_viewer_run(sl_app *app, double start_time);
/* --help-keys: the viewer's keys and every plugin's key bindings. */
void sl_viewer_print_keys(sl_app *app, FILE *f);
#endif
