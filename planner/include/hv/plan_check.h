/* The independent plan checker (DESIGN §5).
 *
 * Its own code path: it never uses the instance builder, its pairs or hv_assignment_eval.
 * From the fruit map and a pick model (the product's: exact IK, hv_pick_model_ik) it
 * recomputes every pick and verifies:
 *  - parameters: stop step, tau, vehicle speed as configured; the stop margin as the
 *    configuration gives it (row.stops_beyond_ends, the arms' reach); T_travel = (length +
 *    2 margin) / speed;
 *  - stops: on the candidate grid (y = row_start - margin + index * step), in driving
 *    order (pass, then y, strictly), each with at least one pick; Serial: pass 0 left only,
 *    pass 1 right only; other methods: pass 0 only;
 *  - every map fruit picked exactly once or listed unreachable, with its side and pose;
 *  - every pick reachable from its stop, its cost and start time as the model says;
 *  - a fruit listed unreachable is reached by no candidate stop, with a known reason
 *    ("row_end": a position beyond the candidate stops reaches it);
 *  - per-stop C^L, C^R, C, idle, the totals and the makespan, within 1e-6 s.
 * The first violation is reported as one line naming the plan's field.
 */
#ifndef HV_PLAN_CHECK_H
#define HV_PLAN_CHECK_H

#include <stddef.h>

#include "hv/config.h"
#include "hv/pick_model.h"
#include "hv/plan.h"
#include "hv/plan_instance.h"
#include "hv/plan_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_CHECK_TOL_S 1e-6

/* Check `plan` against in-memory inputs. */
hv_status_t hv_plan_check(const hv_plan_t *plan, const hv_config_t *cfg, const hv_fruit_t *fruits,
                          size_t n_fruits, const hv_pick_model_t *model, char *err, size_t errlen);

/* Re-read the config and the fruit map (limits from the plan's row), then hv_plan_check()
 * with the exact-IK model of the config. Cost tables, when named (here or in the plan's
 * inputs), are read and must have been built for the configured arms and grid
 * (hv_costtab_check_for). A NULL path is taken from plan->inputs and, unless absolute,
 * resolved against the folder of `plan_path`, the plan's file (plan_paths.h); `plan_path`
 * may be NULL only when every path is given. An empty table path in the plan means none. */
hv_status_t hv_plan_check_files(const hv_plan_t *plan, const char *plan_path,
                                const char *config_path, const char *left_path,
                                const char *right_path, const char *fruits_path, char *err,
                                size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_CHECK_H */
