/* Branch-and-price for the stop-and-harvest MILP (internal; planner/SOLVER.md).
 *
 * The same problem as the paper's model, in its Dantzig-Wolfe form: a column is a stop
 * pattern (stop p, left fruits L, right fruits R) costing tau + max(G^L(L), G^R(R)); the
 * master LP (GLPK simplex) covers every reachable fruit exactly once with at most one
 * pattern per stop. Its LP bound is the compact model's after the per-stop max has been
 * convexified, which is where the compact model's bound is weak. Columns are priced per
 * stop exactly (two Pareto knapsack frontiers, one per arm, merged on the stop time);
 * branching is on the number of stops (a master row) and then on one fruit's stop
 * interval, which the pricing obeys. Nodes are taken best bound first with dives;
 * (fruit, stop) pairs are fixed by reduced cost from the root's duals.
 *
 * Every bound used for pruning is the Lagrangian bound sum_i pi_i + sum_p min(0, v_p)
 * (v_p the exact pricing value at stop p), valid for any duals pi, so early stops of the
 * column generation never make a pruning wrong.
 */
#ifndef HV_MILP_PRICE_H
#define HV_MILP_PRICE_H

#include "hv/milp_options.h"
#include "hv/milp_subsolve.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Solve `inst` (one row segment) by branch-and-price until `t_deadline_s` (CLOCK_MONOTONIC
 * seconds). `inc` (may be NULL) is a feasible assignment costing inc_t seconds; it seeds
 * the columns and the incumbent. Fills `out` and `res` like hv_milp_solve. */
hv_status_t hv_price_solve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                           const hv_milp_subsolver_t *sub, const hv_assignment_t *inc, double inc_t,
                           double t_deadline_s, hv_assignment_t *out, hv_milp_result_t *res);

/* A lower bound on the optimum of `inst` with some fruits optional: leaving fruit f
 * uncovered costs skip_ms[f] (INFINITY: f must be covered), and the value of a solution is
 * its patterns' costs plus T_travel plus the skip costs of the fruits it leaves out. The
 * search prunes at cutoff_ms (as if a plan of that value were known) and ends there or at
 * t_deadline_s, with `opt`'s choices as a sub-solve's (milp_subsolve.h), no column dive,
 * no gap and no helper thread (no centre ascent: it runs in hv_price_solve only). `plan`
 * (may be NULL, else n_fruits entries) receives the best solution's stop per fruit,
 * HV_NO_STOP for one left out. */
hv_status_t hv_price_bound(const hv_instance_t *inst, const hv_milp_options_t *opt,
                           const hv_milp_subsolver_t *sub, const double *skip_ms, double cutoff_ms,
                           double t_deadline_s, uint32_t *plan, hv_price_bound_result_t *res);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_PRICE_H */
