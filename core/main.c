/* shadelab command line: headless renders, the window viewer, plugin/parameter listings. */
#include "app.h"
#include "cli.h"
#include "quality/autoquality.h" /* --auto-quality (shadelab_quality) */
#include "log.h"
#include "render/renderer.h"
#include "startup.h"
#include "still.h"
#include "turntable.h"
#include "viewer.h"
#include <cjson/cJSON.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <dirent.h>
#include <unistd.h>
#include <time.h>

static int die(const char *msg) {
    fprintf(stderr, "shadelab: %s\n", msg);
    return 1;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static double median(double *v, int n) {
    if (n <= 0) return 0;
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Per-pass time series over the frames of a run. */
typedef struct series { const char *name, *owner; double *ms; int n; } series;
typedef struct recorder { series s[65]; int count; double *frame; int frames; } recorder;

static void record(recorder *rec, const sl_frame_stats *st) {
    rec->frame = realloc(rec->frame, (rec->frames + 1) * sizeof *rec->frame);
    rec->frame[rec->frames++] = st->frame_ms;
    for (int i = 0; i < st->pass_count; i++) {
        if (!st->passes[i].ran) continue;
        series *s = NULL;
        for (int k = 0; k < rec->count; k++)
            if (!strcmp(rec->s[k].name, st->passes[i].name)) s = &rec->s[k];
        if (!s && rec->count < 65) { s = &rec->s[rec->count++]; s->name = st->passes[i].name; s->owner = st->passes[i].owner; }
        if (!s) continue;
        s->ms = realloc(s->ms, (s->n + 1) * sizeof *s->ms);
        s->ms[s->n++] = st->passes[i].ms;
    }
}

static void summarise(const double *v, int n, double *med, double *mean, double *mn) {
    double *copy = malloc((n ? n : 1) * sizeof *copy);
    memcpy(copy, v, n * sizeof *copy);
    *med = median(copy, n);
    double sum = 0;
    *mn = n ? v[0] : 0;
    for (int i = 0; i < n; i++) { sum += v[i]; if (v[i] < *mn) *mn = v[i]; }
    *mean = n ? sum / n : 0;
    free(copy);
}

/* The process's peak resident memory (getrusage: llvmpipe's textures and buffers count here too). */
static double peak_rss_mib(void) {
    struct rusage ru;
    return getrusage(RUSAGE_SELF, &ru) == 0 ? ru.ru_maxrss / 1024.0 : 0;
}

/* The start-up profile (startup.h): phases to the end of the second frame, and the GLSL front
 * end's total (glCompileShader + glLinkProgram; llvmpipe's code generation is not in it, it runs
 * at a program's first draw, inside the first frame's passes). */
static void add_startup(cJSON *root) {
    const sl_startup_phase *ph;
    int n = sl_startup_phases(&ph);
    cJSON *a = cJSON_AddArrayToObject(root, "startup_phases");
    for (int i = 0; i < n; i++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "phase", ph[i].name);
        cJSON_AddNumberToObject(p, "wall_ms", ph[i].wall_ms);
        cJSON_AddNumberToObject(p, "cpu_ms", ph[i].cpu_ms);
        cJSON_AddNumberToObject(p, "main_thread_cpu_ms", ph[i].main_cpu_ms);
        cJSON_AddItemToArray(a, p);
    }
    double cpu, wall;
    int progs;
    sl_startup_glsl_total(&cpu, &wall, &progs);
    cJSON *g = cJSON_AddObjectToObject(root, "glsl_front_end");
    cJSON_AddNumberToObject(g, "programs_built", progs);
    cJSON_AddNumberToObject(g, "main_thread_cpu_ms", cpu);
    cJSON_AddNumberToObject(g, "wall_ms", wall);
    cJSON_AddStringToObject(g, "mesa_shader_cache_dir", getenv("MESA_SHADER_CACHE_DIR") ? getenv("MESA_SHADER_CACHE_DIR") : "");
}

static void log_startup(void) {
    const sl_startup_phase *ph;
    int n = sl_startup_phases(&ph);
    double w = 0, c = 0, m = 0;
    SL_DEBUG("start-up profile (wall, CPU of all threads, CPU of this thread = GL front end and shader compiles):");
    for (int i = 0; i < n; i++) {
        w += ph[i].wall_ms, c += ph[i].cpu_ms, m += ph[i].main_cpu_ms;
        SL_DEBUG("  %-52s %8.1f ms %8.1f ms %8.1f ms", ph[i].name, ph[i].wall_ms, ph[i].cpu_ms, ph[i].main_cpu_ms);
    }
    SL_DEBUG("  %-52s %8.1f ms %8.1f ms %8.1f ms", "total", w, c, m);
}

static bool write_stats(const char *path, sl_app *app, recorder *rec, double first_frame_ms, int warmup) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "backend", app->backend.name);
    cJSON_AddBoolToObject(root, "gpu", app->backend.is_gpu);
    cJSON_AddStringToObject(root, "timing", sl_renderer_stats(app)->timing_mode);
    cJSON_AddStringToObject(root, "scene", app->scene.path);
    cJSON_AddNumberToObject(root, "width", app->backend.width);
    cJSON_AddNumberToObject(root, "height", app->backend.height);
    cJSON_AddNumberToObject(root, "frames", rec->frames);
    cJSON_AddNumberToObject(root, "warmup_frames_excluded", warmup);
    cJSON_AddNumberToObject(root, "startup_to_first_frame_ms", first_frame_ms);
    cJSON_AddNumberToObject(root, "peak_rss_mib", peak_rss_mib());
    add_startup(root);
    double med, mean, mn;
    int skip = rec->frames > warmup ? warmup : 0;
    summarise(rec->frame + skip, rec->frames - skip, &med, &mean, &mn);
    cJSON *fr = cJSON_AddObjectToObject(root, "frame_ms");
    cJSON_AddNumberToObject(fr, "median", med);
    cJSON_AddNumberToObject(fr, "mean", mean);
    cJSON_AddNumberToObject(fr, "min", mn);
    cJSON *passes = cJSON_AddArrayToObject(root, "passes");
    for (int i = 0; i < rec->count; i++) {
        series *s = &rec->s[i];
        int sk = s->n > warmup ? warmup : 0;
        summarise(s->ms + sk, s->n - sk, &med, &mean, &mn);
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "name", s->name);
        cJSON_AddStringToObject(p, "plugin", s->owner);
        cJSON_AddNumberToObject(p, "runs", s->n - sk);
        cJSON_AddNumberToObject(p, "median_ms", med);
        cJSON_AddNumberToObject(p, "mean_ms", mean);
        cJSON_AddNumberToObject(p, "min_ms", mn);
        cJSON_AddItemToArray(passes, p);
    }
    const sl_frame_stats *st = sl_renderer_stats(app);
    cJSON_AddNumberToObject(root, "draw_calls", st->draw_calls);
    cJSON_AddNumberToObject(root, "programs", st->program_count);
    char *text = cJSON_Print(root);
    FILE *f = fopen(path, "w");
    bool ok = f != NULL;
    if (f) { fprintf(f, "%s\n", text); fclose(f); }
    else fprintf(stderr, "shadelab: cannot write %s: %s\n", path, strerror(errno));
    free(text);
    cJSON_Delete(root);
    return ok;
}

/* Triangles of every node's meshes (a mesh two nodes draw counts twice). */
static long scene_triangles(const sl_scene *s) {
    long n = 0;
    for (int i = 0; i < s->node_count; i++)
        for (int k = 0; k < s->nodes[i].mesh_count; k++) n += s->meshes[s->nodes[i].meshes[k]].data.index_count / 3;
    return n;
}

static void print_bench(sl_app *app, recorder *rec, int warmup) {
    double med, mean, mn;
    int skip = rec->frames > warmup ? warmup : 0;
    summarise(rec->frame + skip, rec->frames - skip, &med, &mean, &mn);
    printf("%s, %dx%d, %s timing, %d frames after %d warm-up\n", app->backend.name, app->backend.width, app->backend.height,
           sl_renderer_stats(app)->timing_mode, rec->frames - skip, skip);
    printf("  %-24s %10s %10s %10s\n", "pass", "median ms", "mean ms", "min ms");
    for (int i = 0; i < rec->count; i++) {
        series *s = &rec->s[i];
        int sk = s->n > warmup ? warmup : 0;
        double a, b, c;
        summarise(s->ms + sk, s->n - sk, &a, &b, &c);
        printf("  %-24s %10.3f %10.3f %10.3f\n", s->name, a, b, c);
    }
    printf("  %-24s %10.3f %10.3f %10.3f\n", "frame (CPU wall)", med, mean, mn);
}

static void list_views(sl_app *app) {
    printf("final                    the shaded image (default)\n");
    for (int i = 0; i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if (c->d.hook != SL_HOOK_DEBUG_VIEW && c->d.hook != SL_HOOK_DEBUG_VIEW_LIGHT) continue;
        printf("%-24s %s [%s]\n", c->d.name, c->d.description ? c->d.description : "", app->plugins.items[c->owner]->id);
    }
}

static void list_cameras(sl_app *app) {
    const sl_scene *s = &app->scene;
    if (!s->camera_count) printf("(no cameras in %s: the view frames the scene's bounds)\n", s->path);
    for (int i = 0; i < s->camera_count; i++) {
        const sl_camera *cam = &s->cameras[i];
        printf("%-32s %s  position %.4g %.4g %.4g  target %.4g %.4g %.4g  ", cam->name,
               cam->orthographic ? "orthographic" : "perspective ", cam->position[0], cam->position[1],
               cam->position[2], cam->target[0], cam->target[1], cam->target[2]);
        if (cam->orthographic) printf("ymag %.4g\n", cam->ymag);
        else printf("fov_y %.4g deg\n", cam->fov_y_deg);
    }
}

/* ---------------------------------------------------------------- main ------------------ */

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* ------------------------------------------------------------- --turntable ------------- */

/* An executable named `name` in $PATH (what `command -v` finds), without running a shell. */
static bool find_in_path(const char *name, char *out, size_t n) {
    const char *path = getenv("PATH");
    if (!path || !*path) return false;
    for (const char *p = path; *p;) {
        const char *end = strchr(p, ':');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        int w = snprintf(out, n, "%.*s/%s", (int)len, len ? p : ".", name);
        struct stat st;
        if (w > 0 && (size_t)w < n && stat(out, &st) == 0 && S_ISREG(st.st_mode) && access(out, X_OK) == 0) return true;
        if (!end) break;
        p = end + 1;
    }
    return false;
}

/* ffmpeg -framerate 30 -i DIR/frame-%0Nd.png … OUTPUT (H.264/VP9 by the container's default,
 * yuv420p for players; odd sizes padded to even, which yuv420p needs). */
static bool encode_video(const char *ffmpeg, const char *pattern, const char *output) {
    const char *args[] = {ffmpeg, "-y", "-hide_banner", "-loglevel", "error", "-framerate", "30", "-i", pattern, "-vf",
                          "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", output, NULL};
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) { fprintf(stderr, "shadelab: cannot start ffmpeg: %s\n", strerror(errno)); return false; }
    if (pid == 0) {
        execv(ffmpeg, (char *const *)args);
        fprintf(stderr, "shadelab: cannot run %s: %s\n", ffmpeg, strerror(errno));
        _exit(127);
    }
    int status;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return true;
    fprintf(stderr, "shadelab: ffmpeg failed (%s %d) encoding %s\n", WIFEXITED(status) ? "exit status" : "signal",
            WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status), output);
    return false;
}

static void remove_frames(const char *dir) {
    DIR *d = opendir(dir);
    if (d) {
        char path[8192];
        for (struct dirent *e; (e = readdir(d));)
            if (!strncmp(e->d_name, "frame-", 6)) snprintf(path, sizeof path, "%s/%s", dir, e->d_name), unlink(path);
        closedir(d);
    }
    rmdir(dir);
}

/* N frames orbiting the camera once around the scene's bounds (turntable.h); each frame is a
 * still (the frames a plugin's still needs, TAA's history, at the frozen start time), so frame k
 * depends only on its angle and frame N would equal frame 0. */
static int run_turntable(sl_app *app, const sl_cli *c, const char *ffmpeg, recorder *rec, double start, double *first_ms) {
    const char *output = c->output ? c->output : "out.png";
    bool video = sl_cli_is_video(output);
    char dir[4096] = "", base[4200], path[4300], err[4096];
    if (video) {
        const char *tmp = getenv("TMPDIR");
        snprintf(dir, sizeof dir, "%s/shadelab-turntable.XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(dir)) {
            fprintf(stderr, "shadelab: cannot create a directory for the frames (%s): %s\n", dir, strerror(errno));
            return 1;
        }
        snprintf(base, sizeof base, "%s/frame.png", dir);
    } else {
        snprintf(base, sizeof base, "%s", output);
    }
    const int n = c->turntable;
    if (!sl_turntable_frame_path(base, n - 1, n, path, sizeof path)) {
        fprintf(stderr, "shadelab: --output %s: the frame names are too long\n", output);
        if (video) remove_frames(dir);
        return 1;
    }
    const sl_camera_state start_cam = app->camera;
    double t0 = now_ms(), last_report = t0;
    int rc = 0;
    char first[4300] = "";
    for (int k = 0; k < n && !rc; k++) {
        sl_turntable_camera(&start_cam, app->frame_min, app->frame_max, k, n, &app->camera);
        float p[3];
        sl_camera_position(&app->camera, p);
        SL_DEBUG("turntable frame %d: camera at %.4f %.4f %.4f, yaw %.4f rad", k, p[0], p[1], p[2], app->camera.yaw);
        /* A still at this camera. After a move, the first frame is one of motion (TAA reprojects
         * its history) and the still starts at the next: one frame more than the still needs. */
        for (int f = 0;; f++) {
            app->time = c->start_time;
            sl_app_render_frame(app);
            if (k == 0 && f == 0) {
                sl_renderer_finish(app); /* complete, not only issued (the PNG reads it next anyway) */
                *first_ms = now_ms() - start;
                SL_DEBUG("start-up to the first complete frame: %.0f ms", *first_ms);
            }
            if (sl_startup_recording()) { sl_startup_mark("frame 0: outside the passes"); sl_startup_end(); log_startup(); }
            record(rec, sl_renderer_stats(app));
            int still = sl_renderer_still_frames(app);
            if (f + 1 >= (still > 1 && k > 0 ? still + 1 : still)) break;
        }
        sl_turntable_frame_path(base, k, n, path, sizeof path);
        if (!sl_app_save(app, path, err, sizeof err)) { rc = die(err); break; }
        if (k == 0) snprintf(first, sizeof first, "%s", path);
        double t = now_ms();
        if (n > 1 && (t - last_report > 1000 || k == n - 1)) {
            double per = (t - t0) / (k + 1);
            SL_INFO("turntable: frame %d of %d, %.1f s so far, about %.0f s left", k + 1, n, (t - t0) / 1e3,
                    per * (n - k - 1) / 1e3);
            last_report = t;
        }
    }
    app->camera = start_cam;
    if (rc) { if (video) remove_frames(dir); return rc; }
    if (!video) {
        SL_INFO("wrote %d frames %s ... %s (%dx%d, one orbit)", n, first, path, app->backend.width, app->backend.height);
        return 0;
    }
    char pattern[4300];
    int digits = (int)strlen(path) - (int)strlen(dir) - (int)strlen("/frame-.png");
    snprintf(pattern, sizeof pattern, "%s/frame-%%0%dd.png", dir, digits);
    SL_INFO("turntable: encoding %s with %s", output, ffmpeg);
    bool ok = encode_video(ffmpeg, pattern, output);
    remove_frames(dir);
    if (!ok) return 1;
    SL_INFO("wrote %s (%d frames at 30 fps, %dx%d, one orbit)", output, n, app->backend.width, app->backend.height);
    return 0;
}

/* A plugin named on the command line that does not exist is an error, not a disabled record (a
 * typo would otherwise render without it); the loader has said where it looked. */
static bool named_plugins_found(const sl_app *app, char *err, size_t n) {
    for (int i = 0; i < app->plugins.count; i++) {
        const sl_plugin_rec *r = app->plugins.items[i];
        if (r->not_found && !strcmp(r->requested_by, "command line")) {
            snprintf(err, n, "--plugin %s: no such plugin (--list-plugins lists those installed)", r->id);
            return false;
        }
    }
    return true;
}

int main(int argc, char **argv) {
    sl_startup_huge_pages(argv);
    double start = now_ms();
    sl_startup_begin();
    sl_cli c;
    char err[16384] = "";
    sl_cli_result parsed = sl_cli_parse(argc, argv, &c, err, sizeof err);
    if (parsed == SL_CLI_DONE) return 0;
    if (parsed == SL_CLI_ERROR) return die(err);
    sl_startup_mark("command line");
    char ffmpeg[4096] = "";
    if (c.turntable && c.output && sl_cli_is_video(c.output) && !find_in_path("ffmpeg", ffmpeg, sizeof ffmpeg)) {
        snprintf(err, sizeof err, "--output %s: encoding a video needs ffmpeg, which is not installed (it is optional: "
                 "apt-get install ffmpeg); --output NAME.png writes the frames as NAME-000.png ... instead", c.output);
        return die(err);
    }
    /* references: the plugin's declared settings become --set values, its accumulation count applies */
    const char *ref_settings[64];
    int nref = 0;
    char *ref_copy = NULL;
    sl_app app;
    if (!sl_app_init(&app, &c.opt, err, sizeof err) || !named_plugins_found(&app, err, sizeof err)) {
        sl_app_shutdown(&app);
        return die(err);
    }
    if (c.reference) {
        int idx = sl_plugins_find(&app.plugins, c.reference);
        if (idx < 0 || !app.plugins.items[idx]->ok) {
            sl_app_shutdown(&app);
            snprintf(err, sizeof err, "--reference %s: plugin not loaded (add --plugin %s)", c.reference, c.reference);
            return die(err);
        }
        sl_plugin_rec *r = app.plugins.items[idx];
        if (!r->has_reference) {
            sl_app_shutdown(&app);
            snprintf(err, sizeof err, "--reference %s: the plugin declares no reference", c.reference);
            return die(err);
        }
        ref_copy = strdup(r->reference.settings ? r->reference.settings : "");
        char *save = NULL;
        for (char *t = strtok_r(ref_copy, " ", &save); t && nref < 64; t = strtok_r(NULL, " ", &save)) ref_settings[nref++] = t;
        int acc = r->reference.accumulate_frames;
        /* r belongs to the app shut down here: keep what is printed below */
        char ref_description[512];
        snprintf(ref_description, sizeof ref_description, "%s", r->reference.description ? r->reference.description : "");
        sl_app_shutdown(&app);
        for (int i = 0; i < nref && c.opt.setting_count < 128; i++) c.opt.settings[c.opt.setting_count++] = ref_settings[i];
        if (acc > 1 && c.opt.accumulate <= 1) c.opt.accumulate = acc;
        if (!sl_app_init(&app, &c.opt, err, sizeof err)) {
            sl_app_shutdown(&app);
            free(ref_copy);
            return die(err);
        }
        SL_INFO("reference for %s: %s", c.reference, ref_description);
    }
    if (c.auto_quality && !sl_autoquality_apply(&app, c.auto_quality, err, sizeof err)) { sl_app_shutdown(&app); free(ref_copy); return die(err); }
    if (c.list_plugins || c.dump_params || c.list_views || c.help_keys || c.list_cameras) {
        if (c.list_cameras) list_cameras(&app);
        if (c.list_plugins) sl_plugins_print(&app.plugins, stdout);
        if (c.dump_params) sl_params_dump_json(&app.params, stdout);
        if (c.list_views) list_views(&app);
        if (c.help_keys) sl_viewer_print_keys(&app, stdout);
        sl_app_shutdown(&app);
        free(ref_copy);
        return 0;
    }
    if (!sl_app_start_gl(&app, err, sizeof err)) {
        die(err);
        sl_app_shutdown(&app);
        free(ref_copy);
        return 1;
    }
    int rc = 0;
    if (app.backend.has_window && c.frames < 0 && !c.turntable) {
        rc = sl_viewer_run(&app, c.start_time);
    } else if (c.turntable) {
        recorder rec = {0};
        double first_frame_ms = 0;
        rc = run_turntable(&app, &c, ffmpeg, &rec, start, &first_frame_ms);
        if (!rc && c.stats && !write_stats(c.stats, &app, &rec, first_frame_ms, 0)) rc = 1;
        if (!rc && c.bench) print_bench(&app, &rec, 0);
        if (c.explain) sl_renderer_explain(&app, stdout);
        for (int i = 0; i < rec.count; i++) free(rec.s[i].ms);
        free(rec.frame);
    } else {
        if (!app.backend.has_window && !c.output && !c.stats && !c.bench && !c.explain) c.output = "out.png";
        int frames = c.frames > 0 ? c.frames : 1;
        int warmup = frames >= 10 ? 3 : 0;
        recorder rec = {0};
        double first_frame_ms = 0;
        double last_report = now_ms();
        /* Without --frames, a still: the frames a plugin's still image needs (TAA's history, host
         * set_still_frames; 1 otherwise), all at the start time, until it is done (still.h). */
        sl_still still;
        sl_still_begin(&still, c.still_budget);
        bool done = false;
        for (int f = 0; !done; f++) {
            app.time = c.start_time + (c.frames < 0 ? 0 : f * app.opt.fixed_dt);
            sl_app_render_frame(&app);
            if (f == 0) {
                sl_renderer_finish(&app); /* complete, not only issued (the PNG reads it next anyway) */
                first_frame_ms = now_ms() - start;
                SL_DEBUG("start-up to the first complete frame: %.0f ms", first_frame_ms);
            }
            done = c.frames < 0 ? sl_still_done(&still, &app) : f + 1 >= frames;
            if (sl_startup_recording()) {
                sl_startup_mark("frame %d: outside the passes", f);
                /* the first two frames: the second shows what the first paid once */
                if (f == 1 || done) {
                    sl_startup_end();
                    log_startup();
                }
            }
            record(&rec, sl_renderer_stats(&app));
            if (app.backend.has_window) { glfwPollEvents(); sl_backend_swap(&app.backend); }
            if (frames > 1 && now_ms() - last_report > 2000) {
                SL_INFO("frame %d of %d", f + 1, frames);
                last_report = now_ms();
            }
        }
        if (c.frames < 0 && strcmp(still.stopped, "complete"))
            SL_INFO("still: %d of %d frames, stopped: %s", still.frames, still.needed,
                    !strcmp(still.stopped, "budget") ? "--still-budget ran out" : "no display value changed by 1/255");
        sl_still_end(&still);
        if (c.output) {
            if (!sl_app_save(&app, c.output, err, sizeof err)) rc = die(err);
            else SL_INFO("wrote %s (%dx%d, %s%s)", c.output, app.backend.width, app.backend.height, app.backend.name,
                         app.backend.has_window ? "" : ", headless");
        }
        if (c.stats && !write_stats(c.stats, &app, &rec, first_frame_ms, warmup)) rc = 1;
        if (c.bench) {
            print_bench(&app, &rec, warmup);
            printf("  startup to first frame: %.1f ms\n", first_frame_ms);
            printf("  peak memory (resident): %.1f MiB\n", peak_rss_mib());
            printf("  triangles: %ld in the scene, %ld drawn in the last frame (every pass)\n", scene_triangles(&app.scene),
                   sl_renderer_stats(&app)->triangles);
        }
        if (c.explain) sl_renderer_explain(&app, stdout);
        for (int i = 0; i < rec.count; i++) free(rec.s[i].ms);
        free(rec.frame);
    }
    if (!rc && app.strict_failure) rc = die(app.strict_failure);
    /* A render that printed an error (a magenta stand-in for a texture, a plugin switched off for
     * its GLSL, a pass skipped) wrote its image but must not look like a clean one to a script. */
    bool interactive = app.backend.has_window && c.frames < 0 && !c.turntable;
    int errors = sl_log_count(SL_LOG_ERROR);
    if (!rc && !interactive && errors) {
        fprintf(stderr, "shadelab: %d error%s above; exit status 2 (the output was written)\n", errors, errors > 1 ? "s" : "");
        rc = 2;
    }
    sl_app_shutdown(&app);
    free(ref_copy);
    return rc;
}
