/* A helper thread that improves the search's incumbent on the second core (internal to the
 * branch-and-price; milp_price.h). DESIGN §10 counts 2 cores; the tree search uses one.
 *
 * The helper first polishes its starting plan by a long local search (the polish the
 * search would otherwise run in its own thread after the root), then re-plans row windows
 * of the best plan it knows (milp_window.h), with widths 5, 4, 3, 6, 2 in turn, until it
 * is stopped or its deadline passes. The search offers it
 * every better plan it finds and takes the helper's better plans at each pricing round. Each
 * thread has its own GLPK environment (GLPK keeps it thread-local).
 */
#ifndef HV_MILP_HELPER_H
#define HV_MILP_HELPER_H

#include "hv/milp_options.h"
#include "hv/milp_subsolve.h"
#include "hv/milp_window.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_helper hv_helper_t;

/* Start the helper from `plan` (makespan t_s) of `inst`, which must outlive it; it works
 * until hv_helper_stop or the clock (CLOCK_MONOTONIC, s) reaches t_deadline_s, beginning
 * with `polish_kicks` local-search kicks (0: none). `opt` is copied; the windows'
 * sub-solves go through `sub`. Returns HV_OK, HV_ERR_PLAN_NOMEM, or HV_ERR_ARG when the
 * thread cannot start. */
hv_status_t hv_helper_start(const hv_instance_t *inst, const hv_milp_options_t *opt,
                            const hv_milp_subsolver_t *sub, const hv_assignment_t *plan, double t_s,
                            double t_deadline_s, unsigned polish_kicks, hv_helper_t **out);

/* The search's better plan: the helper continues from it when it beats its own. */
void hv_helper_offer(hv_helper_t *h, const hv_assignment_t *plan, double t_s);

/* 1 when the helper holds a plan better than t_s: copied into `plan` (inst->n_fruits
 * entries) with its makespan in *t_out. 0 otherwise. */
int hv_helper_take(hv_helper_t *h, double t_s, hv_assignment_t *plan, double *t_out);

/* Stop the helper (its sub-solve ends at its next node), join and free it. stats (may be
 * NULL) receives its window counts. Returns HV_OK or the helper's first error. */
hv_status_t hv_helper_stop(hv_helper_t *h, hv_window_stats_t *stats);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_HELPER_H */
