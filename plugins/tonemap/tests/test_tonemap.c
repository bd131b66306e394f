/* tonemap: the operators' identities evaluated from the plugin's own GLSL (tonemap_ops.glsl)
 * against C, and the post pass end to end. */
#include "check.h"
#include "image/image.h"
#include <shadelab/harness.h>
#include <stdlib.h>
#include <string.h>

enum { N = 1024, OPS = 6 };
static float in[N * 4], out[N * 4];
static sl_harness *h;

static bool eval(const char *expr) {
    char err[8192];
    const char *files[] = {"tonemap_ops.glsl", NULL};
    sl_glsl_eval_desc e = {.struct_size = sizeof e, .plugin = "tonemap", .files = files, .expression = expr,
                           .width = N, .height = 1, .in0 = in};
    bool ok = sl_harness_eval_glsl(h, &e, out, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    return ok;
}

static double hue(const float *c) { /* angle in the chroma plane (Hexcone-free, atan2 form) */
    double a = c[0] - 0.5 * (c[1] + c[2]), b = 0.8660254 * (c[1] - c[2]);
    return atan2(b, a);
}

static void test_identities(void) {
    char expr[256];
    /* linear at exposure 0: the identity on [0,1], bit for bit */
    for (int i = 0; i < N; i++) in[i * 4] = i / (N - 1.0f), in[i * 4 + 1] = 0.5f * in[i * 4], in[i * 4 + 2] = 1 - in[i * 4];
    eval("vec4(tonemap_apply(in0.rgb, 0, 0.0, 4.0), 0.0)");
    int diff = 0;
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++) diff += out[i * 4 + c] != in[i * 4 + c];
    CHECK_MSG(diff == 0, "linear is not the identity on [0,1] (%d values differ)", diff);
    /* +1 EV doubles radiance (linear), and every operator sees exposure before its curve */
    for (int i = 0; i < N; i++) in[i * 4] = 100.0f * i / N, in[i * 4 + 1] = 0.3f * in[i * 4], in[i * 4 + 2] = 0.01f * i;
    eval("vec4(tonemap_apply(in0.rgb, 0, 1.0, 4.0), 0.0)");
    diff = 0;
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++) diff += out[i * 4 + c] != 2 * in[i * 4 + c];
    CHECK_MSG(diff == 0, "+1 exposure does not double radiance (%d values)", diff);
    for (int op = 1; op < OPS; op++) {
        static float a[N * 4];
        snprintf(expr, sizeof expr, "vec4(tonemap_apply(in0.rgb, %d, 1.0, 4.0), 0.0)", op);
        eval(expr);
        memcpy(a, out, sizeof a);
        snprintf(expr, sizeof expr, "vec4(tonemap_apply(2.0 * in0.rgb, %d, 0.0, 4.0), 0.0)", op);
        eval(expr);
        double worst = 0;
        for (int i = 0; i < N * 4; i++) worst = fmax(worst, fabs(a[i] - out[i]));
        CHECK_MSG(worst < 1e-6, "operator %d: exposure is not applied before the curve (%g)", op, worst);
    }
    /* Reinhard x/(1+x); extended: white maps to 1 */
    for (int i = 0; i < N; i++) in[i * 4] = in[i * 4 + 1] = in[i * 4 + 2] = powf(2, -12 + 24.0f * i / N);
    eval("vec4(tonemap_apply(in0.rgb, 1, 0.0, 4.0), 0.0)");
    double worst = 0;
    for (int i = 0; i < N; i++) worst = fmax(worst, fabs(out[i * 4] - in[i * 4] / (1 + in[i * 4])) / (in[i * 4] / (1 + in[i * 4])));
    CHECK_MSG(worst < 1e-6, "Reinhard differs from x/(1+x) by %g (relative)", worst);
    eval("vec4(tonemap_reinhard_extended(vec3(4.0), 4.0), tonemap_reinhard_extended(vec3(in0.x), 2.5).x)");
    CHECK_NEAR(out[0], 1.0, 1e-6);
    worst = 0;
    for (int i = 0; i < N; i++) {
        double x = in[i * 4];
        worst = fmax(worst, fabs(out[i * 4 + 3] - x * (1 + x / 6.25) / (1 + x)) / (x * (1 + x / 6.25) / (1 + x)));
    }
    CHECK_MSG(worst < 1e-6, "extended Reinhard differs by %g", worst);
}

static void test_monotonic(void) {
    char expr[256];
    for (int i = 0; i < N; i++) in[i * 4] = in[i * 4 + 1] = in[i * 4 + 2] = powf(2, -14 + 30.0f * i / (N - 1));
    for (int op = 0; op < OPS; op++) {
        snprintf(expr, sizeof expr, "vec4(tonemap_apply(in0.rgb, %d, 0.0, 4.0), 0.0)", op);
        eval(expr);
        int bad = 0;
        for (int i = 0; i + 1 < N; i++)
            for (int c = 0; c < 3; c++) bad += out[(i + 1) * 4 + c] < out[i * 4 + c] - 1e-7f;
        CHECK_MSG(bad == 0, "operator %d is not monotonic along grey (%d decreasing steps)", op, bad);
        CHECK_MSG(out[(N - 1) * 4] > out[0] + 0.5f, "operator %d is flat", op);
        /* luminance along a saturated colour ramp. AgX's path to white dips it by ~2e-5 per step
         * (3e-4 in all) once the dominant channel passes max_ev (k ≈ 100 here): a property of
         * the published fit, allowed for with a 1e-4 per-step tolerance and reported */
        for (int i = 0; i < N; i++) {
            float k = powf(2, -14 + 30.0f * i / (N - 1));
            in[i * 4] = k, in[i * 4 + 1] = 0.35f * k, in[i * 4 + 2] = 0.05f * k;
        }
        eval(expr);
        bad = 0;
        double dip = 0;
        for (int i = 0; i + 1 < N; i++) {
            double y0 = 0.2126 * out[i * 4] + 0.7152 * out[i * 4 + 1] + 0.0722 * out[i * 4 + 2];
            double y1 = 0.2126 * out[(i + 1) * 4] + 0.7152 * out[(i + 1) * 4 + 1] + 0.0722 * out[(i + 1) * 4 + 2];
            bad += y1 < y0 - 1e-4;
            dip = fmax(dip, y0 - y1);
        }
        printf("operator %d: monotonic along grey; largest luminance decrease along an orange ramp %.1e\n", op, dip);
        CHECK_MSG(bad == 0, "operator %d: luminance not monotonic along an orange ramp (%d steps)", op, bad);
        for (int i = 0; i < N; i++) in[i * 4] = in[i * 4 + 1] = in[i * 4 + 2] = powf(2, -14 + 30.0f * i / (N - 1));
    }
}

static void test_pbr_neutral(void) {
    /* below the start of compression: the input, less the toe offset (equal in all channels) */
    srand(7);
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++) in[i * 4 + c] = 0.75f * rand() / (float)RAND_MAX;
    eval("vec4(tonemap_pbr_neutral(in0.rgb), 0.0)");
    double worst = 0, worst_hue = 0;
    int tested = 0;
    for (int i = 0; i < N; i++) {
        const float *c = in + i * 4;
        double x = fmin(c[0], fmin(c[1], c[2])), off = x < 0.08 ? x - 6.25 * x * x : 0.04;
        double peak = fmax(c[0], fmax(c[1], c[2])) - off;
        if (peak >= 0.76) continue;
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(out[i * 4 + k] - (c[k] - off)));
        tested++;
    }
    printf("PBR Neutral below its start of compression: %d colours, max |out - (in - offset)| %.2e\n", tested, worst);
    CHECK(tested > 500);
    CHECK_MSG(worst < 1e-6, "PBR Neutral is not the identity below the start (%g)", worst);
    /* hue kept everywhere, the compressed range included */
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++) in[i * 4 + c] = 0.1f + 20.0f * rand() / (float)RAND_MAX;
    eval("vec4(tonemap_pbr_neutral(in0.rgb), 0.0)");
    tested = 0;
    for (int i = 0; i < N; i++) {
        const float *c = in + i * 4, *o = out + i * 4;
        double chroma = fmax(c[0], fmax(c[1], c[2])) - fmin(c[0], fmin(c[1], c[2]));
        double ochroma = fmax(o[0], fmax(o[1], o[2])) - fmin(o[0], fmin(o[1], o[2]));
        if (chroma < 0.5 || ochroma < 1e-3) continue;
        double d = fabs(hue(c) - hue(o));
        if (d > M_PI) d = 2 * M_PI - d;
        worst_hue = fmax(worst_hue, d);
        tested++;
    }
    printf("PBR Neutral hue: %d colours up to 20, max hue change %.2e rad\n", tested, worst_hue);
    CHECK(tested > 500);
    CHECK_MSG(worst_hue < 2e-3, "PBR Neutral changes hue by %g rad", worst_hue);
}

static void test_finite(void) {
    const float bad[8] = {NAN, INFINITY, -INFINITY, -1, 1e30f, 0, 65504, 1e-30f};
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++) in[i * 4 + c] = bad[(i + c * 3) % 8];
    char expr[256];
    for (int op = 0; op < OPS + 2 + 2 * OPS; op++) { /* each operator at +3 EV, then at -16 and +16 EV */
        if (op >= OPS + 2) snprintf(expr, sizeof expr, "vec4(tonemap_apply(in0.rgb, %d, %s, 4.0), 0.0)", (op - OPS - 2) % OPS,
                                    op - OPS - 2 < OPS ? "-16.0" : "16.0");
        else if (op < OPS) snprintf(expr, sizeof expr, "vec4(tonemap_apply(in0.rgb, %d, 3.0, 4.0), 0.0)", op);
        else if (op == OPS) snprintf(expr, sizeof expr, "vec4(tonemap_false_color(in0.rgb, 0.0), 0.0)");
        else snprintf(expr, sizeof expr, "vec4(tonemap_dither(tonemap_apply(in0.rgb, 5, 0.0, 4.0), vec2(0.3, 0.9)), 0.0)");
        eval(expr);
        long nonfinite = 0, negative = 0;
        for (int i = 0; i < N * 4; i++) nonfinite += !isfinite(out[i]), negative += out[i] < 0;
        CHECK_MSG(nonfinite == 0 && negative == 0, "case %d: %ld non-finite, %ld negative outputs from NaN/Inf input", op,
                  nonfinite, negative);
    }
}

static void test_srgb(void) {
    for (int i = 0; i < N; i++) in[i * 4] = i / (N - 1.0f), in[i * 4 + 1] = 0.0031308f * i / N;
    eval("vec4(sl_srgb_encode(in0.xxx).x, sl_srgb_encode(in0.yyy).x, 0.0, 0.0)");
    double worst = 0;
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 2; c++) {
            double x = in[i * 4 + c], want = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
            worst = fmax(worst, fabs(out[i * 4 + c] - want));
        }
    printf("display sRGB encoding vs IEC 61966-2-1: max |diff| %.2e\n", worst);
    CHECK_MSG(worst < 1e-5, "sRGB encoding differs by %g", worst);
}

/* The post pass end to end: a constant environment fills the frame with radiance x. */
static void test_pass(void) {
    const double x = 0.7;
    char json[512], err[1024];
    snprintf(json, sizeof json, "{\"plugins\": [\"tonemap\"], \"environment\": {\"color\": [%g, %g, %g]}}", x, x / 2, x * 4);
    const char *reinhard[] = {"tonemap.operator=reinhard", "tonemap.dither=false", NULL};
    sl_harness *p = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 16, .height = 16,
                                                          .scene_json = json, .settings = reinhard, .float32 = true,
                                                          .strict = true}, err, sizeof err);
    CHECK_MSG(p != NULL, "%s", err);
    if (!p) return;
    static float im[16 * 16 * 4], disp[16 * 16 * 4];
    const double rad[3] = {x, x / 2, x * 4};
    for (int e = 0; e < 2; e++) {
        if (e) CHECK(sl_harness_set(p, "tonemap.exposure=1", err, sizeof err));
        CHECK(sl_harness_render(p, im) && sl_harness_read_display(p, disp));
        double worst = 0, worst_disp = 0;
        for (int i = 0; i < 16 * 16; i++)
            for (int c = 0; c < 3; c++) {
                double r = rad[c] * (e ? 2 : 1), want = r / (1 + r);
                worst = fmax(worst, fabs(im[i * 4 + c] - want));
                worst_disp = fmax(worst_disp, fabs(disp[i * 4 + c] - sl_srgb_encode((float)want)));
            }
        printf("post pass, reinhard, exposure %d: max |color - x/(1+x)| %.2e, display vs sRGB(x/(1+x)) %.4f\n", e, worst,
               worst_disp);
        CHECK_MSG(worst < 1e-3, "%g", worst);
        CHECK_MSG(worst_disp <= 0.5 / 255 + 1e-4, "display %g", worst_disp);
    }
    sl_harness_structure st;
    sl_harness_structure_of(p, &st);
    bool ran = false; /* run as a pass, or fused into the pass before it (ext/post.h) */
    for (int i = 0; i < st.effect_count; i++) ran |= !strcmp(st.in_effect[i], "tonemap");
    CHECK(ran);
    /* linear, exposure 0, no dither: the identity, so the pass does not run at all */
    CHECK(sl_harness_set(p, "tonemap.operator=linear", err, sizeof err) && sl_harness_set(p, "tonemap.exposure=0", err, sizeof err));
    CHECK(sl_harness_render(p, im));
    sl_harness_structure_of(p, &st);
    ran = false;
    for (int i = 0; i < st.effect_count; i++) ran |= !strcmp(st.in_effect[i], "tonemap");
    CHECK_MSG(!ran, "the identity setting still runs the pass");
    CHECK_NEAR(im[0], x, 1e-3);
    /* dithering: values vary, the mean stays (within a code value) */
    CHECK(sl_harness_set(p, "tonemap.dither=true", err, sizeof err));
    CHECK(sl_harness_render(p, im) && sl_harness_read_display(p, disp));
    double mean = 0;
    int distinct = 0;
    for (int i = 0; i < 16 * 16; i++) mean += disp[i * 4 + 1], distinct += disp[i * 4 + 1] != disp[1];
    mean /= 16 * 16;
    printf("dither: display mean %.5f vs %.5f undithered, %d of 256 pixels differ from the first\n", mean,
           sl_srgb_encode((float)(x / 2)), distinct);
    CHECK(fabs(mean - sl_srgb_encode((float)(x / 2))) < 1.0 / 255);
    CHECK(distinct > 20);
    /* false colour: middle grey is green, 6 stops over is red */
    CHECK(sl_harness_set(p, "tonemap.false_color=true", err, sizeof err));
    CHECK(sl_harness_set(p, "tonemap.dither=false", err, sizeof err));
    double y = 0.2126 * rad[0] + 0.7152 * rad[1] + 0.0722 * rad[2], ev = log2(0.18 / y); /* Y × 2^E = 0.18 */
    char set[64];
    snprintf(set, sizeof set, "tonemap.exposure=%.4f", ev);
    CHECK(sl_harness_set(p, set, err, sizeof err));
    CHECK(sl_harness_render(p, im));
    CHECK_MSG(im[1] > 0.5 && im[0] < 0.1, "middle grey should be green: %g %g %g", im[0], im[1], im[2]);
    snprintf(set, sizeof set, "tonemap.exposure=%.4f", ev + 6);
    CHECK(sl_harness_set(p, set, err, sizeof err));
    CHECK(sl_harness_render(p, im));
    CHECK_MSG(im[0] > 0.9 && im[1] < 0.1, "6 stops over should be red: %g %g %g", im[0], im[1], im[2]);
    sl_harness_destroy(p);
}

int main(void) {
    char err[4096];
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8, .scene_json = "{}",
                                             .plugins = (const char *[]){"tonemap", NULL}, .strict = true}, err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();
    test_identities();
    test_monotonic();
    test_pbr_neutral();
    test_finite();
    test_srgb();
    sl_harness_destroy(h);
    test_pass();
    return check_result();
}
