/* Regional bounds of the branch-and-price (internal; planner/SOLVER.md).
 *
 * At fruit duals pi the branch-and-price's Lagrangian bound is a constant plus the sum over
 * stops of v_p <= 0, stop p's least reduced cost of a pattern (milp_price.h). The patterns
 * a plan uses at a stretch of stops [s0, s1] cover every fruit that no other stop reaches
 * and no fruit twice, so their reduced costs sum to at least the optimum Z of the stretch
 * as a problem of its own, in which the other fruits it reaches are optional and a covered
 * fruit f earns pi_f (the subset-row cuts' penalties left out: that only lowers Z). The
 * bound therefore rises by Z - sum_{p in [s0, s1]} v_p, and by the sum of such rises over
 * disjoint stretches. Z is bounded below by sub->bound (hv_price_bound) on the stretch's
 * sub-instance.
 */
#ifndef HV_MILP_REGION_H
#define HV_MILP_REGION_H

#include "hv/milp_options.h"
#include "hv/milp_subsolve.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What hv_region_rise found. */
typedef struct hv_region_result {
    double rise_ms;      /* >= 0; 0 when the stretch reaches no fruit */
    double root_rise_ms; /* ... at its sub-solve's root */
    long nodes;          /* of its sub-solve */
    int finished;        /* the sub-solve closed every node: the rise is the stretch's exact
                            one, or at least need_ms */
    int has_plan;        /* `plan` holds the stretch's best solution */
} hv_region_result_t;

/* The rise of the bound of `inst` at fruit duals pi_ms (n_fruits entries) and stop terms
 * v_ms (n_stops entries, the same duals') from the stretch [s0, s1]. The sub-solve stops
 * once the rise reaches need_ms (it proves no more) or at t_deadline_s (CLOCK_MONOTONIC
 * s), with `opt`'s choices as sub->bound (hv_price_bound) takes them. `plan` (may be
 * NULL, else n_fruits entries) receives, when res->has_plan, the stop of every fruit the
 * stretch's best solution covers and HV_NO_STOP for the rest. */
hv_status_t hv_region_rise(const hv_instance_t *inst, uint32_t s0, uint32_t s1, const double *pi_ms,
                           const double *v_ms, double need_ms, const hv_milp_options_t *opt,
                           const hv_milp_subsolver_t *sub, double t_deadline_s, uint32_t *plan,
                           hv_region_result_t *res);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_REGION_H */
