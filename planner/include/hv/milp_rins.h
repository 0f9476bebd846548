/* Relaxation-induced neighbourhoods of a plan: a primal heuristic (internal to the
 * branch-and-price; milp.h).
 *
 * The fruits on which a plan and a node's LP point agree keep their stops; the others
 * (free_fruit) are re-planned exactly by a sub-solve, each over the stops its pairs allow
 * (pair_open: in the search, where the LP point holds some of it) and its own. Each kept
 * stop's fixed load on an arm becomes one stand-in fruit of that arm, reachable from that
 * stop only at the load's cost, so the kept stops stay open with their loads and the
 * sub-instance's makespan is the whole plan's: a better sub-plan is a better plan.
 */
#ifndef HV_MILP_RINS_H
#define HV_MILP_RINS_H

#include "hv/milp_options.h"
#include "hv/milp_subsolve.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Re-plan the fruits f with free_fruit[f] != 0 of `plan` (a complete plan of `inst`,
 * makespan *t_s), the others staying at their stops, each over its plan's stop and the
 * stops of its pairs k with pair_open[k] != 0 (inst->pairs order; NULL: every pair), by
 * sub->solve with `opt` (copied: quiet, one thread, no windows, polish or
 * neighbourhoods) for at most limit_s. On a better plan, `plan` and *t_s are updated and
 * *better = 1. res_out (may be NULL) receives the sub-solve's result. Returns HV_OK,
 * HV_ERR_ARG (also when a kept fruit's stop does not reach it), HV_ERR_PLAN_NOMEM or the
 * sub-solve's error; the plan stays valid either way. */
hv_status_t hv_rins_improve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                            const hv_milp_subsolver_t *sub, const unsigned char *free_fruit,
                            const unsigned char *pair_open, double limit_s, hv_assignment_t *plan,
                            double *t_s, int *better, hv_milp_result_t *res_out);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_RINS_H */
