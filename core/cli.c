/* The command line: the option table below is the one list of shadelab's options. The parser
 * reads it, --help prints it, --help-markdown prints it as README.md's option table (the
 * readme_options test fails when README.md's copy differs; tools/readme-options.sh rewrites it). */
#include "cli.h"
#include "backend/backend.h"
#include "log.h"
#include "scene/scene.h"
#include <shadelab/input.h>
#include <shadelab/shadelab.h>
#include <string.h>
#include <strings.h>

typedef enum option_kind {
    OPTION_FLAG,  /* sets a bool of sl_cli */
    OPTION_TEXT,  /* keeps its value in a const char * of sl_cli */
    OPTION_WHOLE, /* a whole number min..max into an int of sl_cli */
    OPTION_CALL,  /* anything else: call(c, value) */
} option_kind;

typedef struct option {
    const char *name;  /* "--size" */
    const char *alias; /* "-v"; "FILE" for the scene given without --scene; NULL */
    const char *arg;   /* placeholder of the value ("WxH"); NULL: takes none */
    const char *help;  /* what it does, for README.md (Markdown: `code`) and --help (without the marks) */
    option_kind kind;
    size_t field; /* FLAG, TEXT, WHOLE: offset in sl_cli */
    long min, max; /* WHOLE */
    sl_cli_result (*call)(sl_cli *c, const char *value, char *err, size_t n);
} option;

#define FLAG(f) .kind = OPTION_FLAG, .field = offsetof(sl_cli, f)
#define TEXT(f) .kind = OPTION_TEXT, .field = offsetof(sl_cli, f)
#define WHOLE(f, lo, hi) .kind = OPTION_WHOLE, .field = offsetof(sl_cli, f), .min = lo, .max = hi
#define CALL(fn) .kind = OPTION_CALL, .call = fn

static sl_cli_result print_help(sl_cli *c, const char *v, char *err, size_t n) {
    sl_cli_print_help(stdout);
    return SL_CLI_DONE;
}
static sl_cli_result print_markdown(sl_cli *c, const char *v, char *err, size_t n) {
    sl_cli_print_markdown(stdout);
    return SL_CLI_DONE;
}
static sl_cli_result print_version(sl_cli *c, const char *v, char *err, size_t n) {
    printf("shadelab %s (plugin ABI %d.%d)\n", SL_VERSION, SL_ABI_MAJOR, SL_ABI_MINOR);
    return SL_CLI_DONE;
}
static sl_cli_result verbose(sl_cli *c, const char *v, char *err, size_t n) {
    sl_log_threshold = SL_LOG_DEBUG;
    return SL_CLI_RUN;
}
static sl_cli_result quiet(sl_cli *c, const char *v, char *err, size_t n) {
    sl_log_threshold = SL_LOG_WARN;
    return SL_CLI_RUN;
}
static sl_cli_result backend(sl_cli *c, const char *v, char *err, size_t n) {
    if (sl_backend_parse(v, &c->opt.backend)) return SL_CLI_RUN;
    snprintf(err, n, "--backend %s: expected auto, headless, glfw, osmesa or egl", v);
    return SL_CLI_ERROR;
}
static sl_cli_result size(sl_cli *c, const char *v, char *err, size_t n) {
    if (sl_parse_size(v, 16384, &c->opt.width, &c->opt.height)) return SL_CLI_RUN;
    snprintf(err, n, "--size %s: expected WxH, 1..16384 each", v);
    return SL_CLI_ERROR;
}
static sl_cli_result start_time(sl_cli *c, const char *v, char *err, size_t n) {
    if (sl_parse_double(v, -1e9, 1e9, &c->start_time)) return SL_CLI_RUN;
    snprintf(err, n, "--time %s: expected seconds, a finite number within +-1e9", v);
    return SL_CLI_ERROR;
}
static sl_cli_result still_budget(sl_cli *c, const char *v, char *err, size_t n) {
    if (sl_parse_double(v, 0.001, 1e6, &c->still_budget)) return SL_CLI_RUN;
    snprintf(err, n, "--still-budget %s: expected seconds, 0.001 to 1e6", v);
    return SL_CLI_ERROR;
}
static sl_cli_result list_gltf_extensions(sl_cli *c, const char *v, char *err, size_t n) {
    static const char *const support[] = {"rendered", "approximated", "not rendered"};
    int count;
    const sl_gltf_extension *e = sl_gltf_features(&count);
    for (int i = 0; i < count; i++) printf("%-40s %-13s %s\n", e[i].name, support[e[i].support], e[i].what);
    e = sl_gltf_extensions(&count);
    for (int i = 0; i < count; i++) printf("%-40s %-13s %s\n", e[i].name, support[e[i].support], e[i].what);
    printf("(any other extension: not rendered; a file that requires one is refused)\n");
    return SL_CLI_DONE;
}
static sl_cli_result gltf_markdown(sl_cli *c, const char *v, char *err, size_t n) {
    sl_gltf_print_markdown();
    return SL_CLI_DONE;
}
/* --budget 66ms (or 66, or off): the setting core.budget, as --set would give it */
static sl_cli_result budget(sl_cli *c, const char *v, char *err, size_t n) {
    char num[64];
    size_t l = strlen(v);
    snprintf(num, sizeof num, "%.*s", (int)(l > 2 && !strcasecmp(v + l - 2, "ms") ? l - 2 : l), v);
    double ms = 0;
    if (strcasecmp(v, "off") && !sl_parse_double(num, 0, 10000, &ms)) {
        snprintf(err, n, "--budget %s: expected milliseconds (66ms, 66) from 0 to 10000, or off", v);
        return SL_CLI_ERROR;
    }
    if (c->opt.setting_count == 128) { snprintf(err, n, "too many --set (128 at most)"); return SL_CLI_ERROR; }
    snprintf(c->budget_setting, sizeof c->budget_setting, "core.budget=%g", ms);
    c->opt.settings[c->opt.setting_count++] = c->budget_setting;
    return SL_CLI_RUN;
}
static sl_cli_result plugin(sl_cli *c, const char *v, char *err, size_t n) {
    if (c->opt.plugin_count == 64) { snprintf(err, n, "too many --plugin (64 at most)"); return SL_CLI_ERROR; }
    c->opt.plugins[c->opt.plugin_count++] = v;
    return SL_CLI_RUN;
}
static sl_cli_result setting(sl_cli *c, const char *v, char *err, size_t n) {
    if (c->opt.setting_count == 128) { snprintf(err, n, "too many --set (128 at most)"); return SL_CLI_ERROR; }
    c->opt.settings[c->opt.setting_count++] = v;
    return SL_CLI_RUN;
}

static const option options[] = {
    {"--scene", "FILE", "FILE", "a JSON scene or a model file (glTF, OBJ, anything assimp reads; detected by content); "
     "default: the built-in scene", TEXT(opt.scene_path)},
    {"--headless", NULL, NULL, "render without a window (EGL on a GPU, else OSMesa)", FLAG(headless)},
    {"--backend", NULL, "NAME", "`auto` (a window when there is a display), `headless`, `glfw`, `osmesa` or `egl`; "
     "a failure lists every backend tried and why", CALL(backend)},
    {"--size", NULL, "WxH", "viewport size (default 1280x720)", CALL(size)},
    {"--frames", NULL, "N", "render N frames, then write `--output` and exit (headless default: the frames a still "
     "needs)", WHOLE(frames, 1, 1000000)},
    {"--still-budget", NULL, "SECONDS", "a headless still (no `--frames`) stops when SECONDS have passed since its "
     "first frame, or earlier once no display value changes by 1/255 from one frame to the next; default: no "
     "budget", CALL(still_budget)},
    {"--budget", NULL, "MS", "frame-time budget of the window (default `66ms`; `off`): while the view moves, the "
     "render scale and the plugins' quality knobs are chosen per frame for the least predicted error within it; a "
     "still refines to the best settings (`core.budget`, docs/budget.md)", CALL(budget)},
    {"--output", NULL, "FILE", "`.png` (display-encoded) or `.exr` (linear HDR); headless default `out.png`",
     TEXT(output)},
    {"--turntable", NULL, "N", "N frames orbiting the camera once around the scene, written as `OUT-000.png` …; "
     "`--output x.mp4` encodes them with `ffmpeg` when it is installed", WHOLE(turntable, 1, 100000)},
    {"--stats", NULL, "FILE.json", "per-pass and frame times (median, mean, min over the frames)", TEXT(stats)},
    {"--bench", NULL, NULL, "print the median frame and per-pass times (use `--frames` ≥ 30)", FLAG(bench)},
    {"--plugin", NULL, "NAME|PATH", "load a plugin (repeatable)", CALL(plugin)},
    {"--set", NULL, "ID=VALUE", "set a parameter: `plugin.param`, `material.NAME.key`, `light.NAME.key` "
     "(repeatable)", CALL(setting)},
    {"--env", NULL, "FILE", "an environment map (`.hdr`, `.exr`: lat-long) lighting the scene, in place of its own",
     TEXT(opt.env_map)},
    {"--ground", NULL, NULL, "a grey floor under the scene's bounds that receives its shadows", FLAG(opt.ground)},
    {"--shadows", NULL, NULL, "every light casts shadows, and a key light that casts them is added (off while a plugin "
                              "lights the scene with a shadow-casting sun of its own)", FLAG(opt.shadows)},
    {"--variant", NULL, "NAME", "the glTF `KHR_materials_variants` variant shown (name or index)", TEXT(opt.gltf_variant)},
    {"--animation", NULL, "N|NAME", "the glTF animation played (index or name; default the first)",
     TEXT(opt.gltf_animation)},
    {"--list-gltf-extensions", NULL, NULL, "glTF 2.0's features and the extensions shadelab knows: rendered, "
     "approximated or not, and how", CALL(list_gltf_extensions)},
    {"--camera", NULL, "NAME", "start from a scene camera (a model's first camera by default)", TEXT(opt.camera)},
    {"--list-cameras", NULL, NULL, "the scene's cameras with position and field of view", FLAG(list_cameras)},
    {"--debug-view", NULL, "NAME", "replace the output with a debug view (`--list-debug-views`)",
     TEXT(opt.debug_view)},
    {"--accumulate", NULL, "N", "average N frames per output (Monte Carlo references)",
     WHOLE(opt.accumulate, 1, 1000000)},
    {"--reference", NULL, "PLUGIN", "render the plugin's declared ground truth", TEXT(reference)},
    {"--auto-quality", NULL, "SPEC", "`[METRIC=]BUDGET[@FRONT.json,…]`: per plugin the cheapest benchmarked setting "
     "within the budget", TEXT(auto_quality)},
    {"--float", NULL, NULL, "RGBA32F colour target instead of RGBA16F", FLAG(opt.float32)},
    {"--data", NULL, "DIR", "data directory for assets (also `SHADELAB_DATA`)", TEXT(opt.data_dir)},
    {"--time", NULL, "T", "scene time in seconds of the first frame (default 0)", CALL(start_time)},
    {"--strict", NULL, NULL, "a plugin that fails to load is fatal", FLAG(opt.strict)},
    {"--list-plugins", NULL, NULL, "loaded plugins; disabled ones with their reasons", FLAG(list_plugins)},
    {"--list-debug-views", NULL, NULL, "the debug views of the loaded plugins", FLAG(list_views)},
    {"--dump-params", NULL, NULL, "the parameter schema and values as JSON", FLAG(dump_params)},
    {"--explain", NULL, NULL, "passes, programs and plugins the scene really runs, with their cost", FLAG(explain)},
    {"--help-keys", NULL, NULL, "key bindings of the viewer and the plugins", FLAG(help_keys)},
    {"--verbose", "-v", NULL, "debug messages too", CALL(verbose)},
    {"--quiet", "-q", NULL, "warnings and errors only", CALL(quiet)},
    {"--version", NULL, NULL, "the version and the plugin ABI it loads", CALL(print_version)},
    {"--help", "-h", NULL, "this list", CALL(print_help)},
    {"--help-markdown", NULL, NULL, "this list as the Markdown table in README.md "
     "(`tools/readme-options.sh` puts it there)", CALL(print_markdown)},
    {"--gltf-markdown", NULL, NULL, "`--list-gltf-extensions` as the Markdown table in README.md (the same tool "
     "puts it there)", CALL(gltf_markdown)},
};
#define OPTION_COUNT (sizeof options / sizeof *options)

static const option *find_option(const char *a) {
    for (size_t i = 0; i < OPTION_COUNT; i++)
        if (!strcmp(a, options[i].name) || (options[i].alias && options[i].alias[0] == '-' && !strcmp(a, options[i].alias)))
            return &options[i];
    return NULL;
}

static sl_cli_result apply(const option *o, sl_cli *c, const char *value, char *err, size_t n) {
    char *field = (char *)c + o->field;
    switch (o->kind) {
    case OPTION_FLAG: *(bool *)field = true; return SL_CLI_RUN;
    case OPTION_TEXT: *(const char **)field = value; return SL_CLI_RUN;
    case OPTION_WHOLE: {
        long v;
        if (!sl_parse_long(value, o->min, o->max, &v)) {
            snprintf(err, n, "%s %s: expected a whole number %ld..%ld", o->name, value, o->min, o->max);
            return SL_CLI_ERROR;
        }
        *(int *)field = (int)v;
        return SL_CLI_RUN;
    }
    case OPTION_CALL: return o->call(c, value, err, n);
    }
    return SL_CLI_ERROR;
}

/* What the options imply for each other, and the combinations refused. */
static sl_cli_result finish(sl_cli *c, char *err, size_t n) {
    if (c->headless && c->opt.backend == SL_BACKEND_AUTO) c->opt.backend = SL_BACKEND_HEADLESS;
    /* pass timings (glFinish on CPU rasterisers) only where they are printed */
    c->opt.timings = c->bench || c->stats || c->explain;
    /* an EXR is the final linear "color": no pass writes the display encoding on the fly */
    const char *ext = c->output ? strrchr(c->output, '.') : NULL;
    c->opt.keep_color = ext && (!strcasecmp(ext, ".exr") || !strcasecmp(ext, ".hdr"));
    if (c->turntable && c->frames > 0) {
        snprintf(err, n, "--turntable renders its own frames (each a still); leave out --frames");
        return SL_CLI_ERROR;
    }
    if (c->output && sl_cli_is_video(c->output) && !c->turntable) {
        snprintf(err, n, "--output %s: a video is written by --turntable N (a still is .png or .exr)", c->output);
        return SL_CLI_ERROR;
    }
    return SL_CLI_RUN;
}

sl_cli_result sl_cli_parse(int argc, char **argv, sl_cli *c, char *err, size_t n) {
    memset(c, 0, sizeof *c);
    c->frames = -1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const option *o = find_option(a);
        if (!o && a[0] != '-') { /* shadelab model.glb */
            if (c->opt.scene_path) {
                snprintf(err, n, "%s: only one scene or model file (already %s)", a, c->opt.scene_path);
                return SL_CLI_ERROR;
            }
            c->opt.scene_path = a;
            continue;
        }
        if (!o) { snprintf(err, n, "unknown option %s (see --help)", a); return SL_CLI_ERROR; }
        const char *value = NULL;
        if (o->arg) {
            if (i + 1 >= argc) { snprintf(err, n, "%s needs a value (%s)", a, o->arg); return SL_CLI_ERROR; }
            value = argv[++i];
        }
        sl_cli_result r = apply(o, c, value, err, n);
        if (r != SL_CLI_RUN) return r;
    }
    return finish(c, err, n);
}

bool sl_cli_is_video(const char *path) {
    const char *dot = strrchr(path, '.');
    return dot && (!strcasecmp(dot, ".mp4") || !strcasecmp(dot, ".mkv") || !strcasecmp(dot, ".webm") || !strcasecmp(dot, ".mov"));
}

/* ---- the table printed ------------------------------------------------------------------ */

/* "FILE, --scene FILE", "-v, --verbose", "--size WxH" */
static void option_names(const option *o, char *buf, size_t n) {
    snprintf(buf, n, "%s%s%s%s%s", o->alias ? o->alias : "", o->alias ? ", " : "", o->name, o->arg ? " " : "",
             o->arg ? o->arg : "");
}

enum { HELP_COLUMN = 25, HELP_WIDTH = 110 };

void sl_cli_print_help(FILE *f) {
    fprintf(f, "usage: shadelab [options] [FILE]\n");
    for (size_t i = 0; i < OPTION_COUNT; i++) {
        char names[128], text[1024];
        option_names(&options[i], names, sizeof names);
        size_t t = 0; /* the description without its Markdown code marks */
        for (const char *p = options[i].help; *p && t + 1 < sizeof text; p++)
            if (*p != '`') text[t++] = *p;
        text[t] = 0;
        int col = fprintf(f, "  %s", names);
        /* its words, wrapped at HELP_WIDTH into the column */
        bool first = true;
        for (const char *s = text; *s;) {
            int len = (int)strcspn(s, " ");
            if (first || col + 1 + len > HELP_WIDTH) {
                if (!first || col >= HELP_COLUMN - 1) { fputc('\n', f); col = 0; }
                col += fprintf(f, "%*s", HELP_COLUMN - col, "");
            } else {
                col += fprintf(f, " ");
            }
            col += fprintf(f, "%.*s", len, s);
            first = false;
            s += len;
            while (*s == ' ') s++;
        }
        fputc('\n', f);
    }
    fprintf(f, "exit status: 0 done; 1 failed, nothing written; 2 the output was written but an error was printed\n"
               "(a missing texture's magenta stand-in, a plugin switched off because its GLSL does not compile, ...)\n");
}

/* Text for a Markdown table cell: | escaped (also inside `code`, as GitHub's tables need), < and
 * > outside code as entities. */
static void markdown_text(FILE *f, const char *s) {
    bool in_code = false;
    for (const char *p = s; *p; p++) {
        if (*p == '`') in_code = !in_code;
        if (*p == '|') fputs("\\|", f);
        else if (!in_code && *p == '<') fputs("&lt;", f);
        else if (!in_code && *p == '>') fputs("&gt;", f);
        else fputc(*p, f);
    }
}

void sl_cli_print_markdown(FILE *f) {
    fprintf(f, "| option | meaning |\n|---|---|\n");
    for (size_t i = 0; i < OPTION_COUNT; i++) {
        const option *o = &options[i];
        fprintf(f, "| ");
        if (o->alias) fprintf(f, "`%s`, ", o->alias);
        fputc('`', f);
        markdown_text(f, o->name);
        if (o->arg) fputc(' ', f), markdown_text(f, o->arg);
        fprintf(f, "` | ");
        markdown_text(f, o->help);
        fprintf(f, " |\n");
    }
}
