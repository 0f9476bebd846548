/* The stop-and-harvest MILP of the paper, solved with GLPK's C API (DESIGN §5, §10).
 *
 * Variables: b_p (stop p used), a_fp (fruit f picked at stop p, only for reachable pairs),
 * C^L_p, C^R_p, C_p >= both; minimise sum C_p + tau * sum b_p + T_travel.
 */
#ifndef HV_MILP_H
#define HV_MILP_H

#include "hv/milp_options.h"
#include "hv/milp_subsolve.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Solve. `incumbent` (may be NULL) is a feasible assignment handed to the solver as its
 * starting incumbent; `out` (out->fruit_stop has inst->n_fruits entries, caller-allocated)
 * receives the best assignment found. Returns HV_OK when `res` is filled (whatever the
 * solve status), or a negative code on bad arguments / GLPK failure. */
hv_status_t hv_milp_solve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                          const hv_assignment_t *incumbent, hv_assignment_t *out,
                          hv_milp_result_t *res);

/* Write the compact model of `inst` (the paper's, as `--export-lp` writes it: the linking
 * opt->link_disaggregated chooses) to `path` in CPLEX LP format, without solving: what an
 * independent solver re-solves. HV_ERR_MILP_EXPORT when the file cannot be written. */
hv_status_t hv_milp_export_lp(const hv_instance_t *inst, const hv_milp_options_t *opt,
                              const char *path);

/* The sub-solver the MILP's own sub-solves go through (milp_subsolve.h): hv_milp_solve and
 * hv_price_bound. Row windows, neighbourhoods, regional bounds and their tests take it. */
const hv_milp_subsolver_t *hv_milp_default_subsolver(void);

/* A strong heuristic plan (e.g. FOV-like seed + local search), deterministic. */
hv_status_t hv_heuristic_solve(const hv_instance_t *inst, hv_assignment_t *out);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_H */
