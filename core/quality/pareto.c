/* Pareto front (see autoquality.h). n is a handful of settings, so the O(n^2) definition is used as
 * written rather than a sort-and-sweep: it is obviously right and handles ties and NaN. */
#include "autoquality.h"
#include <math.h>

static bool valid(double c, double e) { return !isnan(c) && !isnan(e); }

int sl_pareto_front(const double *cost, const double *error, int n, bool *on_front) {
    int count = 0;
    for (int i = 0; i < n; i++) {
        bool dominated = !valid(cost[i], error[i]);
        for (int j = 0; j < n && !dominated; j++) {
            if (j == i || !valid(cost[j], error[j])) continue;
            dominated = cost[j] <= cost[i] && error[j] <= error[i] && (cost[j] < cost[i] || error[j] < error[i]);
        }
        on_front[i] = !dominated;
        count += on_front[i];
    }
    return count;
}

int sl_pareto_cheapest_within(const double *cost, const double *error, int n, double budget) {
    int best = -1;
    for (int i = 0; i < n; i++) {
        if (!valid(cost[i], error[i]) || !(error[i] <= budget)) continue;
        if (best < 0 || cost[i] < cost[best] || (cost[i] == cost[best] && error[i] < error[best])) best = i;
    }
    return best;
}

int sl_pareto_most_accurate(const double *cost, const double *error, int n) {
    int best = -1;
    for (int i = 0; i < n; i++) {
        if (!valid(cost[i], error[i])) continue;
        if (best < 0 || error[i] < error[best] || (error[i] == error[best] && cost[i] < cost[best])) best = i;
    }
    return best;
}
