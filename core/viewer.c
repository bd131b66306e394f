/* The interactive window viewer: camera controls, keys (with conflict resolution), the GUI
 * panel, hot reload with on-screen errors, screenshots, and a script hook for tests. */
#include "viewer.h"
#include "budget/budget.h"
#include "gui/gui.h"
#include "gui/panel.h"
#include "image/image.h"
#include "log.h"
#include "render/renderer.h"
#include <shadelab/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* The window's frame-time budget when none is given (core.budget, --budget): 15 frames a second. */
#define SL_VIEWER_BUDGET_MS 66

/* render/renderer.c: re-reads shader files whose modification time changed (not in its header) */
bool sl_renderer_poll_reload(sl_app *app);

/* ------------------------------------------------------------------ key bindings -------- */

/* Keys the viewer itself uses; Shift+fly keys are taken too (Shift = fly faster). */
static const struct { const char *key; bool shift; const char *what; } viewer_keys[] = {
    {"W", false, "fly"}, {"A", false, "fly"}, {"S", false, "fly"}, {"D", false, "fly"}, {"Q", false, "fly"},
    {"E", false, "fly"}, {"W", true, "fast fly"}, {"A", true, "fast fly"}, {"S", true, "fast fly"},
    {"D", true, "fast fly"}, {"Q", true, "fast fly"}, {"E", true, "fast fly"}, {"C", false, "print camera"},
    {"P", false, "screenshot"}, {"F1", false, "toggle panel"}, {"F5", false, "reload shaders"},
};

/* "a" → "A", "f3" → "F3"; GLFW code or -1. */
static int parse_key(const char *name, char *norm, size_t n) {
    norm[0] = 0;
    if (!name) return -1;
    size_t l = strlen(name);
    if (l == 1 && isalnum((unsigned char)name[0])) {
        char c = (char)toupper((unsigned char)name[0]);
        snprintf(norm, n, "%c", c);
        return isdigit((unsigned char)c) ? GLFW_KEY_0 + (c - '0') : GLFW_KEY_A + (c - 'A');
    }
    if ((name[0] == 'F' || name[0] == 'f') && l <= 3) {
        char *end;
        long f = strtol(name + 1, &end, 10);
        if (*end == 0 && f >= 1 && f <= 12) {
            snprintf(norm, n, "F%ld", f);
            return GLFW_KEY_F1 + (int)f - 1;
        }
    }
    return -1;
}

int sl_viewer_resolve_keys(sl_app *app, sl_key_binding *out, int max, FILE *warn) {
    int count = 0;
    for (int i = 0; i < app->plugins.key_count && count < max; i++) {
        const sl_key_reg *k = &app->plugins.keys[i];
        sl_key_binding *b = &out[count++];
        memset(b, 0, sizeof *b);
        b->reg = i;
        b->code = parse_key(k->d.key, b->key, sizeof b->key);
        const char *owner = app->plugins.items[k->owner]->id;
        if (b->code < 0) {
            b->unbound = true;
            if (warn)
                fprintf(warn, "warning: plugin %s: key \"%s\" (%s) is not a valid key (0-9, A-Z, F1-F12); it can "
                              "only be triggered from the panel\n", owner, k->d.key ? k->d.key : "",
                        k->d.description ? k->d.description : "");
            continue;
        }
        /* who holds key+shift already? */
        for (int pass = 0; pass < 2; pass++) {
            bool shift = pass == 1;
            char holder[200] = "";
            for (size_t v = 0; v < sizeof viewer_keys / sizeof *viewer_keys && !holder[0]; v++)
                if (viewer_keys[v].shift == shift && !strcmp(viewer_keys[v].key, b->key))
                    snprintf(holder, sizeof holder, "the viewer (%s)", viewer_keys[v].what);
            for (int j = 0; j < count - 1 && !holder[0]; j++) {
                const sl_key_binding *o = &out[j];
                if (!o->unbound && o->shift == shift && !strcmp(o->key, b->key))
                    snprintf(holder, sizeof holder, "plugin %s (\"%s\")",
                             app->plugins.items[app->plugins.keys[o->reg].owner]->id,
                             app->plugins.keys[o->reg].d.description ? app->plugins.keys[o->reg].d.description : "");
            }
            if (!holder[0]) {
                b->shift = shift;
                break;
            }
            if (!shift) snprintf(b->clash, sizeof b->clash, "%s", holder);
            else b->unbound = true;
        }
        if (b->clash[0] && warn) {
            if (b->unbound)
                fprintf(warn, "warning: key %s: plugin %s (\"%s\") and %s both want it, and Shift+%s is taken too; "
                              "%s's binding is left unbound (trigger it from the panel's Keys section)\n",
                        b->key, owner, k->d.description ? k->d.description : "", b->clash, b->key, owner);
            else
                fprintf(warn, "warning: key %s: plugin %s (\"%s\") and %s both want it; %s keeps %s (first come), "
                              "plugin %s gets Shift+%s\n",
                        b->key, owner, k->d.description ? k->d.description : "", b->clash, b->clash, b->key, owner,
                        b->key);
        }
    }
    return count;
}

void sl_viewer_print_keys(sl_app *app, FILE *f) {
    fprintf(f, "viewer keys:\n"
               "  left drag     orbit            right/middle drag  pan\n"
               "  wheel         zoom             W A S D Q E        fly (Shift: faster)\n"
               "  C             print camera     F5                 reload shaders\n"
               "  P             screenshot       F1                 show/hide the panel\n"
               "  Esc           quit\n");
    int n = app->plugins.key_count;
    if (!n) return;
    sl_key_binding *b = calloc(n, sizeof *b);
    n = sl_viewer_resolve_keys(app, b, n, stderr);
    fprintf(f, "plugin keys (clashes: first loaded keeps the key, the next gets Shift+key):\n");
    for (int i = 0; i < n; i++) {
        const sl_key_reg *k = &app->plugins.keys[b[i].reg];
        char key[32];
        if (b[i].unbound) snprintf(key, sizeof key, "(panel only)");
        else snprintf(key, sizeof key, "%s%s", b[i].shift ? "Shift+" : "", b[i].key);
        fprintf(f, "  %-13s %s [%s]", key, k->d.description ? k->d.description : "", app->plugins.items[k->owner]->id);
        if (b[i].clash[0]) fprintf(f, "  (%s was taken by %s)", b[i].key, b[i].clash);
        fprintf(f, "\n");
    }
    free(b);
}

void sl_viewer_trigger_binding(sl_app *app, const sl_key_binding *b) {
    const sl_key_reg *k = &app->plugins.keys[b->reg];
    /* a disabled plugin's keys do nothing, except one bound to its own "enabled" (turn it back on) */
    if (!sl_plugin_enabled(&app->plugins, k->owner) && !(k->d.param && !strcmp(k->d.param, "enabled"))) return;
    if (k->d.on_press) { k->d.on_press(k->d.user); return; }
    if (!k->d.param) return;
    char id[300], err[1024];
    snprintf(id, sizeof id, "%s.%s", app->plugins.items[k->owner]->id, k->d.param);
    sl_param *q = sl_params_find(&app->params, id);
    if (!q) { SL_WARN("key %s: plugin parameter %s does not exist", b->key, id); return; }
    char assignment[600];
    if (q->desc.type == SL_PARAM_BOOL) snprintf(assignment, sizeof assignment, "%s=%s", id, q->value.b ? "false" : "true");
    else if (q->desc.type == SL_PARAM_ENUM) {
        int nv = 0;
        while (q->desc.enum_values && q->desc.enum_values[nv]) nv++;
        if (!nv) return;
        snprintf(assignment, sizeof assignment, "%s=%s", id, q->desc.enum_values[(q->value.i + 1) % nv]);
    } else {
        SL_WARN("key %s: %s is neither bool nor enum; nothing to toggle", b->key, id);
        return;
    }
    if (sl_panel_apply(app, assignment, err, sizeof err)) fprintf(stderr, "%s\n", assignment);
}

/* ------------------------------------------------------------------ viewer state -------- */

typedef struct viewer {
    sl_app *app;
    double last_x, last_y;
    bool dragging[3];
    bool screenshot, reload, quit, gui;
    sl_panel *panel;
    sl_key_binding *bindings;
    int binding_count;
    int next_shot;
    char capture[65536];     /* log text of the last compile attempt */
    char errors[8192];       /* condensed for the screen */
    int frames_rendered;     /* frames rendered so far (a status line needs a previous image) */
    int status_frames;       /* frames shown with the "compiling" status before recompiling */
    int events;              /* input events since the loop last looked (the callbacks count them) */
    bool resting;            /* at rest: waiting for events instead of drawing (main loop) */
} viewer;

/* The errors in the captured log, condensed for the screen: a failing chunk breaks every
 * material's program with the same message, so identical messages are shown once, followed by
 * the programs they broke. Returns v->errors ("" when none). */
static const char *errors_from_capture(viewer *v) {
    typedef struct { const char *body; size_t len; char who[600]; } group;
    group g[16];
    int ng = 0;
    size_t used = 0;
    v->errors[0] = 0;
    const char *p = v->capture;
    while ((p = strstr(p, "error: "))) {
        if (p != v->capture && p[-1] != '\n') { p++; continue; }
        const char *head = p + 7, *nl = strchr(head, '\n');
        const char *next = nl ? nl : head + strlen(head);
        while ((next = strstr(next, "\n")) && strncmp(next + 1, "error: ", 7) && strncmp(next + 1, "warning: ", 9) && next[1])
            next++;
        const char *end = next ? next : head + strlen(head);
        /* "LABEL: shader compile failed:\nBODY" or a one-line message */
        const char *colon = nl && nl < end ? strstr(head, ": shader compile failed") : NULL;
        const char *body = colon && colon < nl ? nl + 1 : head;
        size_t blen = (size_t)(end - body);
        while (blen && (body[blen - 1] == '\n' || body[blen - 1] == ' ')) blen--;
        int k = 0;
        while (k < ng && !(g[k].len == blen && !strncmp(g[k].body, body, blen))) k++;
        if (k == ng && ng < 16) { g[ng] = (group){.body = body, .len = blen}; ng++; }
        if (k < ng && body != head) {
            size_t l = strlen(g[k].who);
            snprintf(g[k].who + l, sizeof g[k].who - l, "%s%.*s", l ? ", " : "", (int)(colon - head), head);
        }
        p = end;
    }
    for (int k = 0; k < ng && used + 1 < sizeof v->errors; k++)
        used += snprintf(v->errors + used, sizeof v->errors - used, "%s%.*s%s%s%s", k ? "\n" : "", (int)g[k].len, g[k].body,
                         g[k].who[0] ? "\n  (breaks " : "", g[k].who, g[k].who[0] ? "; they keep their last good program)" : "");
    return v->errors;
}

static void do_reload(viewer *v, bool from_key) {
    sl_app *app = v->app;
    int before = sl_log_count(SL_LOG_ERROR);
    sl_log_capture(v->capture, sizeof v->capture);
    int failed = from_key ? sl_renderer_reload_shaders(app) : (sl_renderer_poll_reload(app) ? -1 : -2);
    sl_log_capture(NULL, 0);
    if (failed == -2) return; /* nothing changed on disk */
    bool errors = sl_log_count(SL_LOG_ERROR) > before;
    if (from_key) fprintf(stderr, "shaders reloaded%s\n", errors ? " with errors (last good programs kept)" : "");
    if (v->panel) sl_panel_set_shader_error(v->panel, errors ? errors_from_capture(v) : NULL);
}

static void handle_key(viewer *v, int key, int mods) {
    sl_app *app = v->app;
    bool shift = mods & GLFW_MOD_SHIFT;
    if (key == GLFW_KEY_ESCAPE) { v->quit = true; return; }
    if (!shift) {
        if (key == GLFW_KEY_C) { sl_camera_print(&app->camera, stdout); fflush(stdout); return; }
        if (key == GLFW_KEY_F5) { v->reload = true; return; }
        if (key == GLFW_KEY_P) { v->screenshot = true; return; }
        if (key == GLFW_KEY_F1) { if (v->panel) sl_panel_toggle(v->panel); return; }
    }
    int code = key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9 ? GLFW_KEY_0 + (key - GLFW_KEY_KP_0) : key;
    for (int i = 0; i < v->binding_count; i++) {
        const sl_key_binding *b = &v->bindings[i];
        if (!b->unbound && b->code == code && b->shift == shift) sl_viewer_trigger_binding(app, b);
    }
}

static void on_key(GLFWwindow *w, int key, int sc, int action, int mods) {
    viewer *v = glfwGetWindowUserPointer(w);
    v->events++;
    if (action != GLFW_PRESS || (v->gui && sl_gui_wants_keyboard())) return;
    handle_key(v, key, mods);
}

static void on_cursor(GLFWwindow *w, double x, double y) {
    viewer *v = glfwGetWindowUserPointer(w);
    v->events++;
    double dx = x - v->last_x, dy = y - v->last_y;
    v->last_x = x;
    v->last_y = y;
    if (v->dragging[0]) sl_camera_orbit(&v->app->camera, (float)-dx * 0.005f, (float)dy * 0.005f);
    if (v->dragging[1] || v->dragging[2]) sl_camera_pan(&v->app->camera, (float)-dx * 0.0015f, (float)dy * 0.0015f);
}

static void on_button(GLFWwindow *w, int button, int action, int mods) {
    viewer *v = glfwGetWindowUserPointer(w);
    v->events++;
    if (button >= 3) return;
    if (action == GLFW_PRESS && v->gui && sl_gui_wants_mouse()) return; /* a click on the panel */
    v->dragging[button] = action == GLFW_PRESS;
}

static void on_scroll(GLFWwindow *w, double dx, double dy) {
    viewer *v = glfwGetWindowUserPointer(w);
    v->events++;
    if (v->gui && sl_gui_wants_mouse()) return;
    sl_camera_zoom(&v->app->camera, powf(0.9f, (float)dy));
}

/* The window needs drawing again: uncovered, resized or refocused (a waiting loop wakes). */
static void on_refresh(GLFWwindow *w) { ((viewer *)glfwGetWindowUserPointer(w))->events++; }
static void on_size(GLFWwindow *w, int width, int height) { on_refresh(w); }
static void on_focus(GLFWwindow *w, int focused) { on_refresh(w); }

static bool file_exists(const char *p) {
    struct stat st;
    return stat(p, &st) == 0;
}

/* P: the rendered image (panel not included) as PNG (display-encoded) and EXR (linear HDR). */
static void save_screenshot(viewer *v) {
    char png[64], exr[64], err[1024];
    for (;; v->next_shot++) {
        snprintf(png, sizeof png, "shadelab-%03d.png", v->next_shot);
        snprintf(exr, sizeof exr, "shadelab-%03d.exr", v->next_shot);
        if (!file_exists(png) && !file_exists(exr)) break;
    }
    v->next_shot++;
    /* A screenshot is a still, as a headless render without --frames is: the frames a plugin's
     * still needs (TAA's history, plugins/aa) rendered at this time, so P gives the image the
     * window settles on, even right after a change. */
    /* The window's frames may write the display encoding on the fly and keep no final linear
     * "color" (graph_plan.c): the screenshot's frames keep it for the EXR. */
    bool keep = v->app->opt.keep_color;
    v->app->opt.keep_color = true;
    sl_budget_settle(v->app); /* the best settings, as the window settles on when still */
    int still = sl_renderer_still_frames(v->app);
    for (int k = 0; k < (still > 1 ? still : 1); k++) sl_app_render_frame(v->app);
    v->app->opt.keep_color = keep;
    if (sl_app_save(v->app, png, err, sizeof err)) fprintf(stderr, "saved %s (display-encoded)\n", png);
    else fprintf(stderr, "screenshot: %s\n", err);
    if (sl_app_save(v->app, exr, err, sizeof err)) fprintf(stderr, "saved %s (linear HDR)\n", exr);
    else fprintf(stderr, "screenshot: %s\n", err);
}

/* The window's back buffer, panel included (script "grab"). */
static void grab_window(viewer *v, const char *path) {
    int w = v->app->backend.width, h = v->app->backend.height;
    float *px = malloc((size_t)w * h * 4 * sizeof(float)), *flipped = malloc((size_t)w * h * 4 * sizeof(float));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px);
    for (int y = 0; y < h; y++) memcpy(flipped + (size_t)y * w * 4, px + (size_t)(h - 1 - y) * w * 4, (size_t)w * 4 * sizeof(float));
    for (size_t i = 0; i < (size_t)w * h; i++) flipped[i * 4 + 3] = 1;
    char err[1024];
    if (sl_image_write(path, flipped, w, h, true, err, sizeof err)) fprintf(stderr, "grabbed the window into %s (scene time %.17g s)\n", path, v->app->time);
    else fprintf(stderr, "grab: %s\n", err);
    free(px);
    free(flipped);
}

/* ------------------------------------------------------------------ script hook --------- */

typedef struct script { char *text; char *cursor; int wait; char grab[1024]; double waiting_since; } script;

/* The script has nothing to do this iteration but wait (or there is none, or it has ended). */
static bool script_idle(const script *s) { return !s->text || s->wait > 0 || !s->cursor || !*s->cursor; }

/* Runs the script's next command (one per frame, before the frame is rendered). */
static void script_step(viewer *v, script *s) {
    if (!s->text) return;
    if (s->wait > 0) { s->wait--; return; }
    while (s->cursor && *s->cursor) {
        char *end = strchr(s->cursor, ';');
        if (end) *end = 0;
        char *cmd = s->cursor;
        s->cursor = end ? end + 1 : NULL;
        while (isspace((unsigned char)*cmd)) cmd++;
        for (char *e = cmd + strlen(cmd); e > cmd && isspace((unsigned char)e[-1]);) *--e = 0;
        if (!*cmd) continue;
        char err[2048];
        if (strncmp(cmd, "waitfile ", 9) || !s->waiting_since) fprintf(stderr, "script: %s\n", cmd);
        if (!strncmp(cmd, "set ", 4)) {
            sl_panel_apply(v->app, cmd + 4, err, sizeof err);
        } else if (!strncmp(cmd, "view ", 5)) {
            sl_panel_set_debug_view(v->app, cmd + 5, err, sizeof err);
        } else if (!strncmp(cmd, "key ", 4)) {
            const char *k = cmd + 4;
            int mods = 0;
            if (!strncasecmp(k, "shift+", 6)) { mods = GLFW_MOD_SHIFT; k += 6; }
            char norm[16];
            int code = !strcasecmp(k, "esc") ? GLFW_KEY_ESCAPE : parse_key(k, norm, sizeof norm);
            if (code < 0) fprintf(stderr, "script: unknown key %s\n", k);
            else handle_key(v, code, mods);
        } else if (!strncmp(cmd, "orbit ", 6)) {
            float yaw = 0, pitch = 0;
            if (sscanf(cmd + 6, "%f %f", &yaw, &pitch) >= 1) sl_camera_orbit(&v->app->camera, yaw, pitch);
            else fprintf(stderr, "script: orbit expects YAW [PITCH] in radians\n");
        } else if (!strncmp(cmd, "wait ", 5)) {
            s->wait = atoi(cmd + 5) - 1;
            return;
        } else if (!strncmp(cmd, "waitfile ", 9)) {
            /* render frames until the file exists (a test edits shaders meanwhile) */
            struct stat st;
            if (stat(cmd + 9, &st) != 0) {
                if (end) *end = ';';
                s->cursor = cmd;
                if (!s->waiting_since) s->waiting_since = glfwGetTime();
                if (glfwGetTime() - s->waiting_since > 120) {
                    fprintf(stderr, "script: gave up waiting for %s\n", cmd + 9);
                    v->quit = true;
                }
                return;
            }
            s->waiting_since = 0;
        } else if (!strncmp(cmd, "grab ", 5)) {
            snprintf(s->grab, sizeof s->grab, "%s", cmd + 5);
            return; /* grabbed after this frame is drawn */
        } else if (!strcmp(cmd, "quit")) {
            v->quit = true;
            return;
        } else {
            fprintf(stderr, "script: unknown command \"%s\" (set, view, key, orbit, wait, waitfile, grab, quit)\n", cmd);
        }
        return; /* one command per frame */
    }
}

/* ------------------------------------------------------------------ main loop ----------- */

int sl_viewer_run(sl_app *app, double start_time) {
    GLFWwindow *w = (GLFWwindow *)app->backend.window;
    viewer *v = calloc(1, sizeof *v);
    v->app = app;
    glfwSetWindowUserPointer(w, v);
    glfwSetKeyCallback(w, on_key);
    glfwSetCursorPosCallback(w, on_cursor);
    glfwSetMouseButtonCallback(w, on_button);
    glfwSetScrollCallback(w, on_scroll);
    glfwSetWindowRefreshCallback(w, on_refresh);
    glfwSetFramebufferSizeCallback(w, on_size);
    glfwSetWindowFocusCallback(w, on_focus);

    int nk = app->plugins.key_count;
    v->bindings = calloc(nk + 1, sizeof *v->bindings);
    v->binding_count = sl_viewer_resolve_keys(app, v->bindings, nk, stderr);

    const char *no_gui = getenv("SHADELAB_NO_GUI");
    if (!(no_gui && *no_gui && strcmp(no_gui, "0"))) {
        char err[512];
        /* ImGui chains to the callbacks installed above */
        if (sl_gui_init(w, err, sizeof err)) {
            v->gui = true;
            v->panel = sl_panel_create(app, v->bindings, v->binding_count);
        } else {
            SL_WARN("no GUI panel: %s", err);
        }
    }
    /* what loading left (a missing texture, an unknown key, a plugin that did not load) stays on
     * screen until dismissed, like a shader error: a window user may never see stderr */
    const char *load_problems = sl_log_problems();
    if (v->panel && *load_problems) {
        size_t n = strlen(load_problems) + 64;
        char *text = malloc(n);
        if (text) {
            snprintf(text, n, "Loading reported:\n%s", load_problems);
            sl_panel_set_shader_error(v->panel, text);
            free(text);
        }
    }
    /* the window keeps a frame-time budget unless the scene or the command line chose one
     * (--budget): 66 ms, 15 frames a second */
    sl_param *budget = sl_params_find(&app->params, "core.budget");
    if (budget && budget->source == SL_SRC_DEFAULT) {
        sl_value v = budget->value;
        v.f[0] = SL_VIEWER_BUDGET_MS;
        sl_params_set_value(&app->params, budget, v, SL_SRC_DEFAULT);
    }
    script sc = {0};
    const char *st = getenv("SHADELAB_VIEWER_SCRIPT");
    if (st && *st) sc.cursor = sc.text = strdup(st);

    double t0 = glfwGetTime(), last_poll = t0, last = t0;
    int turns = 0;
    while (!glfwWindowShouldClose(w) && !v->quit) {
        turns++;
        /* At rest (the still complete, nothing playing, the budget settled, the script only
         * waiting, the panel not in use: its hover, tooltips and text cursor want frames) the same
         * image would be drawn again: wait for an event, or for the half-second poll of the
         * files, instead of keeping both cores busy. */
        bool rest = v->frames_rendered && script_idle(&sc) && sl_budget_settled(app) && sl_renderer_at_rest(app) &&
                    !(v->gui && (sl_gui_wants_mouse() || sl_gui_wants_keyboard()));
        bool entering = rest && !v->resting; /* one more frame, its panel saying so */
        bool idle_before = v->resting;       /* the time since the last turn was waiting, not drawing */
        if (entering) SL_DEBUG("viewer: at rest after %d frames: waiting for events", v->frames_rendered);
        v->resting = rest;
        v->events = 0;
        if (rest && !entering) glfwWaitEventsTimeout(0.5);
        else glfwPollEvents();
        script_step(v, &sc);
        if (v->quit) break;
        double t = glfwGetTime(), dt = t - last;
        last = t;
        if (!(v->gui && sl_gui_wants_keyboard())) {
            float speed = 2.0f * (float)dt * (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) ? 4.f : 1.f);
            float fwd = (glfwGetKey(w, GLFW_KEY_W) - glfwGetKey(w, GLFW_KEY_S)) * speed;
            float right = (glfwGetKey(w, GLFW_KEY_D) - glfwGetKey(w, GLFW_KEY_A)) * speed;
            float up = (glfwGetKey(w, GLFW_KEY_E) - glfwGetKey(w, GLFW_KEY_Q)) * speed;
            if (fwd || right || up) sl_camera_fly(&app->camera, fwd, right, up);
        }
        int fw, fh;
        glfwGetFramebufferSize(w, &fw, &fh);
        if (fw > 0 && fh > 0) sl_app_resize(app, fw, fh);
        if (v->reload) { do_reload(v, true); v->reload = false; }
        if (t - last_poll > 0.5) { do_reload(v, false); last_poll = t; }
        if (rest && !entering && !v->events && !v->reload && !v->screenshot && !sl_renderer_compose_pending(app)) continue;
        if (rest && v->panel) sl_panel_set_status(v->panel, "at rest: the still is complete; drawn again on input");

        /* widgets first: their changes apply to this frame (a frame boundary) */
        sl_panel_actions act = {.trigger_binding = -1};
        if (v->gui) {
            sl_gui_new_frame();
            sl_panel_draw(v->panel, rest || idle_before ? 0.0 : dt, &act); /* 0: no frame rate from a wait */
        }
        if (act.trigger_binding >= 0) sl_viewer_trigger_binding(app, &v->bindings[act.trigger_binding]);
        if (act.reload_shaders) do_reload(v, true);
        if (act.screenshot) v->screenshot = true;

        /* A change that recompiles takes a moment on a CPU rasteriser: first show the previous
         * image with a status line for three frames (ImGui sizes a new overlay in its first frame and
         * shows it in the next),
         * then compile and render. */
        bool hold = v->panel && v->frames_rendered && sl_renderer_compose_pending(app) && v->status_frames < 3;
        if (hold) {
            sl_panel_set_status(v->panel, "compiling shaders ...");
            v->status_frames++;
            sl_renderer_present(app); /* the previous image stays */
        } else {
            v->status_frames = 0;
            app->time = start_time + (t - t0);
            int before = sl_log_count(SL_LOG_ERROR);
            sl_log_capture(v->capture, sizeof v->capture);
            sl_app_render_frame(app);
            v->frames_rendered++;
            if (v->panel) sl_panel_set_status(v->panel, NULL);
            sl_log_capture(NULL, 0);
            /* a parameter that recompiles (or a reload) can fail here too: keep it on screen */
            if (v->panel && sl_log_count(SL_LOG_ERROR) > before) sl_panel_set_shader_error(v->panel, errors_from_capture(v));
            if (v->screenshot) {
                save_screenshot(v);
                v->screenshot = false;
            }
        }
        if (v->gui) sl_gui_render();
        if (sc.grab[0]) {
            grab_window(v, sc.grab);
            sc.grab[0] = 0;
        }
        sl_backend_swap(&app->backend);
    }
    SL_DEBUG("viewer: drew %d frames in %d turns of the loop", v->frames_rendered, turns);
    if (v->gui) sl_gui_shutdown();
    sl_panel_destroy(v->panel);
    free(v->bindings);
    free(sc.text);
    free(v);
    return 0;
}
