/* Makespan of an assignment (DESIGN §1):
 *   T = sum_p max(C^L_p, C^R_p) + tau * (number of used stops) + T_travel
 * where C^L_p (C^R_p) is the sum of the pick costs of the left (right) fruits at stop p.
 * Used by the plan builder, the baselines, the horizon and the MILP's local search.
 * (The independent checker does NOT use this: it recomputes from the files.)
 */
#ifndef HV_PLAN_EVAL_H
#define HV_PLAN_EVAL_H

#include <stddef.h>

#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_eval {
    double makespan_s;    /* T */
    double pick_time_s;   /* sum_p C_p */
    double stop_time_s;   /* tau * stops */
    double travel_time_s; /* T_travel */
    size_t stops;         /* used stops */
    size_t fruits_planned;
} hv_eval_t;

/* Index into inst->pairs of the pair (fruit < n_fruits, stop), SIZE_MAX when the fruit
 * does not reach the stop. O(log pairs of the fruit). */
size_t hv_instance_pair_index(const hv_instance_t *inst, uint32_t fruit, uint32_t stop);

/* Cost (s) of the pair (fruit, stop): HV_OK and *cost_s, or HV_ERR_UNREACHABLE.
 * O(log pairs of the fruit). */
hv_status_t hv_instance_pair_cost(const hv_instance_t *inst, uint32_t fruit, uint32_t stop,
                                  double *cost_s);

/* Evaluate `a` on `inst`. Every fruit with pairs must be assigned to one of its reachable
 * stops (else HV_ERR_PLAN_UNASSIGNED / HV_ERR_PLAN_BAD_PAIR), fruits without pairs must be
 * HV_NO_STOP. `work` holds 2 * inst->n_stops doubles (caller's scratch, no allocation):
 * on return work[p] = C^L_p and work[n_stops + p] = C^R_p. */
hv_status_t hv_assignment_eval_ws(const hv_instance_t *inst, const hv_assignment_t *a, double *work,
                                  hv_eval_t *ev);

/* Same, allocating its own scratch. */
hv_status_t hv_assignment_eval(const hv_instance_t *inst, const hv_assignment_t *a, hv_eval_t *ev);

/* Shorthand: only T. */
hv_status_t hv_assignment_makespan(const hv_instance_t *inst, const hv_assignment_t *a,
                                   double *makespan_s);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_EVAL_H */
