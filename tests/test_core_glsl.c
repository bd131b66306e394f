/* GLSL unit tests of the core's shader library, evaluated on the GPU path and compared with C. */
#include "check.h"
#include <shadelab/harness.h>
#include <stdlib.h>

#define N 32

int main(void) {
    char err[8192];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();
    static float in0[N * N * 4], in1[N * N * 4], out[N * N * 4];

    /* Lambert: f = k_d/π, L = f·E·max(0, n·l), for l sweeping the upper and lower hemisphere */
    for (int i = 0; i < N * N; i++) {
        float t = (float)M_PI * i / (N * N - 1); /* angle from the normal, 0..π */
        in0[i * 4 + 0] = sinf(t);
        in0[i * 4 + 1] = cosf(t);
        in0[i * 4 + 2] = 0;
        in1[i * 4 + 0] = 0.25f + (i % 7) * 0.1f; /* k_d */
        in1[i * 4 + 1] = 0.5f + (i % 5);         /* E */
    }
    const char *files[] = {"lambert.glsl", NULL};
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .files = files, .width = N, .height = N, .in0 = in0, .in1 = in1,
                           .expression = "vec4(sl_model_lambert(SlSurface(vec3(0), vec3(0,1,0), vec3(0,1,0), vec3(1,0,0), "
                                         "vec3(0,0,1), vec2(0), vec3(0,1,0), vec3(in1.x), 1.0, 1.0, 1.0, 1.0, 0.0, vec3(0), 0.0, vec2(0), vec3(1)), in0.xyz, vec3(in1.y)), 0.0)"};
    CHECK_MSG(sl_harness_eval_glsl(h, &d, out, err, sizeof err), "%s", err);
    double worst = 0;
    for (int i = 0; i < N * N; i++) {
        double cosv = in0[i * 4 + 1];
        double expect = in1[i * 4 + 0] / M_PI * in1[i * 4 + 1] * (cosv > 0 ? cosv : 0);
        double e = fabs(out[i * 4] - expect);
        if (e > worst) worst = e;
    }
    CHECK_MSG(worst < 1e-5, "lambert differs from k_d/pi E cos by %g", worst);

    /* sRGB encoding against the IEC 61966-2-1 piecewise definition */
    for (int i = 0; i < N * N; i++) in0[i * 4] = (float)i / (N * N - 1);
    const char *none[] = {NULL};
    d = (sl_glsl_eval_desc){.struct_size = sizeof d, .files = none, .width = N, .height = N, .in0 = in0,
                            .expression = "vec4(sl_srgb_encode(vec3(in0.x)), 0.0)"};
    CHECK_MSG(sl_harness_eval_glsl(h, &d, out, err, sizeof err), "%s", err);
    worst = 0;
    for (int i = 0; i < N * N; i++) {
        double x = in0[i * 4];
        double expect = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
        if (fabs(out[i * 4] - expect) > worst) worst = fabs(out[i * 4] - expect);
    }
    CHECK_MSG(worst < 1e-5, "srgb differs by %g", worst);

    /* point light: E = I/d², l towards the light */
    const char *lights[] = {"lights.glsl", NULL};
    for (int i = 0; i < N * N; i++) {
        in0[i * 4 + 0] = 0.1f * (i % 13);
        in0[i * 4 + 1] = 0.2f + 0.05f * (i % 17);
        in0[i * 4 + 2] = -0.3f;
    }
    const char *point_files[] = {SL_TEST_DATA_DIR "/glsl/eval_point_light.glsl", NULL};
    (void)lights;
    d = (sl_glsl_eval_desc){.struct_size = sizeof d, .files = point_files, .width = N, .height = N, .in0 = in0,
                            .expression = "test_point_light(in0.xyz)"};
    CHECK_MSG(sl_harness_eval_glsl(h, &d, out, err, sizeof err), "%s", err);
    worst = 0;
    for (int i = 0; i < N * N; i++) {
        double dx = 0.5 - in0[i * 4], dy = 1.5 - in0[i * 4 + 1], dz = -0.3 - in0[i * 4 + 2];
        double d2 = dx * dx + dy * dy + dz * dz;
        double rel = fabs(out[i * 4 + 3] - 10 / d2) / (10 / d2);
        if (rel > worst) worst = rel;
        CHECK_NEAR(out[i * 4 + 1], dy / sqrt(d2), 1e-5); /* l.y */
    }
    CHECK_MSG(worst < 1e-5, "point light E differs from I/d^2 by %g (relative)", worst);

    /* a compile error in the evaluated code is reported with the file and line */
    d = (sl_glsl_eval_desc){.struct_size = sizeof d, .files = none, .width = 4, .height = 4,
                            .expression = "vec4(no_such_function(1.0))"};
    CHECK(!sl_harness_eval_glsl(h, &d, out, err, sizeof err));
    CHECK_CONTAINS(err, "no_such_function");
    sl_harness_destroy(h);
    return check_result();
}
