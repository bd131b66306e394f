/* Pareto front of (cost, error) points, both lower-is-better.
 *
 * Point i is dominated when some other point j has cost_j <= cost_i and error_j <= error_i
 * with at least one of the two strictly smaller. The front is every point that is not
 * dominated; exact duplicates of a front point are on the front too. Points with a NaN cost
 * or error are never on the front and never dominate. */
#ifndef SL_BENCH_PARETO_H
#define SL_BENCH_PARETO_H
#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Marks on_front[i]; returns how many points are on the front. */
int sl_pareto_front(const double *cost, const double *error, int n, bool *on_front);
/* The cheapest point whose error is <= budget (ties in cost: the lower error, then the lower
 * index), or -1 when none is. That point is always on the front. */
int sl_pareto_cheapest_within(const double *cost, const double *error, int n, double budget);
/* The point with the lowest error (ties: the cheaper one), or -1 when all are NaN. */
int sl_pareto_most_accurate(const double *cost, const double *error, int n);

#ifdef __cplusplus
}
#endif
#endif
