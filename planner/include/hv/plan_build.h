/* Turn a solved instance into a plan (plan.h): stops in driving order, per-arm pick lists
 * with planned start times, per-stop C^L, C^R, C, idle times, totals, unreachable fruits. */
#ifndef HV_PLAN_BUILD_H
#define HV_PLAN_BUILD_H

#include "hv/plan.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What the plan says besides the assignment. Strings are copied. */
typedef struct hv_plan_meta {
    const char *method; /* "milp", "fov", "serial" */
    const char *fruit_map, *cost_table_left, *cost_table_right, *config; /* input paths */
    hv_instance_params_t params; /* the row the instance was built on */
    const char *pick_time;       /* "cycle" or "one_way" (hv_pick_model_name); NULL: one_way */
    double vehicle_speed_mps;
    const char *solver_status; /* "optimal", "feasible", "heuristic", ... */
    double gap;                /* < 0 = unknown */
    long nodes;
    double runtime_s, time_limit_s;
    hv_plan_horizon_t horizon;
} hv_plan_meta_t;

/* Build `plan` from `a` on `inst` (a stop index of `inst` is the candidate stop index over
 * meta->params' row). `passes` (may be NULL = all 0) gives each fruit's pass: Serial puts
 * the left side in pass 0 and the right side in pass 1; with `passes` set the row is
 * driven twice, so T_travel counts twice.
 * Picks of one arm at one stop are ordered by y, then id. The assignment must be valid
 * (hv_assignment_eval); errors HV_ERR_PLAN_UNASSIGNED / _BAD_PAIR / _NOMEM / HV_ERR_ARG. */
hv_status_t hv_plan_build(const hv_instance_t *inst, const hv_assignment_t *a,
                          const unsigned char *passes, const hv_plan_meta_t *meta, hv_plan_t *plan);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_BUILD_H */
