/* The command line of shadelab: one table of options (core/cli.c) drives the parser, --help and
 * the option table in README.md (--help-markdown; tools/readme-options.sh writes it there). */
#ifndef SL_CLI_H
#define SL_CLI_H
#include "app.h"
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct sl_cli {
    sl_app_options opt;
    const char *output, *stats, *reference, *auto_quality;
    int frames;       /* -1: not given */
    int turntable;    /* 0: no turntable */
    bool headless, list_plugins, list_views, dump_params, explain, bench, help_keys, list_cameras;
    double start_time;
    double still_budget; /* seconds; 0: none (core/still.h) */
    char budget_setting[64]; /* --budget as the setting core.budget=MS */
} sl_cli;

typedef enum sl_cli_result {
    SL_CLI_RUN,   /* parsed: go on */
    SL_CLI_ERROR, /* err holds the message */
    SL_CLI_DONE,  /* --help, --version and the like printed their answer: exit 0 */
} sl_cli_result;

sl_cli_result sl_cli_parse(int argc, char **argv, sl_cli *c, char *err, size_t n);

/* --help: the options with their descriptions, wrapped for a terminal. */
void sl_cli_print_help(FILE *f);
/* --help-markdown: the same as a Markdown table (the region of README.md between
 * <!-- options:begin --> and <!-- options:end -->). */
void sl_cli_print_markdown(FILE *f);

/* --output names a video (encoded by ffmpeg from the turntable's PNG frames). */
bool sl_cli_is_video(const char *path);
#endif
