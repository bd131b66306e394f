/* shadelab-xcheck: a scene or model file against Blender's path tracer (docs/xcheck.md).
 * Exports the scene as a Blender scene, renders it with Cycles (cached by a hash of the export,
 * Blender's version and the sample count), renders the same view with shadelab and compares them
 * before tone mapping, per object and per material. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "compare.h"
#include "export.h"
#include "bench/metrics.h"
#include "toolkit.h"

#define XC_EXIT_NO_BLENDER 77 /* ctest's skip code: the cross-check cannot run without Blender */

static const char usage[] =
    "usage: shadelab-xcheck [options] SCENE.json|MODEL.gltf|MODEL.glb\n"
    "Renders SCENE with Blender's Cycles and with shadelab, and compares them before tone mapping.\n"
    "  --size WxH         image size (default 256x256)\n"
    "  --samples N        Cycles samples per pixel (default 128)\n"
    "  --bounces N        Cycles' light bounces (default 8; 0 = direct light only)\n"
    "  --unoccluded       objects seen by camera rays only in the reference: no object occludes,\n"
    "                     shadows or reflects any object (environment lighting without visibility,\n"
    "                     as IBL methods compute it); the default is the full path-traced scene\n"
    "  --out DIR          where the report and images go (default xcheck-<scene name>)\n"
    "  --set ID=VALUE     a shadelab setting, applied before the export (repeatable)\n"
    "  --plugin NAME      load a plugin (repeatable)\n"
    "  --camera NAME      the scene camera to use\n"
    "  --data DIR         data directory for scene assets\n"
    "  --frames N         shadelab frames rendered, at least (default 8; more where the still needs\n"
    "                     them: TAA's history); the last is compared\n"
    "  --noise N          also measure each region's noise: the spread of samples 0..N-1 of an\n"
    "                     N-frame still, each rendered on its own, at FLIP's exposure (2..1024)\n"
    "  --reference-only   export and render Cycles only (DIR/cycles.exr, DIR/index.exr; with --eevee,\n"
    "                     DIR/eevee-N.exr and their times in DIR/eevee.tsv)\n"
    "  --export-only      export the Blender scene only (DIR/blender/) and print what is not\n"
    "                     cross-checked; needs no Blender\n"
    "  --eevee N[,N...]   also render with EEVEE at these sample counts (under xvfb-run without a\n"
    "                     display) and report its error and time beside shadelab's\n"
    "  --blender PATH     the Blender executable (default $SHADELAB_BLENDER or blender)\n"
    "  --cache DIR        reference cache (default $SHADELAB_CACHE, $XDG_CACHE_HOME/shadelab or\n"
    "                     ~/.cache/shadelab; references under DIR/xcheck/)\n"
    "  --no-cache         always render the reference\n"
    "  --max-rel-rms X    exit 1 when a cross-checked object's relative RMS exceeds X\n"
    "Writes DIR/report.txt (printed), DIR/report.json, DIR/shadelab.exr, DIR/cycles.exr,\n"
    "DIR/index.exr, DIR/error.png, DIR/side_by_side.png and the Blender scene in DIR/blender/.\n"
    "Exit status: 0 done, 1 error (or --max-rel-rms exceeded), 2 done but shadelab printed errors (the\n"
    "report is written), 77 Blender is not installed.\n";

typedef struct options {
    const char *scene, *out, *blender, *cache, *camera, *data;
    int width, height, samples, bounces, frames, noise;
    bool reference_only, export_only, no_cache, unoccluded;
    double max_rel_rms;
    const char *settings[128]; int setting_count;
    const char *plugins[64]; int plugin_count;
    int eevee[16]; int eevee_count;
} options;

static bool parse(int argc, char **argv, options *o) {
    *o = (options){.width = 256, .height = 256, .samples = 128, .bounces = 8, .frames = 8, .max_rel_rms = -1};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool has_next = i + 1 < argc;
#define NEXT() (has_next ? argv[++i] : NULL)
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { fputs(usage, stdout); exit(0); }
        else if (!strcmp(a, "--reference-only")) o->reference_only = true;
        else if (!strcmp(a, "--export-only")) o->export_only = true;
        else if (!strcmp(a, "--no-cache")) o->no_cache = true;
        else if (!strcmp(a, "--unoccluded")) o->unoccluded = true;
        else if (a[0] == '-' && a[1] == '-' && !has_next) { fprintf(stderr, "shadelab-xcheck: %s needs a value\n", a); return false; }
        else if (!strcmp(a, "--size")) {
            const char *v = NEXT();
            if (sscanf(v, "%dx%d", &o->width, &o->height) != 2 || o->width < 8 || o->height < 8 || o->width > 8192 ||
                o->height > 8192) {
                fprintf(stderr, "shadelab-xcheck: --size %s: expected WxH, 8..8192 each\n", v);
                return false;
            }
        } else if (!strcmp(a, "--samples") || !strcmp(a, "--bounces") || !strcmp(a, "--frames") ||
                   !strcmp(a, "--noise")) {
            const char *v = NEXT();
            char *end;
            long x = strtol(v, &end, 10);
            long lo = !strcmp(a, "--bounces") ? 0 : !strcmp(a, "--noise") ? 2 : 1, hi = !strcmp(a, "--samples") ? 1 << 20 : 1024;
            if (*end || x < lo || x > hi) {
                fprintf(stderr, "shadelab-xcheck: %s %s: expected an integer in [%ld, %ld]\n", a, v, lo, hi);
                return false;
            }
            if (!strcmp(a, "--samples")) o->samples = (int)x;
            else if (!strcmp(a, "--bounces")) o->bounces = (int)x;
            else if (!strcmp(a, "--noise")) o->noise = (int)x;
            else o->frames = (int)x;
        } else if (!strcmp(a, "--max-rel-rms")) {
            const char *v = NEXT();
            char *end;
            o->max_rel_rms = strtod(v, &end);
            if (*end || !(o->max_rel_rms >= 0)) { fprintf(stderr, "shadelab-xcheck: --max-rel-rms %s: expected a number >= 0\n", v); return false; }
        } else if (!strcmp(a, "--eevee")) {
            const char *v = NEXT();
            char *end;
            for (const char *p = v; *p; p = *end == ',' ? end + 1 : end) {
                long x = strtol(p, &end, 10);
                if (end == p || (*end && *end != ',') || x < 1 || x > 4096 || o->eevee_count == 16) {
                    fprintf(stderr, "shadelab-xcheck: --eevee %s: expected up to 16 sample counts 1..4096, comma-separated\n", v);
                    return false;
                }
                o->eevee[o->eevee_count++] = (int)x;
            }
        } else if (!strcmp(a, "--out")) o->out = NEXT();
        else if (!strcmp(a, "--blender")) o->blender = NEXT();
        else if (!strcmp(a, "--cache")) o->cache = NEXT();
        else if (!strcmp(a, "--camera")) o->camera = NEXT();
        else if (!strcmp(a, "--data")) o->data = NEXT();
        else if (!strcmp(a, "--set")) {
            if (o->setting_count == 127) { fprintf(stderr, "shadelab-xcheck: too many --set\n"); return false; }
            o->settings[o->setting_count++] = NEXT();
        } else if (!strcmp(a, "--plugin")) {
            if (o->plugin_count == 63) { fprintf(stderr, "shadelab-xcheck: too many --plugin\n"); return false; }
            o->plugins[o->plugin_count++] = NEXT();
        } else if (a[0] == '-') { fprintf(stderr, "shadelab-xcheck: unknown option %s\n%s", a, usage); return false; }
        else if (o->scene) { fprintf(stderr, "shadelab-xcheck: one scene at a time (%s and %s)\n", o->scene, a); return false; }
        else o->scene = a;
#undef NEXT
    }
    if (!o->scene) { fputs(usage, stderr); return false; }
    return true;
}

/* ------------------------------------------------------------------------------ blender -- */

static const char *blender_path(const options *o) {
    if (o->blender) return o->blender;
    const char *env = getenv("SHADELAB_BLENDER");
    return env && *env ? env : "blender";
}

/* Single-quotes s for /bin/sh. */
static void shell_quote(const char *s, char *out, size_t n) {
    size_t u = 0;
    if (u < n) out[u++] = '\'';
    for (; *s && u + 5 < n; s++) {
        if (*s == '\'') { memcpy(out + u, "'\\''", 4); u += 4; }
        else out[u++] = *s;
    }
    if (u < n) out[u++] = '\'';
    out[u < n ? u : n - 1] = 0;
}

/* "Blender 3.4.1" (the first line of blender --version), or false when it does not run. */
static bool blender_version(const char *blender, char *version, size_t n) {
    char q[4200], cmd[4400];
    shell_quote(blender, q, sizeof q);
    snprintf(cmd, sizeof cmd, "%s --version 2>/dev/null", q);
    FILE *p = popen(cmd, "r");
    if (!p) return false;
    char line[256] = "";
    version[0] = 0;
    while (fgets(line, sizeof line, p))
        if (!version[0] && !strncmp(line, "Blender ", 8)) {
            line[strcspn(line, "\r\n")] = 0;
            snprintf(version, n, "%s", line);
        }
    int status = pclose(p);
    return version[0] && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

static double now_seconds(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static bool copy_file(const char *from, const char *to, char *err, size_t n) {
    FILE *in = fopen(from, "rb");
    if (!in) { snprintf(err, n, "%s: %s", from, strerror(errno)); return false; }
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", to, (long)getpid());
    FILE *out = fopen(tmp, "wb");
    if (!out) { fclose(in); snprintf(err, n, "%s: %s", tmp, strerror(errno)); return false; }
    char buf[65536];
    size_t k;
    bool ok = true;
    while ((k = fread(buf, 1, sizeof buf, in)) > 0) ok &= fwrite(buf, 1, k, out) == k;
    ok &= !ferror(in);
    fclose(in);
    ok &= fclose(out) == 0;
    if (ok && rename(tmp, to) != 0) ok = false;
    if (!ok) { remove(tmp); snprintf(err, n, "%s: cannot copy to %s: %s", from, to, strerror(errno)); }
    return ok;
}

static void cache_dir(const options *o, char *out, size_t n) {
    const char *base = o->cache ? o->cache : getenv("SHADELAB_CACHE");
    if (base && *base) { snprintf(out, n, "%s/xcheck", base); return; }
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (xdg && *xdg) snprintf(out, n, "%s/shadelab/xcheck", xdg);
    else snprintf(out, n, "%s/.cache/shadelab/xcheck", home && *home ? home : "/tmp");
}

/* Renders DIR/blender/scene.py with Cycles into DIR/cycles.exr and DIR/index.exr, or copies them
 * from the cache. */
static bool cycles_reference(const options *o, const char *dir, uint64_t key, const char *blender, bool gltf,
                             bool *cached, double *seconds, char *err, size_t n) {
    char cdir[4096], cached_img[4200], cached_idx[4200], out_img[4200], out_idx[4200];
    cache_dir(o, cdir, sizeof cdir);
    snprintf(cdir + strlen(cdir), sizeof cdir - strlen(cdir), "/%016llx", (unsigned long long)key);
    snprintf(cached_img, sizeof cached_img, "%s/combined.exr", cdir);
    snprintf(cached_idx, sizeof cached_idx, "%s/index.exr", cdir);
    snprintf(out_img, sizeof out_img, "%s/cycles.exr", dir);
    snprintf(out_idx, sizeof out_idx, "%s/index.exr", dir);
    *cached = false;
    *seconds = 0;
    struct stat st;
    char cached_obj[4200], out_obj[4200];
    snprintf(cached_obj, sizeof cached_obj, "%s/objects.json", cdir);
    snprintf(out_obj, sizeof out_obj, "%s/objects.json", dir);
    if (!o->no_cache && stat(cached_img, &st) == 0 && stat(cached_idx, &st) == 0 &&
        (!gltf || stat(cached_obj, &st) == 0)) {
        *cached = true;
        return copy_file(cached_img, out_img, err, n) && copy_file(cached_idx, out_idx, err, n) &&
               (!gltf || copy_file(cached_obj, out_obj, err, n));
    }
    char render_dir[4200], qb[4200], qs[4400], qr[4400], ql[4400], cmd[20000];
    snprintf(render_dir, sizeof render_dir, "%s/blender/render", dir);
    char script[4300], log[4300];
    snprintf(script, sizeof script, "%s/blender/scene.py", dir);
    snprintf(log, sizeof log, "%s/blender.log", dir);
    shell_quote(blender, qb, sizeof qb);
    shell_quote(script, qs, sizeof qs);
    shell_quote(render_dir, qr, sizeof qr);
    shell_quote(log, ql, sizeof ql);
    snprintf(cmd, sizeof cmd, "%s -b --factory-startup --python-exit-code 1 --python %s -- %s > %s 2>&1", qb, qs, qr, ql);
    fprintf(stderr, "[xcheck] Cycles: %dx%d, %d samples, %d bounces%s (log: %s)\n", o->width, o->height, o->samples,
            o->bounces, o->unoccluded ? ", unoccluded" : "", log);
    double t0 = now_seconds();
    int status = system(cmd);
    *seconds = now_seconds() - t0;
    char img[4300], idx[4300], obj[4300];
    snprintf(img, sizeof img, "%s/combined_0000.exr", render_dir);
    snprintf(idx, sizeof idx, "%s/index_0000.exr", render_dir);
    snprintf(obj, sizeof obj, "%s/objects.json", render_dir);
    if (status != 0 || stat(img, &st) != 0 || stat(idx, &st) != 0 || (gltf && stat(obj, &st) != 0)) {
        snprintf(err, n, "Blender failed (exit status %d) for %s; its output is in %s", WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                 script, log);
        return false;
    }
    if (!copy_file(img, out_img, err, n) || !copy_file(idx, out_idx, err, n) ||
        (gltf && !copy_file(obj, out_obj, err, n)))
        return false;
    if (!o->no_cache) {
        char why[512];
        if (xc_mkdirs(cdir, why, sizeof why) && (!gltf || copy_file(obj, cached_obj, why, sizeof why)) &&
            copy_file(idx, cached_idx, why, sizeof why) && copy_file(img, cached_img, why, sizeof why)) {
        } else {
            fprintf(stderr, "[xcheck] warning: the reference is not cached: %s\n", why);
        }
    }
    return true;
}

/* EEVEE's render of the exported scene at `samples` samples into DIR/eevee-N.exr; *ms = the timed
 * render (after a one-sample render that compiles its shaders). Under xvfb-run when there is no
 * display: EEVEE needs an OpenGL context even in background mode. */
static bool eevee_render(const char *dir, const char *blender, int samples, double *ms, char *err, size_t n) {
    char render_dir[4200], script[4300], log[4300], qb[4200], qs[4400], qr[4400], ql[4400], cmd[20000];
    snprintf(render_dir, sizeof render_dir, "%s/blender/eevee-%d", dir, samples);
    snprintf(script, sizeof script, "%s/blender/scene.py", dir);
    snprintf(log, sizeof log, "%s/eevee-%d.log", dir, samples);
    shell_quote(blender, qb, sizeof qb);
    shell_quote(script, qs, sizeof qs);
    shell_quote(render_dir, qr, sizeof qr);
    shell_quote(log, ql, sizeof ql);
    const char *display = getenv("DISPLAY");
    snprintf(cmd, sizeof cmd, "%s%s -b --factory-startup --python-exit-code 1 --python %s -- %s --eevee %d > %s 2>&1",
             display && *display ? "" : "xvfb-run -a ", qb, qs, qr, samples, ql);
    fprintf(stderr, "[xcheck] EEVEE: %d samples (log: %s)\n", samples, log);
    int status = system(cmd);
    char img[4300], out[4300];
    snprintf(img, sizeof img, "%s/eevee_0000.exr", render_dir);
    snprintf(out, sizeof out, "%s/eevee-%d.exr", dir, samples);
    struct stat st;
    if (status != 0 || stat(img, &st) != 0) {
        snprintf(err, n, "EEVEE failed (exit status %d; xvfb-run is needed without a display); its output is in %s",
                 WIFEXITED(status) ? WEXITSTATUS(status) : -1, log);
        return false;
    }
    *ms = NAN;
    FILE *f = fopen(log, "r");
    char line[512];
    while (f && fgets(line, sizeof line, f)) sscanf(line, "xcheck-blender: eevee %*d samples %lf ms", ms);
    if (f) fclose(f);
    return copy_file(img, out, err, n);
}

/* ------------------------------------------------------------------------------ shadelab -- */

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Renders the scene's still, as a headless still does: every frame at scene time 0, at least
 * o->frames frames and at least the frames the plugins' still needs (TAA's history: the image
 * compared is its converged mean, not a part of it), the first untimed; reads the last one's
 * linear colour; *ms = the median CPU time of the timed frames. */
static bool render_shadelab(sl_app *app, const options *o, float *rgba, double *ms, char *err, size_t n) {
    if (!sl_app_start_gl(app, err, n)) return false;
    enum { MAX_FRAMES = 1024 };
    double times[MAX_FRAMES];
    int timed = 0;
    for (int f = 0; f < MAX_FRAMES; f++) {
        app->time = 0;
        if (!sl_app_render_frame(app)) { snprintf(err, n, "shadelab could not render frame %d", f); return false; }
        sl_tool_frame_times t;
        sl_tool_frame_times_of(app, &t);
        if (f > 0 || o->frames == 1) times[timed++] = t.frame_ms;
        if (f + 1 >= o->frames && f + 1 >= sl_tool_still_frames(app)) break;
    }
    qsort(times, timed, sizeof *times, cmp_double);
    *ms = timed ? times[timed / 2] : NAN;
    if (!sl_app_read_color(app, rgba)) { snprintf(err, n, "shadelab: cannot read the frame"); return false; }
    if (app->strict_failure) { snprintf(err, n, "%s", app->strict_failure); return false; }
    return true;
}

/* The noise measure (shadelab-bench's, tools/bench/include/bench/metrics.h: sl_noise_*): samples
 * k = 0 … N−1 of an N-frame still (N = --noise), each rendered on its own at time 0
 * (sl_tool_render_sample: no TAA history, no accumulation), at the exposure FLIP reads them at
 * (`scale`, xc_display_scale); each pixel's variance (its standard deviation, RMS over R, G, B,
 * squared) into var, w*h floats. img: w*h RGBA floats of scratch. */
static bool render_noise(sl_app *app, const options *o, double scale, float *img, float *var, char *err, size_t n) {
    sl_noise_acc acc;
    if (!sl_noise_begin(&acc, o->width, o->height)) { snprintf(err, n, "out of memory"); return false; }
    size_t px = (size_t)o->width * o->height;
    for (int k = 0; k < o->noise; k++) {
        app->time = 0;
        if (!sl_tool_render_sample(app, k, o->noise) || !sl_app_read_color(app, img)) {
            sl_noise_end(&acc, NULL);
            snprintf(err, n, "shadelab could not render noise sample %d of %d", k, o->noise);
            return false;
        }
        for (size_t p = 0; p < px; p++)
            for (int c = 0; c < 3; c++) img[p * 4 + c] *= (float)scale;
        sl_noise_add(&acc, img);
    }
    sl_noise_end(&acc, var);
    for (size_t p = 0; p < px; p++) var[p] *= var[p];
    return true;
}

/* ------------------------------------------------------------------------------- report -- */

static void print_row(FILE *f, const char *name, const char *material, const xc_stats *s, bool checked) {
    if (!s->pixels) {
        fprintf(f, "  %-24s %-18s %8s  (not visible)\n", name, material, "");
        return;
    }
    fprintf(f, "  %-24s %-18s %8ld  %8.4f  %8.4f  %8.4f  %10.4g  %10.4g", name, material, s->pixels, s->rel_rms,
            s->mean_ratio, s->flip, s->mean_test, s->mean_ref);
    if (isfinite(s->noise)) fprintf(f, "  %8.5f", s->noise);
    fprintf(f, "%s\n", checked ? "" : "  (not cross-checked)");
}

/* s as a JSON string (quotes, backslashes and control characters escaped). */
static void json_string(FILE *f, const char *s) {
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\') fprintf(f, "\\%c", *s);
        else if ((unsigned char)*s < 0x20) fprintf(f, "\\u%04x", (unsigned char)*s);
        else fputc(*s, f);
    }
    fputc('"', f);
}

static void json_stats(FILE *f, const char *name, const char *material, const xc_stats *s, bool checked, bool last) {
    fprintf(f, "    {\"name\": ");
    json_string(f, name);
    fprintf(f, ", \"material\": ");
    json_string(f, material);
    fprintf(f, ", \"pixels\": %ld, \"rel_rms\": %.6g, \"mean_ratio\": %.6g, \"flip\": %.6g, \"mean_shadelab\": %.6g, "
               "\"mean_cycles\": %.6g, \"noise\": %.6g, \"cross_checked\": %s}%s\n",
            s->pixels, isfinite(s->rel_rms) ? s->rel_rms : -1, isfinite(s->mean_ratio) ? s->mean_ratio : -1,
            isfinite(s->flip) ? s->flip : -1, s->mean_test, s->mean_ref, isfinite(s->noise) ? s->noise : -1,
            checked ? "true" : "false", last ? "" : ",");
}

typedef struct report_ctx {
    const options *o;
    sl_app *app;
    const xc_export *ex;
    const float *test, *ref, *index;
    const float *noise_var; /* --noise: each pixel's variance over the samples (NULL: not measured) */
    int w, h;
    const char *blender_version;
    double cycles_seconds, shadelab_ms;
    bool cached;
    uint64_t key;
    const float *eevee[16]; double eevee_ms[16]; /* one per o->eevee sample count */
} report_ctx;

/* A region's statistics, its FLIP from the map (when there is one), as a row of both reports. */
static xc_stats region_row(const report_ctx *r, FILE *txt, FILE *json, const float *flip, const unsigned char *mask,
                           const char *name, const char *material, bool checked, bool last) {
    xc_stats s;
    xc_region_stats(r->test, r->ref, mask, r->w, r->h, &s);
    s.flip = flip ? xc_masked_mean(flip, mask, r->w, r->h) : NAN;
    s.noise = r->noise_var ? sqrt(xc_masked_mean(r->noise_var, mask, r->w, r->h)) : NAN;
    print_row(txt, name, material, &s, checked);
    json_stats(json, name, material, &s, checked, last);
    return s;
}

static void report_header(const report_ctx *r, FILE *txt, FILE *json) {
    fprintf(txt, "shadelab-xcheck %s: %dx%d, Cycles (%s) %d samples, %d bounces%s\n", r->o->scene, r->w, r->h,
            r->blender_version, r->o->samples, r->o->bounces, r->cached ? ", reference from the cache" : "");
    fprintf(txt, "reference: %s\n", r->o->unoccluded
                     ? "UNOCCLUDED (--unoccluded): objects seen by camera rays only; no occlusion, shadows or "
                       "inter-reflection"
                     : "the full scene, path-traced (occlusion, shadows, inter-reflection)");
    if (!r->cached) fprintf(txt, "Cycles: %.1f s (Blender start-up included)\n", r->cycles_seconds);
    fprintf(txt, "shadelab: %.2f ms per frame (median)\n", r->shadelab_ms);
    fprintf(txt, "compared before tone mapping, on each object's interior (its pixels whose four neighbours are it too);\n"
                 "FLIP: LDR-FLIP of both images at one exposure (Cycles' 99th-percentile luminance at 1)\n");
    if (r->noise_var)
        fprintf(txt, "noise (last column): the spread of %d samples of shadelab's still, each rendered on its own, at\n"
                     "FLIP's exposure, sRGB-encoded, RMS over the region (shadelab-bench's noise)\n", r->o->noise);
    fprintf(json, "{\n  \"scene\": ");
    json_string(json, r->o->scene);
    fprintf(json, ", \"plugins\": \"");
    for (int i = 0, first = 1; i < r->app->plugins.count; i++) {
        const sl_plugin_rec *p = r->app->plugins.items[i];
        if (!p->ok || !strcmp(p->id, "core")) continue;
        fprintf(json, "%s%s", first ? "" : ", ", p->id);
        first = 0;
    }
    fprintf(json, "\", \"width\": %d, \"height\": %d, \"samples\": %d, \"bounces\": %d, \"object_rays\": \"%s\",\n"
                  "  \"blender\": \"%s\", \"reference_key\": \"%016llx\", \"cycles_seconds\": %.3f, \"shadelab_ms\": %.4f,\n"
                  "  \"noise_samples\": %d,\n",
            r->w, r->h, r->o->samples, r->o->bounces, r->o->unoccluded ? "camera" : "all", r->blender_version,
            (unsigned long long)r->key, r->cycles_seconds,
            r->shadelab_ms, r->noise_var ? r->o->noise : 0);
}

static void table_heading(FILE *txt, const char *first, const char *second) {
    fprintf(txt, "\n  %-24s %-18s %8s  %8s  %8s  %8s  %10s  %10s\n", first, second, "pixels", "rel-RMS", "ratio", "FLIP",
            "shadelab", "Cycles");
}

/* Per object; returns the largest relative RMS of a cross-checked one. */
static double report_objects(const report_ctx *r, FILE *txt, FILE *json, const float *flip, unsigned char *mask) {
    double worst = 0;
    table_heading(txt, "object", "material");
    fprintf(json, "  \"objects\": [\n");
    for (int i = 0; i < r->ex->object_count; i++) {
        const xc_object *ob = &r->ex->objects[i];
        xc_region_mask(r->index, r->w, r->h, i + 1, mask);
        xc_stats s = region_row(r, txt, json, flip, mask, ob->name, ob->material, ob->checked, i == r->ex->object_count - 1);
        if (ob->checked && s.pixels && !(s.rel_rms <= worst)) worst = s.rel_rms;
    }
    fprintf(json, "  ],\n");
    return worst;
}

/* Per material: each once, on the union of its objects' interiors. */
static void report_materials(const report_ctx *r, FILE *txt, FILE *json, const float *flip, unsigned char *mask) {
    const xc_export *ex = r->ex;
    size_t n = (size_t)r->w * r->h;
    unsigned char *one = malloc(n);
    table_heading(txt, "material", "");
    fprintf(json, "  \"materials\": [\n");
    for (int i = 0, first = 1; one && i < ex->object_count; i++) {
        const char *m = ex->objects[i].material;
        bool seen = false, checked = true;
        for (int k = 0; k < i; k++) seen |= !strcmp(ex->objects[k].material, m);
        if (seen || !m[0]) continue;
        memset(mask, 0, n);
        for (int k = i; k < ex->object_count; k++) {
            if (strcmp(ex->objects[k].material, m)) continue;
            checked &= ex->objects[k].checked;
            xc_region_mask(r->index, r->w, r->h, k + 1, one);
            for (size_t p = 0; p < n; p++) mask[p] |= one[p];
        }
        fprintf(json, "%s", first ? "" : ",\n");
        region_row(r, txt, json, flip, mask, m, "", checked, true);
        first = 0;
    }
    fprintf(json, "  ],\n");
    free(one);
}

/* The background, the whole image and the interiors (left in mask); returns the interiors'. */
static xc_stats report_regions(const report_ctx *r, FILE *txt, FILE *json, const float *flip, unsigned char *mask) {
    fprintf(txt, "\n");
    xc_region_mask(r->index, r->w, r->h, 0, mask);
    fprintf(json, "  \"background\": ");
    region_row(r, txt, json, flip, mask, "(background)", "", true, true);
    fprintf(json, "  , \"whole_image\": ");
    region_row(r, txt, json, flip, NULL, "(whole image)", "", true, true);
    xc_interior_mask(r->index, r->w, r->h, mask);
    fprintf(json, "  , \"interiors\": ");
    return region_row(r, txt, json, flip, mask, "(interiors)", "", true, true);
}

/* One image's statistics against the reference over mask, with its FLIP from map (or none). */
static xc_stats masked_stats(const report_ctx *r, const float *img, const float *map, const unsigned char *mask) {
    xc_stats s;
    xc_region_stats(img, r->ref, mask, r->w, r->h, &s);
    s.flip = map ? xc_masked_mean(map, mask, r->w, r->h) : NAN;
    return s;
}

/* Per object, shadelab beside each EEVEE render (relative RMS / FLIP), and on how many objects
 * shadelab is at or below each. flips[k]: EEVEE k's FLIP map (or NULL); flip: shadelab's. */
static void report_eevee_objects(const report_ctx *r, FILE *txt, const float *flip, float *const *flips,
                                 unsigned char *mask) {
    int n = r->ex->object_count, better_rr[16] = {0}, better_flip[16] = {0}, visible = 0;
    fprintf(txt, "\nPer object, relative RMS / FLIP:\n  %-24s %-16s", "object", "shadelab");
    for (int k = 0; k < r->o->eevee_count; k++) fprintf(txt, "  EEVEE %-10d", r->o->eevee[k]);
    fprintf(txt, "\n");
    for (int i = 0; i < n; i++) {
        xc_region_mask(r->index, r->w, r->h, i + 1, mask);
        xc_stats s = masked_stats(r, r->test, flip, mask);
        if (!s.pixels) continue;
        visible++;
        fprintf(txt, "  %-24s %.4f / %.4f ", r->ex->objects[i].name, s.rel_rms, s.flip);
        for (int k = 0; k < r->o->eevee_count; k++) {
            xc_stats e = masked_stats(r, r->eevee[k], flips[k], mask);
            fprintf(txt, "  %.4f / %.4f ", e.rel_rms, e.flip);
            better_rr[k] += s.rel_rms <= e.rel_rms, better_flip[k] += s.flip <= e.flip;
        }
        fprintf(txt, "\n");
    }
    for (int k = 0; k < r->o->eevee_count; k++)
        fprintf(txt, "  shadelab at or below EEVEE %d on %d of %d objects by relative RMS, %d by FLIP\n", r->o->eevee[k],
                better_rr[k], visible, better_flip[k]);
}

/* EEVEE k's objects for the report's JSON: name, relative RMS, mean ratio, FLIP. */
static void json_eevee_objects(const report_ctx *r, FILE *json, int k, const float *map, unsigned char *mask) {
    fprintf(json, ", \"objects\": [");
    for (int i = 0; i < r->ex->object_count; i++) {
        xc_region_mask(r->index, r->w, r->h, i + 1, mask);
        xc_stats e = masked_stats(r, r->eevee[k], map, mask);
        fprintf(json, "%s{\"name\": ", i ? ", " : "");
        json_string(json, r->ex->objects[i].name);
        fprintf(json, ", \"pixels\": %ld, \"rel_rms\": %.6g, \"mean_ratio\": %.6g, \"flip\": %.6g}", e.pixels,
                isfinite(e.rel_rms) ? e.rel_rms : -1, isfinite(e.mean_ratio) ? e.mean_ratio : -1,
                isfinite(e.flip) ? e.flip : -1);
    }
    fprintf(json, "]");
}

/* EEVEE's renders over the interiors (interiors: their mask), beside shadelab's figures, then per
 * object. flip: shadelab's FLIP map (kept); scratch: a mask to overwrite. */
static void report_eevee(const report_ctx *r, FILE *txt, FILE *json, const xc_stats *inner, double scale,
                         const float *flip, const unsigned char *interiors, unsigned char *scratch) {
    if (!r->o->eevee_count) return;
    float *flips[16] = {0};
    fprintf(txt, "\nEEVEE against Cycles (the same interiors; shadelab: rel-RMS %.4f, ratio %.4f, FLIP %.4f, %.2f ms):\n",
            inner->rel_rms, inner->mean_ratio, inner->flip, r->shadelab_ms);
    fprintf(json, "  , \"eevee\": [\n");
    for (int k = 0; k < r->o->eevee_count; k++) {
        flips[k] = malloc((size_t)r->w * r->h * sizeof *flips[k]);
        if (flips[k] && !isfinite(xc_flip_map(r->eevee[k], r->ref, r->w, r->h, scale, flips[k]))) {
            free(flips[k]);
            flips[k] = NULL;
        }
        xc_stats e = masked_stats(r, r->eevee[k], flips[k], interiors);
        fprintf(txt, "  %4d samples: rel-RMS %.4f, ratio %.4f, FLIP %.4f, %.1f ms per render (%.1fx shadelab's frame)\n",
                r->o->eevee[k], e.rel_rms, e.mean_ratio, e.flip, r->eevee_ms[k], r->eevee_ms[k] / r->shadelab_ms);
        fprintf(json, "    {\"samples\": %d, \"ms\": %.3f, \"interiors\": {\"rel_rms\": %.6g, \"mean_ratio\": %.6g, "
                      "\"flip\": %.6g}",
                r->o->eevee[k], r->eevee_ms[k], e.rel_rms, e.mean_ratio, isfinite(e.flip) ? e.flip : -1);
        json_eevee_objects(r, json, k, flips[k], scratch);
        fprintf(json, "}%s\n", k + 1 < r->o->eevee_count ? "," : "");
    }
    fprintf(json, "  ]\n");
    report_eevee_objects(r, txt, flip, flips, scratch);
    for (int k = 0; k < r->o->eevee_count; k++) free(flips[k]);
}

static void report_notes(const xc_export *ex, FILE *txt, FILE *json) {
    fprintf(json, "  , \"notes\": [");
    if (ex->note_count) fprintf(txt, "\n");
    for (int i = 0; i < ex->note_count; i++) {
        fprintf(txt, "%s\n", ex->notes[i]);
        fprintf(json, "%s\n    ", i ? "," : "");
        json_string(json, ex->notes[i]);
    }
    fprintf(json, "]\n}\n");
}

/* Prints and writes the report; returns the largest relative RMS of a cross-checked object. */
static double report(const report_ctx *r, FILE *txt, FILE *json) {
    unsigned char *mask = malloc((size_t)r->w * r->h);
    float *flip = malloc((size_t)r->w * r->h * sizeof *flip);
    if (!mask) return INFINITY;
    /* FLIP reads the display range: both images at one exposure (Cycles' 99th percentile at 1) */
    double scale = xc_display_scale(r->ref, r->w, r->h);
    if (flip && !isfinite(xc_flip_map(r->test, r->ref, r->w, r->h, scale, flip))) { free(flip); flip = NULL; }
    report_header(r, txt, json);
    double worst = report_objects(r, txt, json, flip, mask);
    report_materials(r, txt, json, flip, mask);
    xc_stats inner = report_regions(r, txt, json, flip, mask);
    unsigned char *scratch = malloc((size_t)r->w * r->h);
    if (scratch) report_eevee(r, txt, json, &inner, scale, flip, mask, scratch);
    free(scratch);
    report_notes(r->ex, txt, json);
    free(flip);
    free(mask);
    return worst;
}

/* ------------------------------------------------------------------------------ main ---- */

static void default_out(const char *scene, char *out, size_t n) {
    const char *base = strrchr(scene, '/');
    base = base ? base + 1 : scene;
    char stem[256];
    snprintf(stem, sizeof stem, "%s", base);
    char *dot = strrchr(stem, '.');
    if (dot && dot != stem) *dot = 0;
    snprintf(out, n, "xcheck-%s", stem);
}

static bool find_builder(char *out, size_t n) {
    const char *env = getenv("SHADELAB_XCHECK_BUILDER");
    struct stat st;
    if (env && *env) { snprintf(out, n, "%s", env); return stat(out, &st) == 0; }
    char exe[4096];
    ssize_t k = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (k > 0) {
        exe[k] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) *slash = 0;
        snprintf(out, n, "%s/../share/shadelab/xcheck/xcheck_blender.py", exe); /* installed */
        if (stat(out, &st) == 0) return true;
    }
    snprintf(out, n, "%s", SL_XCHECK_SOURCE_DIR "/xcheck_blender.py"); /* the build tree */
    return stat(out, &st) == 0;
}

static bool load_exr(const char *path, sl_image *img, int w, int h, char *err, size_t n) {
    if (!sl_image_load(img, path, err, n)) return false;
    if (img->width != w || img->height != h) {
        snprintf(err, n, "%s: %dx%d, expected %dx%d", path, img->width, img->height, w, h);
        sl_image_free(img);
        return false;
    }
    return true;
}

/* The app as the viewer would load the scene, with tonemap off (compared before tone mapping; a
 * note says the tone curve is not cross-checked). */
static bool open_app(const options *o, sl_app *app, char *err, size_t n) {
    sl_app_options opt = {0};
    opt.scene_path = o->scene;
    opt.data_dir = o->data;
    opt.backend = SL_BACKEND_OSMESA;
    opt.width = o->width;
    opt.height = o->height;
    opt.keep_color = true;
    opt.timings = true;
    opt.accumulate = 1;
    opt.fixed_dt = 1.0 / 60;
    opt.camera = o->camera;
    opt.strict = true; /* a plugin that fails to load would make both sides judge a different scene */
    for (int i = 0; i < o->plugin_count; i++) opt.plugins[opt.plugin_count++] = o->plugins[i];
    for (int i = 0; i < o->setting_count; i++) opt.settings[opt.setting_count++] = o->settings[i];
    memset(app, 0, sizeof *app);
    if (!sl_app_init(app, &opt, err, n)) return false;
    return sl_plugins_find(&app->plugins, "tonemap") < 0 || sl_app_set(app, "tonemap.enabled=false", SL_SRC_CLI, err, n);
}

/* The Cycles reference (rendered or cached) and its object-index pass, read into ref and index. */
static bool reference(const options *o, const char *out, const char *blender, uint64_t key, xc_export *ex,
                      sl_image *ref, sl_image *index, bool *cached, double *seconds, char *err, size_t n) {
    char path[4300];
    if (!cycles_reference(o, out, key, blender, ex->gltf, cached, seconds, err, n)) return false;
    snprintf(path, sizeof path, "%s/objects.json", out);
    if (ex->gltf && !xc_export_read_objects(ex, path, err, n)) return false;
    snprintf(path, sizeof path, "%s/cycles.exr", out);
    if (!load_exr(path, ref, o->width, o->height, err, n)) return false;
    snprintf(path, sizeof path, "%s/index.exr", out);
    return load_exr(path, index, o->width, o->height, err, n);
}

/* OUT/shadelab.exr, OUT/error.png and OUT/side_by_side.png. */
static bool write_images(const char *out, const float *test, const float *ref, int w, int h, char *err, size_t n) {
    size_t px = (size_t)w * h * 4;
    float *emap = malloc(px * sizeof *emap), *side = malloc(px * 3 * sizeof *side);
    char path[4300];
    bool ok = emap && side;
    if (!ok) snprintf(err, n, "out of memory");
    snprintf(path, sizeof path, "%s/shadelab.exr", out);
    ok = ok && sl_image_write(path, test, w, h, false, err, n);
    if (ok) xc_error_map(test, ref, w, h, emap);
    snprintf(path, sizeof path, "%s/error.png", out);
    ok = ok && sl_image_write(path, emap, w, h, true, err, n);
    if (ok) xc_side_by_side(test, ref, emap, w, h, side);
    snprintf(path, sizeof path, "%s/side_by_side.png", out);
    ok = ok && sl_image_write(path, side, w * 3, h, true, err, n);
    free(emap);
    free(side);
    return ok;
}

/* EEVEE at each --eevee sample count: images into eevee[], times into r. */
static bool render_eevee(const options *o, const char *out, const char *blender, sl_image *eevee, report_ctx *r,
                         char *err, size_t n) {
    char path[4300];
    for (int k = 0; k < o->eevee_count; k++) {
        if (!eevee_render(out, blender, o->eevee[k], &r->eevee_ms[k], err, n)) return false;
        snprintf(path, sizeof path, "%s/eevee-%d.exr", out, o->eevee[k]);
        if (!load_exr(path, &eevee[k], o->width, o->height, err, n)) return false;
        r->eevee[k] = eevee[k].pixels;
    }
    return true;
}

/* OUT/eevee.tsv: "samples<TAB>ms per render" a line, for --reference-only's readers (shadelab-bench). */
static bool write_eevee_times(const char *out, const options *o, const report_ctx *r, char *err, size_t n) {
    if (!o->eevee_count) return true;
    char path[4300];
    snprintf(path, sizeof path, "%s/eevee.tsv", out);
    FILE *f = fopen(path, "w");
    if (!f) { snprintf(err, n, "%s: cannot write: %s", path, strerror(errno)); return false; }
    for (int k = 0; k < o->eevee_count; k++) {
        fprintf(f, "%d\t%.3f\n", o->eevee[k], r->eevee_ms[k]);
        printf("EEVEE: %d samples, %.1f ms per render: %s/eevee-%d.exr\n", o->eevee[k], r->eevee_ms[k], out, o->eevee[k]);
    }
    if (fclose(f) != 0) { snprintf(err, n, "%s: cannot write", path); return false; }
    return true;
}

/* OUT/report.txt (printed too) and OUT/report.json; *worst as report() returns it. */
static bool write_report(const char *out, const report_ctx *r, double *worst, char *err, size_t n) {
    char txt_path[4300], json_path[4300];
    snprintf(txt_path, sizeof txt_path, "%s/report.txt", out);
    snprintf(json_path, sizeof json_path, "%s/report.json", out);
    FILE *txt = fopen(txt_path, "w"), *json = fopen(json_path, "w");
    if (!txt || !json) {
        snprintf(err, n, "%s: cannot write: %s", !txt ? txt_path : json_path, strerror(errno));
        if (txt) fclose(txt);
        if (json) fclose(json);
        return false;
    }
    *worst = report(r, txt, json);
    bool ok = fclose(json) == 0;
    ok &= fclose(txt) == 0;
    if (!ok) { snprintf(err, n, "%s: cannot write", out); return false; }
    FILE *again = fopen(txt_path, "r");
    char buf[4096];
    size_t k;
    while (again && (k = fread(buf, 1, sizeof buf, again)) > 0) fwrite(buf, 1, k, stdout);
    if (again) fclose(again);
    printf("\nimages: %s/side_by_side.png (shadelab | Cycles | error: red brighter, blue darker, full at 2x)\n", out);
    return true;
}

int main(int argc, char **argv) {
    options o;
    if (!parse(argc, argv, &o)) return 1;
    char out[4096], err[8192] = "", builder[4096], version[256] = "", blender_dir[4200];
    if (o.out) snprintf(out, sizeof out, "%s", o.out);
    else default_out(o.scene, out, sizeof out);
    const char *blender = blender_path(&o);
    if (o.export_only) snprintf(version, sizeof version, "(not run)");
    else if (!blender_version(blender, version, sizeof version)) {
        fprintf(stderr, "shadelab-xcheck: Blender is not installed or does not run (\"%s --version\" failed): "
                        "the cross-check needs it (Debian package blender; tools/install-deps.sh --with-tests)\n",
                blender);
        return XC_EXIT_NO_BLENDER;
    }
    if (!find_builder(builder, sizeof builder)) {
        fprintf(stderr, "shadelab-xcheck: %s: the Blender builder script is missing\n", builder);
        return 1;
    }
    sl_app app;
    xc_export ex = {0};
    sl_image ref = {0}, index = {0}, eevee[16];
    memset(eevee, 0, sizeof eevee);
    float *test = NULL, *scratch = NULL, *noise_var = NULL;
    bool ok = open_app(&o, &app, err, sizeof err);
    snprintf(blender_dir, sizeof blender_dir, "%s/blender", out);
    xc_export_options eo = {.width = o.width, .height = o.height, .samples = o.samples, .bounces = o.bounces,
                            .unoccluded = o.unoccluded, .builder = builder};
    ok = ok && xc_mkdirs(out, err, sizeof err) && xc_export_scene(&app, &eo, blender_dir, &ex, err, sizeof err);
    uint64_t key = sl_tool_hash64(version, strlen(version), ex.hash);
    report_ctx r = {.o = &o, .app = &app, .ex = &ex, .w = o.width, .h = o.height, .blender_version = version, .key = key,
                    .shadelab_ms = NAN};
    ok = ok && (o.export_only ||
                reference(&o, out, blender, key, &ex, &ref, &index, &r.cached, &r.cycles_seconds, err, sizeof err));
    double worst = 0;
    if (ok && o.export_only) {
        printf("shadelab-xcheck: the Blender scene is in %s\n", blender_dir);
        for (int i = 0; i < ex.note_count; i++) printf("%s\n", ex.notes[i]);
    } else if (ok && o.reference_only) {
        printf("shadelab-xcheck: Cycles reference %s/cycles.exr (%s%s)\n", out, r.cached ? "from the cache" : "rendered",
               o.unoccluded ? "; unoccluded: objects seen by camera rays only" : "");
        for (int i = 0; i < ex.note_count; i++) printf("%s\n", ex.notes[i]);
        ok = render_eevee(&o, out, blender, eevee, &r, err, sizeof err) && write_eevee_times(out, &o, &r, err, sizeof err);
    } else if (ok) {
        test = malloc((size_t)o.width * o.height * 4 * sizeof *test);
        if (!test) snprintf(err, sizeof err, "out of memory");
        r.test = test, r.ref = ref.pixels, r.index = index.pixels;
        ok = test && render_shadelab(&app, &o, test, &r.shadelab_ms, err, sizeof err) &&
             write_images(out, test, ref.pixels, o.width, o.height, err, sizeof err);
        if (ok && o.noise) {
            scratch = malloc((size_t)o.width * o.height * 4 * sizeof *scratch);
            noise_var = malloc((size_t)o.width * o.height * sizeof *noise_var);
            ok = scratch && noise_var;
            if (!ok) snprintf(err, sizeof err, "out of memory");
            ok = ok && render_noise(&app, &o, xc_display_scale(ref.pixels, o.width, o.height), scratch, noise_var, err,
                                    sizeof err);
            r.noise_var = noise_var;
        }
        ok = ok &&
             render_eevee(&o, out, blender, eevee, &r, err, sizeof err) && write_report(out, &r, &worst, err, sizeof err);
    }
    int rc = ok ? 0 : 1;
    if (!ok) fprintf(stderr, "shadelab-xcheck: %s\n", err);
    if (ok && o.max_rel_rms >= 0 && worst > o.max_rel_rms) {
        fprintf(stderr, "shadelab-xcheck: a cross-checked object's relative RMS %.4f exceeds --max-rel-rms %.4f\n", worst,
                o.max_rel_rms);
        rc = 1;
    }
    /* As shadelab's own headless run: a render that printed an error (a magenta stand-in for a
     * texture, a plugin switched off) wrote its report but is not a clean measurement. */
    int errors = sl_log_count(SL_LOG_ERROR);
    if (!rc && errors) {
        fprintf(stderr, "shadelab-xcheck: %d error%s above; exit status 2 (the report was written)\n", errors,
                errors > 1 ? "s" : "");
        rc = 2;
    }
    for (int k = 0; k < 16; k++) sl_image_free(&eevee[k]);
    free(test);
    free(scratch);
    free(noise_var);
    sl_image_free(&ref);
    sl_image_free(&index);
    xc_export_free(&ex);
    sl_app_shutdown(&app);
    return rc;
}
