/* Minimal assertions for the C tests: each CHECK prints the failing expression with file:line
 * and the values; main returns check_result(). */
#ifndef SL_CHECK_H
#define SL_CHECK_H
#include <math.h>
#include <stdio.h>
#include <string.h>

static int check_failures_, check_count_;
#define CHECK(cond) do { check_count_++; if (!(cond)) { check_failures_++; \
    fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); } } while (0)
#define CHECK_MSG(cond, ...) do { check_count_++; if (!(cond)) { check_failures_++; \
    fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond); \
    fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); } } while (0)
#define CHECK_NEAR(a, b, tol) do { double a_ = (a), b_ = (b); check_count_++; \
    if (!(fabs(a_ - b_) <= (tol))) { check_failures_++; \
    fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, tolerance %.3g\n", \
            __FILE__, __LINE__, #a, a_, #b, b_, (double)(tol)); } } while (0)
#define CHECK_CONTAINS(hay, needle) do { const char *h_ = (hay); check_count_++; \
    if (!h_ || !strstr(h_, needle)) { check_failures_++; \
    fprintf(stderr, "%s:%d: expected \"%s\" in: %s\n", __FILE__, __LINE__, needle, h_ ? h_ : "(null)"); } } while (0)

static inline int check_result(void) {
    printf("%d checks, %d failed\n", check_count_, check_failures_);
    return check_failures_ ? 1 : 0;
}
#endif
