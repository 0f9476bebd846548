/* Random tiny instances for the MILP tests, filled directly (no cost tables). */
#ifndef HV_TEST_RANDOM_INSTANCE_H
#define HV_TEST_RANDOM_INSTANCE_H

#include <stddef.h>
#include <stdint.h>

#include "hv/plan_instance.h"

/* splitmix64: the next number of the sequence whose state is *s. */
uint64_t hv_test_rng_next(uint64_t *s);

/* n_fruits fruits over n_stops stops (0.01 m apart; tau 5 s, T_travel 20 s); fruit f
 * reaches each stop of a window of `window` stops around a random centre with probability
 * 3/4 (at least one); costs of cost_lo_ms + [0, cost_span_ms) in whole ms. `unreachable`
 * fruits at the end get no pair. Free with hv_instance_free. */
void hv_test_random_instance(hv_instance_t *in, size_t nf, size_t ns, size_t window,
                             size_t unreachable, uint64_t seed, uint64_t cost_lo_ms,
                             uint64_t cost_span_ms);

/* The value (ms) of a choice per fruit, stop[f] one of its stops or HV_NO_STOP (left out
 * at skip_ms[f], or unreachable): T_travel + per used stop tau + its slower arm's time +
 * the skip costs (INFINITY for a reachable fruit left out when skip_ms is NULL). */
double hv_test_value_ms(const hv_instance_t *in, const uint32_t *stop, const double *skip_ms);

/* The optimum (ms) by enumeration: every reachable fruit at each of its stops, and left out
 * too where skip_ms (may be NULL: none) is finite; best_stop (may be NULL) receives the
 * first optimal choice. */
double hv_test_brute_force_ms(const hv_instance_t *in, const double *skip_ms, uint32_t *best_stop);

#endif /* HV_TEST_RANDOM_INSTANCE_H */
