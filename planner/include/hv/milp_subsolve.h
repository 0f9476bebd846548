/* The MILP's own sub-solves (internal to the MILP solvers): the row windows
 * (milp_window.h), the relaxation-induced neighbourhoods (milp_rins.h) and the regional
 * bounds (milp_region.h) each solve a small instance, on their caller's thread, through a
 * hv_milp_subsolver_t that the caller hands down (milp.h's hv_milp_default_subsolver()): the
 * branch-and-price never calls the public entry point back by name. */
#ifndef HV_MILP_SUBSOLVE_H
#define HV_MILP_SUBSOLVE_H

#include "hv/milp_options.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a bound sub-solve (hv_price_bound, milp_price.h) found. */
typedef struct hv_price_bound_result {
    double lb_ms;      /* min(cutoff, the least open bound): the optimum when finished and a
                          solution below the cutoff was found */
    double root_lb_ms; /* the root's bound */
    long nodes;        /* nodes solved */
    int finished;      /* every node was closed (not stopped by the deadline) */
    int has_plan;      /* a solution below the cutoff was found: the best one is in `plan` */
} hv_price_bound_result_t;

typedef struct hv_milp_subsolver hv_milp_subsolver_t;

/* The two sub-solves: `solve` as hv_milp_solve, `bound` as hv_price_bound (both take the
 * sub-solver itself, for the sub-solves of their own). */
struct hv_milp_subsolver {
    hv_status_t (*solve)(const hv_milp_subsolver_t *self, const hv_instance_t *inst,
                         const hv_milp_options_t *opt, const hv_assignment_t *incumbent,
                         hv_assignment_t *out, hv_milp_result_t *res);
    hv_status_t (*bound)(const hv_milp_subsolver_t *self, const hv_instance_t *inst,
                         const hv_milp_options_t *opt, const double *skip_ms, double cutoff_ms,
                         double t_deadline_s, uint32_t *plan, hv_price_bound_result_t *res);
};

/* `opt`'s choices for a sub-solve of at most limit_s: quiet, no LP export, one tree
 * thread (the caller's: a worker of its own would take a third core), and none of the
 * primal heuristics that start solves of their own or run long (row windows and their
 * helper thread, the polish, which would not see opt->stop, and the neighbourhoods), nor
 * the regional bound, which starts solves of its own too: a sub-instance is small and its
 * plan near its optimum from the start. */
void hv_milp_subsolve_options(const hv_milp_options_t *opt, double limit_s, hv_milp_options_t *out);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_SUBSOLVE_H */
