/* Local search on stop-and-harvest assignments (the MILP's incumbent, DESIGN §5, §10).
 *
 * Moves, each accepted only when it lowers T = sum_p max(C^L_p, C^R_p) + tau * stops:
 *   relocate  one fruit to another reachable stop (opening it if needed);
 *   exchange  fruit f at p goes to q while fruit g at q goes to p (any sides: balances arms);
 *   close     empty a stop, each of its fruits to its best other open stop;
 *   shift     move a whole stop by a few grid steps (fruits it cannot keep go elsewhere).
 * Then an iterated local search: deterministic kicks (close / shift / split a stop) followed
 * by descent, keeping the best plan. Deterministic for a given instance and options.
 */
#ifndef HV_MILP_LOCAL_SEARCH_H
#define HV_MILP_LOCAL_SEARCH_H

#include <stdint.h>

#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_ls_options {
    unsigned kicks;     /* iterated-local-search kicks after the first descent */
    unsigned shift_max; /* largest stop shift tried, in grid steps */
    uint64_t seed;      /* kick choice (deterministic) */
} hv_ls_options_t;

void hv_ls_options_default(hv_ls_options_t *opt);

/* Improve `a` in place (it must be feasible: every reachable fruit on one of its stops,
 * unreachable fruits HV_NO_STOP). *makespan_s receives T of the result (T_travel included).
 * Errors: HV_ERR_ARG, HV_ERR_PLAN_BAD_PAIR / HV_ERR_PLAN_UNASSIGNED for an infeasible `a`,
 * HV_ERR_PLAN_NOMEM. */
hv_status_t hv_local_search(const hv_instance_t *inst, const hv_ls_options_t *opt,
                            hv_assignment_t *a, double *makespan_s);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_LOCAL_SEARCH_H */
