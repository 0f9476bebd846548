/* Options for the MILP's own sub-solves (internal to the MILP solvers): the row windows
 * (milp_window.h) and the relaxation-induced neighbourhoods (milp_rins.h) each solve a
 * small instance exactly, on their caller's thread, with hv_milp_solve. */
#ifndef HV_MILP_SUBSOLVE_H
#define HV_MILP_SUBSOLVE_H

#include "hv/milp.h"

#ifdef __cplusplus
extern "C" {
#endif

/* `opt`'s choices for a sub-solve of at most limit_s: quiet, no LP export, one tree
 * thread (the caller's: a worker of its own would take a third core), and none of the
 * primal heuristics that start solves of their own or run long (row windows and their
 * helper thread, the polish, which would not see opt->stop, and the neighbourhoods), nor
 * the regional bound, which starts solves of its own too: a sub-instance is small and its
 * plan near its optimum from the start. */
void hv_milp_subsolve_options(const hv_milp_options_t *opt, double limit_s,
                              hv_milp_options_t *out);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_SUBSOLVE_H */
