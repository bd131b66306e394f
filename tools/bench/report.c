/* shadelab-bench outputs: CSV, JSON (also the input of --auto-quality) and the gnuplot chart. */
#include "bench.h"
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>


/* ---------------------------------------------------------------------- output -------- */

static void csv_string(FILE *f, const char *s) {
    fputc('"', f);
    for (; s && *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static void csv_number(FILE *f, double v) {
    if (isnan(v)) fputs(",", f);
    else if (isinf(v)) fprintf(f, ",%s", v > 0 ? "inf" : "-inf");
    else fprintf(f, ",%.6g", v);
}

static int union_passes(const sl_bench_result *res, const char **names, int max) {
    int count = 0;
    for (int i = 0; i < res->row_count; i++)
        for (int k = 0; k < res->rows[i].pass_count; k++) {
            bool seen = false;
            for (int j = 0; j < count; j++) seen |= !strcmp(names[j], res->rows[i].passes[k].name);
            if (!seen && count < max) names[count++] = res->rows[i].passes[k].name;
        }
    return count;
}

static double pass_median(const sl_bench_row *r, const char *name) {
    for (int k = 0; k < r->pass_count; k++)
        if (!strcmp(r->passes[k].name, name)) return r->passes[k].median_ms;
    return NAN;
}

bool sl_bench_write_csv(const sl_bench_result *res, const char *path, sl_metric primary, char *err, size_t n) {
    FILE *f = fopen(path, "w");
    if (!f) { snprintf(err, n, "cannot write %s: %s", path, strerror(errno)); return false; }
    const char *passes[64];
    int np = union_passes(res, passes, 64);
    fprintf(f, "settings,label,ok,frame_ms_median,frame_ms_mean,frame_ms_min,passes_ms,rmse,relmse,psnr,ssim,dssim,max_abs,"
               "flip,noise,noisy,nonfinite_pixels,pareto_%s", sl_metric_name(primary));
    for (int k = 0; k < np; k++) fprintf(f, ",ms_%s", passes[k]);
    fputc('\n', f);
    for (int i = 0; i < res->row_count; i++) {
        const sl_bench_row *r = &res->rows[i];
        csv_string(f, r->settings);
        fputc(',', f);
        csv_string(f, r->label);
        fprintf(f, ",%d", r->ok);
        csv_number(f, r->frame_ms_median);
        csv_number(f, r->frame_ms_mean);
        csv_number(f, r->frame_ms_min);
        csv_number(f, r->passes_ms);
        csv_number(f, r->ok ? r->error.rmse : NAN);
        csv_number(f, r->ok ? r->error.relmse : NAN);
        csv_number(f, r->ok ? r->error.psnr : NAN);
        csv_number(f, r->ok ? r->error.ssim : NAN);
        csv_number(f, r->ok ? 1 - r->error.ssim : NAN);
        csv_number(f, r->ok ? r->error.max_abs : NAN);
        csv_number(f, r->ok ? r->error.flip : NAN);
        csv_number(f, r->ok ? r->error.noise : NAN);
        fprintf(f, ",%d,%ld,%d", r->noisy, r->error.nonfinite, r->front[primary]);
        for (int k = 0; k < np; k++) csv_number(f, pass_median(r, passes[k]));
        fputc('\n', f);
    }
    bool ok = !ferror(f);
    ok = (fclose(f) == 0) && ok;
    if (!ok) snprintf(err, n, "cannot write %s", path);
    return ok;
}

static cJSON *num(double v) { return isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull(); }

bool sl_bench_write_json(const sl_bench_result *res, const char *path, sl_metric primary, char *err, size_t n) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "format", "shadelab-bench/1");
    cJSON_AddStringToObject(root, "created", res->created);
    cJSON_AddStringToObject(root, "shadelab_version", SL_VERSION);
    cJSON_AddStringToObject(root, "scene", res->scene);
    cJSON_AddStringToObject(root, "scene_hash", res->scene_hash);
    cJSON_AddStringToObject(root, "plugin", res->plugin);
    cJSON_AddStringToObject(root, "plugins_loaded", res->plugins_loaded ? res->plugins_loaded : "");
    cJSON_AddNumberToObject(root, "width", res->width);
    cJSON_AddNumberToObject(root, "height", res->height);
    cJSON_AddStringToObject(root, "backend", res->backend ? res->backend : "");
    cJSON_AddStringToObject(root, "renderer", res->renderer ? res->renderer : "");
    cJSON_AddBoolToObject(root, "gpu", res->gpu);
    cJSON_AddStringToObject(root, "timing", res->timing_mode ? res->timing_mode : "");
    cJSON_AddNumberToObject(root, "frames", res->frames);
    cJSON_AddNumberToObject(root, "warmup_frames", res->warmup);
    cJSON_AddNumberToObject(root, "rounds", res->rounds);
    cJSON_AddStringToObject(root, "cost", "frame_ms_median: median CPU wall time of a whole frame over the timed frames");
    cJSON_AddStringToObject(root, "primary_metric", sl_metric_name(primary));
    cJSON *md = cJSON_AddObjectToObject(root, "metrics");
    cJSON_AddStringToObject(md, "rmse", "sqrt(mean((a-b)^2)) over RGB, linear radiance");
    cJSON_AddStringToObject(md, "relmse", "mean((a-b)^2/(b^2+eps)) over RGB, linear radiance, b = reference");
    cJSON_AddNumberToObject(md, "relmse_epsilon", SL_RELMSE_EPSILON);
    cJSON_AddStringToObject(md, "psnr", "20 log10(1/rmse) dB, peak 1, linear radiance");
    cJSON_AddStringToObject(md, "ssim", "mean SSIM (Wang et al. 2004), 11x11 Gaussian sigma 1.5, K1 0.01, K2 0.03, L 1, valid "
                                        "windows only, on Y' = 0.2126R'+0.7152G'+0.0722B' of the sRGB-encoded image clamped to [0,1]");
    cJSON_AddStringToObject(md, "dssim", "1 - ssim");
    cJSON_AddStringToObject(md, "flip", "mean LDR-FLIP (Andersson et al. 2020) of the image clamped to [0,1], 67 pixels per degree");
    cJSON_AddStringToObject(md, "noise", "RMS over pixels and RGB of the per-pixel standard deviation of the sRGB-encoded value "
                                         "over the frames of a still (sample k of noise_samples, each rendered on its own)");
    cJSON_AddItemToObject(md, "noise_samples", num(res->noise_samples));
    cJSON_AddItemToObject(md, "noise_limit", num(res->noise_limit));
    cJSON_AddStringToObject(md, "noisy", "noise > noise_limit: on no Pareto front, never chosen by --auto-quality");
    cJSON *ref = cJSON_AddObjectToObject(root, "reference");
    cJSON_AddStringToObject(ref, "settings", res->reference.settings ? res->reference.settings : "");
    cJSON_AddNumberToObject(ref, "accumulate", res->reference.accumulate);
    cJSON_AddNumberToObject(ref, "scale", res->reference.scale);
    cJSON_AddStringToObject(ref, "description", res->reference.description ? res->reference.description : "");
    cJSON_AddStringToObject(ref, "cache_key", res->reference.key);
    cJSON_AddBoolToObject(ref, "from_cache", res->reference.from_cache);
    cJSON_AddItemToObject(ref, "render_s", num(res->reference.render_s));
    cJSON *rows = cJSON_AddArrayToObject(root, "settings");
    cJSON *front = cJSON_CreateArray();
    for (int i = 0; i < res->row_count; i++) {
        const sl_bench_row *r = &res->rows[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "settings", r->settings);
        cJSON_AddStringToObject(o, "label", r->label);
        cJSON_AddBoolToObject(o, "ok", r->ok);
        if (!r->ok) cJSON_AddStringToObject(o, "failure", r->failure ? r->failure : "");
        if (r->ok) {
            cJSON *fm = cJSON_AddObjectToObject(o, "frame_ms");
            cJSON_AddItemToObject(fm, "median", num(r->frame_ms_median));
            cJSON_AddItemToObject(fm, "mean", num(r->frame_ms_mean));
            cJSON_AddItemToObject(fm, "min", num(r->frame_ms_min));
            cJSON_AddItemToObject(o, "passes_ms", num(r->passes_ms));
            cJSON *ps = cJSON_AddArrayToObject(o, "passes");
            for (int k = 0; k < r->pass_count; k++) {
                cJSON *p = cJSON_CreateObject();
                cJSON_AddStringToObject(p, "name", r->passes[k].name);
                cJSON_AddStringToObject(p, "plugin", r->passes[k].owner);
                cJSON_AddItemToObject(p, "median_ms", num(r->passes[k].median_ms));
                cJSON_AddItemToObject(p, "mean_ms", num(r->passes[k].mean_ms));
                cJSON_AddItemToObject(p, "min_ms", num(r->passes[k].min_ms));
                cJSON_AddNumberToObject(p, "runs", r->passes[k].runs);
                cJSON_AddItemToArray(ps, p);
            }
            cJSON *e = cJSON_AddObjectToObject(o, "error");
            cJSON_AddItemToObject(e, "rmse", num(r->error.rmse));
            cJSON_AddItemToObject(e, "relmse", num(r->error.relmse));
            cJSON_AddItemToObject(e, "psnr", isinf(r->error.psnr) && r->error.psnr > 0 ? cJSON_CreateString("inf") : num(r->error.psnr));
            cJSON_AddItemToObject(e, "ssim", num(r->error.ssim));
            cJSON_AddItemToObject(e, "dssim", num(1 - r->error.ssim));
            cJSON_AddItemToObject(e, "max_abs", num(r->error.max_abs));
            cJSON_AddItemToObject(e, "flip", num(r->error.flip));
            cJSON_AddItemToObject(e, "noise", num(r->error.noise));
            cJSON_AddBoolToObject(e, "noisy", r->noisy);
            cJSON_AddNumberToObject(e, "nonfinite_pixels", r->error.nonfinite);
            cJSON *pf = cJSON_AddObjectToObject(o, "pareto");
            for (int m = 0; m < SL_METRIC_COUNT; m++) cJSON_AddBoolToObject(pf, sl_metric_name((sl_metric)m), r->front[m]);
        }
        cJSON_AddItemToArray(rows, o);
        if (r->front[primary]) cJSON_AddItemToArray(front, cJSON_CreateString(r->settings));
    }
    cJSON_AddItemToObject(root, "front", front);
    cJSON *peers = cJSON_AddArrayToObject(root, "peers"); /* other renderers, the same reference */
    for (int i = 0; i < res->peer_count; i++) {
        const sl_bench_peer *p = &res->peers[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "label", p->label);
        cJSON_AddItemToObject(o, "ms_per_render", num(p->ms));
        cJSON *e = cJSON_AddObjectToObject(o, "error");
        cJSON_AddItemToObject(e, "rmse", num(p->error.rmse));
        cJSON_AddItemToObject(e, "relmse", num(p->error.relmse));
        cJSON_AddItemToObject(e, "psnr", num(p->error.psnr));
        cJSON_AddItemToObject(e, "dssim", num(1 - p->error.ssim));
        cJSON_AddItemToObject(e, "flip", num(p->error.flip));
        cJSON_AddItemToArray(peers, o);
    }
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    FILE *f = fopen(path, "w");
    bool ok = f && text;
    if (f) {
        ok = fputs(text, f) >= 0 && fputc('\n', f) != EOF && ok;
        ok = (fclose(f) == 0) && ok;
    }
    if (!ok) snprintf(err, n, "cannot write %s: %s", path, strerror(errno));
    free(text);
    return ok;
}

/* gnuplot on PATH (or $SHADELAB_GNUPLOT)? */
static const char *find_gnuplot(char *buf, size_t n) {
    const char *env = getenv("SHADELAB_GNUPLOT");
    if (env && *env) return access(env, X_OK) ? NULL : env;
    const char *path = getenv("PATH");
    if (!path) path = "/usr/bin:/bin";
    char *copy = strdup(path), *save = NULL;
    const char *found = NULL;
    for (char *d = strtok_r(copy, ":", &save); d && !found; d = strtok_r(NULL, ":", &save)) {
        snprintf(buf, n, "%s/gnuplot", *d ? d : ".");
        if (!access(buf, X_OK)) found = buf;
    }
    free(copy);
    return found;
}

/* gnuplot double-quoted string: backslash, quote and newline escaped. */
static void gp_string(FILE *f, const char *s) {
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '\n') { fputs("\\n", f); continue; }
        if (*s == '"' || *s == '\\') fputc('\\', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

/* The chart's geometry, fixed so that where a label ends can be computed: 960×640 px, DejaVu Sans
 * 10 (labels measure ≈ 7 px a character, 7.5 assumed so estimates err towards "does not fit";
 * gnuplot's `char` unit is 8.3 px), the plot from 9.5 % to 97.4 % of the width, the x axis from
 * 0 to 12 % past the slowest setting (room for the key and the labels). */
enum { CHART_W = 960, CHART_H = 640 };
static const double chart_char_px = 7.5, chart_char_unit_px = 8.3;
static const double chart_plot_left = 0.095, chart_plot_right = 0.974, chart_x_room = 1.12;
#define CHART_TITLE_CHARS 118 /* a title line: the chart's width less a margin, in characters */

/* Copies s into out with line breaks (at spaces, else mid-word) so no line exceeds width
 * characters (UTF-8 sequences count as one); existing '\n' are kept. */
static void wrap_text(const char *s, char *out, size_t n, int width) {
    size_t o = 0, line_start = 0, last_space = (size_t)-1;
    int col = 0;
    for (; *s && o + 1 < n; s++) {
        out[o] = *s;
        if (*s == '\n') { col = 0, line_start = o + 1, last_space = (size_t)-1; o++; continue; }
        if ((*s & 0xc0) != 0x80) col++; /* not a UTF-8 continuation byte */
        if (*s == ' ') last_space = o;
        o++;
        if (col > width) {
            if (last_space != (size_t)-1 && last_space > line_start) {
                out[last_space] = '\n';
                line_start = last_space + 1;
            } else if (o + 1 < n) { /* one word longer than a line: break it before this character */
                memmove(out + o, out + o - 1, 1);
                out[o - 1] = '\n';
                line_start = o;
                o++;
            }
            last_space = (size_t)-1;
            col = 0;
            for (size_t k = line_start; k < o; k++) col += (out[k] & 0xc0) != 0x80;
        }
    }
    out[o] = 0;
}

/* Characters of a label (UTF-8 sequences count as one). */
static int text_chars(const char *s) {
    int c = 0;
    for (; *s; s++) c += (*s & 0xc0) != 0x80;
    return c;
}

/* 1 when a label written to the right of its point (offset 0.8 char) would pass the chart's right
 * edge: it is then written to the left of the point. The x axis runs from x_start to x_end
 * (x_start > 0: a log scale). */
static int label_goes_left(double x, double x_start, double x_end, const char *label) {
    double left = chart_plot_left * CHART_W, width = (chart_plot_right - chart_plot_left) * CHART_W;
    double at = x_start > 0 ? log(x / x_start) / log(x_end / x_start) : x_end > 0 ? x / x_end : 0;
    double x_px = left + at * width;
    return x_px + 0.8 * chart_char_unit_px + text_chars(label) * chart_char_px > CHART_W - 4;
}

/* The peers' points (ms, error, label, label left of its point) into path; how many, and in
 * *left how many of them have their label on the left. */
static int write_peers(const sl_bench_result *res, const char *path, sl_metric metric, double x_start, double x_end,
                       int *left) {
    FILE *f = res->peer_count ? fopen(path, "w") : NULL;
    int count = 0;
    *left = 0;
    for (int i = 0; f && i < res->peer_count; i++) {
        const sl_bench_peer *p = &res->peers[i];
        double y = metric == SL_METRIC_PSNR ? p->error.psnr : sl_metric_value(&p->error, metric);
        if (!isfinite(y) || !(p->ms > 0) || (metric != SL_METRIC_PSNR && y <= 0)) continue;
        int l = label_goes_left(p->ms, x_start, x_end, p->label);
        fprintf(f, "%.6g %.6g \"%s\" %d\n", p->ms, y, p->label, l);
        *left += l;
        count++;
    }
    if (f) fclose(f);
    return count;
}

static int cmp_cost(const void *a, const void *b) {
    const double *x = a, *y = b;
    return x[0] < y[0] ? -1 : x[0] > y[0] ? 1 : (x[1] > y[1]) - (x[1] < y[1]);
}

int sl_bench_write_chart(const sl_bench_result *res, const char *png, sl_metric metric, char *err, size_t n) {
    char gpbuf[4096];
    const char *gp = find_gnuplot(gpbuf, sizeof gpbuf);
    if (!gp) {
        snprintf(err, n, "gnuplot not found on PATH: chart %s skipped (install gnuplot-nox, e.g. tools/install-deps.sh; "
                 "the CSV and JSON are written)", png);
        return 0;
    }
    bool psnr = metric == SL_METRIC_PSNR;
    /* Zero errors cannot sit on a log axis and PSNR = inf on no axis: such settings (identical
     * to the reference) are drawn at the bottom (top for PSNR) with their own marker. */
    double minpos = INFINITY, peak = -INFINITY, xmax = 0;
    for (int i = 0; i < res->row_count; i++) {
        const sl_bench_row *r = &res->rows[i];
        if (!r->ok) continue;
        double y = psnr ? r->error.psnr : sl_metric_value(&r->error, metric);
        if (!isnan(y) && r->frame_ms_median > xmax) xmax = r->frame_ms_median;
        if (!psnr && y > 0 && y < minpos) minpos = y;
        if (psnr && isfinite(y) && y > peak) peak = y;
    }
    /* other renderers (EEVEE) take seconds where shadelab takes milliseconds: with them the x axis
     * is logarithmic, from below the fastest point to past the slowest */
    double xmin = INFINITY;
    for (int i = 0; i < res->row_count; i++)
        if (res->rows[i].ok && res->rows[i].frame_ms_median > 0 && res->rows[i].frame_ms_median < xmin)
            xmin = res->rows[i].frame_ms_median;
    for (int i = 0; i < res->peer_count; i++) {
        double y = psnr ? res->peers[i].error.psnr : sl_metric_value(&res->peers[i].error, metric);
        if (isnan(y) || !(res->peers[i].ms > 0)) continue;
        if (res->peers[i].ms > xmax) xmax = res->peers[i].ms;
        if (res->peers[i].ms < xmin) xmin = res->peers[i].ms;
        if (!psnr && y > 0 && y < minpos) minpos = y;
        if (psnr && isfinite(y) && y > peak) peak = y;
    }
    bool log_x = res->peer_count > 0 && isfinite(xmin) && xmax > 0 && isfinite(xmax);
    double x_start = log_x ? xmin / 1.5 : 0;
    double x_end = log_x ? xmax * 4 : xmax > 0 && isfinite(xmax) ? xmax * chart_x_room : 0; /* 0: gnuplot's autoscale */
    double special_y = psnr ? (isfinite(peak) ? peak + 6 : 60) : (isfinite(minpos) ? minpos / 4 : 1e-6);
    char dir[] = "/tmp/shadelab-chart-XXXXXX";
    if (!mkdtemp(dir)) { snprintf(err, n, "mkdtemp: %s", strerror(errno)); return -1; }
    char pts[4200], frt[4200], zero[4200], script[4200], peer[4200];
    snprintf(peer, sizeof peer, "%s/peers.dat", dir);
    int peer_left, npeer = write_peers(res, peer, metric, x_start, x_end, &peer_left);
    snprintf(pts, sizeof pts, "%s/points.dat", dir);
    snprintf(frt, sizeof frt, "%s/front.dat", dir);
    snprintf(zero, sizeof zero, "%s/zero.dat", dir);
    snprintf(script, sizeof script, "%s/chart.gp", dir);
    FILE *fp = fopen(pts, "w"), *ff = fopen(frt, "w"), *fz = fopen(zero, "w");
    double (*front)[2] = calloc(res->row_count + 1, sizeof *front);
    int nf = 0, nz = 0, npts = 0, ndom = 0, nnoisy = 0, left[2] = {0, 0}; /* labels left of their point: [points, zero] */
    for (int i = 0; i < res->row_count && fp && ff && fz; i++) {
        const sl_bench_row *r = &res->rows[i];
        if (!r->ok) continue;
        double y = psnr ? r->error.psnr : sl_metric_value(&r->error, metric);
        if (isnan(y)) continue;
        /* every point says how noisy its frames are (metrics.h); deterministic ones say nothing */
        char label[600];
        if (r->error.noise > 0) snprintf(label, sizeof label, "%s (noise %.2g)", r->label, r->error.noise);
        else snprintf(label, sizeof label, "%s", r->label);
        int l = label_goes_left(r->frame_ms_median, x_start, x_end, label);
        if (psnr ? isinf(y) : y <= 0) {
            y = special_y;
            fprintf(fz, "%.6g %.6g \"%s\" %d\n", r->frame_ms_median, y, label, l);
            nz++;
            left[1] += l;
        } else {
            fprintf(fp, "%.6g %.6g \"%s\" %d %d %d\n", r->frame_ms_median, y, label, r->front[metric] ? 1 : 0, l, r->noisy);
            npts++;
            left[0] += l;
            ndom += !r->front[metric] && !r->noisy;
            nnoisy += r->noisy;
        }
        if (r->front[metric]) { front[nf][0] = r->frame_ms_median; front[nf][1] = y; nf++; }
    }
    qsort(front, nf, sizeof *front, cmp_cost);
    for (int i = 0; ff && i < nf; i++) fprintf(ff, "%.6g %.6g\n", front[i][0], front[i][1]);
    free(front);
    if (fp) fclose(fp);
    if (ff) fclose(ff);
    if (fz) fclose(fz);
    FILE *g = fopen(script, "w");
    if (!g) { snprintf(err, n, "cannot write %s", script); return -1; }
    const char *metric_title = metric == SL_METRIC_RMSE     ? "RMSE vs reference (linear radiance, log scale)"
                               : metric == SL_METRIC_RELMSE ? "relative MSE vs reference (eps 0.01, log scale)"
                               : metric == SL_METRIC_DSSIM  ? "1 - SSIM vs reference (display luma, log scale)"
                               : metric == SL_METRIC_FLIP   ? "mean FLIP vs reference (perceptual, 67 px/degree, log scale)"
                               : metric == SL_METRIC_NOISE  ? "noise: std. dev. of a still's frames (sRGB, RMS, log scale)"
                                                            : "PSNR vs reference (dB, peak 1, linear radiance; higher is better)";
    char title[2048], wrapped[2100];
    snprintf(title, sizeof title, "%s quality knobs on %s, %dx%d\n%s (%s), %s timing\nreference: %s%s",
             res->plugin, res->scene, res->width, res->height, res->backend, res->renderer ? res->renderer : "?",
             res->timing_mode ? res->timing_mode : "?", res->reference.settings,
             res->reference.accumulate > 1 ? " (accumulated)" : "");
    if (res->reference.scale > 1) {
        size_t u = strlen(title);
        snprintf(title + u, sizeof title - u, " at %dx the size, box-filtered", res->reference.scale);
    }
    if (res->noise_samples > 1) {
        size_t u = strlen(title);
        snprintf(title + u, sizeof title - u, "\nnoise: spread of a %d-frame still's frames; above %.3g a setting is noisy "
                 "and on no front", res->noise_samples, res->noise_limit);
    }
    /* long titles (reference settings, file names) wrap instead of running off both edges */
    wrap_text(title, wrapped, sizeof wrapped, CHART_TITLE_CHARS);
    fprintf(g, "set terminal pngcairo size %d,%d font 'DejaVu Sans,10' noenhanced\n", CHART_W, CHART_H);
    fprintf(g, "set output ");
    gp_string(g, png);
    fprintf(g, "\nset lmargin at screen %g\nset rmargin at screen %g\nset title ", chart_plot_left, chart_plot_right);
    gp_string(g, wrapped);
    fprintf(g, "\nset xlabel ");
    char xl[256];
    if (res->rounds > 1)
        snprintf(xl, sizeof xl, "median frame time (ms, %d frames in %d rounds, %d warm-up each)", res->frames, res->rounds, res->warmup);
    else
        snprintf(xl, sizeof xl, "median frame time (ms, %d frames after %d warm-up)", res->frames, res->warmup);
    if (log_x) {
        size_t u = strlen(xl);
        snprintf(xl + u, sizeof xl - u, "; EEVEE: one render of N samples per pixel; log scale");
    }
    gp_string(g, xl);
    fprintf(g, "\nset ylabel ");
    gp_string(g, metric_title);
    /* the key below the plot: inside it, any corner can cover a point */
    fprintf(g, "\nset grid\nset key below box\n");
    if (log_x) fprintf(g, "set logscale x\nset format x '%%g'\nset xrange [%.9g:%.9g]\n", x_start, x_end);
    else if (x_end > 0) fprintf(g, "set xrange [0:%.9g]\n", x_end);
    else fprintf(g, "set xrange [0:*]\nset offsets 0, graph %g, 0, 0\n", chart_x_room - 1);
    if (!psnr) fprintf(g, "set logscale y\nset format y '%%g'\n");
    fprintf(g, "plot ");
    bool first = true;
    if (npts) {
        if (ndom) /* settings off the front: another setting is both cheaper and more accurate */
            fprintf(g, "'%s' using 1:($4 == 0 && $6 == 0 ? $2 : 1/0) with points pt 7 ps 1.3 lc rgb '#1f77b4' "
                       "title 'dominated setting', \\\n     ", pts);
        if (nnoisy) /* visible noise: whatever its mean error, never the choice */
            fprintf(g, "'%s' using 1:($6 != 0 ? $2 : 1/0) with points pt 2 ps 1.8 lw 2 lc rgb '#ff7f0e' "
                       "title 'noisy setting (its frames scatter visibly)', \\\n     ", pts);
        /* labels right of their point, or left of it where they would pass the right edge (a
         * plot whose points are all undefined is left out: gnuplot 5.4 crashes on it) */
        if (left[0] < npts)
            fprintf(g, "'%s' using 1:($5 == 0 ? $2 : 1/0):3 with labels offset char 0.8,0.7 left tc rgb '#333333' notitle%s",
                    pts, left[0] ? ", \\\n     " : "");
        if (left[0])
            fprintf(g, "'%s' using 1:($5 != 0 ? $2 : 1/0):3 with labels offset char -0.8,0.7 right tc rgb '#333333' notitle", pts);
        first = false;
    }
    if (nz) {
        fprintf(g, "%s'%s' using 1:2 with points pt 6 ps 1.8 lc rgb '#2ca02c' title '%s'", first ? "" : ", \\\n     ",
                zero, psnr ? "identical to the reference (PSNR = inf), drawn at the top"
                           : "error 0 (identical to the reference), drawn at the axis floor");
        if (left[1] < nz)
            fprintf(g, ", \\\n     '%s' using 1:($4 == 0 ? $2 : 1/0):3 with labels offset char 0.8,-0.7 left tc rgb '#333333' notitle",
                    zero);
        if (left[1])
            fprintf(g, ", \\\n     '%s' using 1:($4 != 0 ? $2 : 1/0):3 with labels offset char -0.8,-0.7 right tc rgb '#333333' notitle",
                    zero);
        first = false;
    }
    if (nf) {
        fprintf(g, "%s'%s' using 1:2 with linespoints lw 2 pt 7 ps 0.8 lc rgb '#d62728' title 'Pareto front (settings no other beats on both time and error)'",
                first ? "" : ", \\\n     ", frt);
        first = false;
    }
    if (npeer) { /* EEVEE: a peer renderer, its time per render; labels as the settings' are */
        fprintf(g, "%s'%s' using 1:2 with points pt 5 ps 1.6 lc rgb '#000000' title 'EEVEE (Blender, real time): ms per render'",
                first ? "" : ", \\\n     ", peer);
        if (peer_left < npeer)
            fprintf(g, ", \\\n     '%s' using 1:($4 == 0 ? $2 : 1/0):3 with labels offset char 0.8,-0.7 left tc rgb '#000000' notitle",
                    peer);
        if (peer_left)
            fprintf(g, ", \\\n     '%s' using 1:($4 != 0 ? $2 : 1/0):3 with labels offset char -0.8,-0.7 right tc rgb '#000000' notitle",
                    peer);
    }
    fprintf(g, "\n");
    fclose(g);
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "'%s' '%s' 2>'%s/gnuplot.err'", gp, script, dir);
    int rc = system(cmd);
    int result = 1;
    if (rc != 0) {
        char ep[4300];
        snprintf(ep, sizeof ep, "%s/gnuplot.err", dir);
        char *msg = sl_read_file(ep, NULL, NULL, 0);
        snprintf(err, n, "gnuplot failed on %s: %s", png, msg && *msg ? msg : "(no message)");
        free(msg);
        result = -1;
    }
    /* clean the temporary directory */
    const char *files[] = {"points.dat", "front.dat", "zero.dat", "peers.dat", "chart.gp", "gnuplot.err"};
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        char p[4300];
        snprintf(p, sizeof p, "%s/%s", dir, files[i]);
        unlink(p);
    }
    rmdir(dir);
    return result;
}
