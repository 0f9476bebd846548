/* The paper's FOV baseline (DESIGN §1, §5; paper §IV.B), on the same instance as the MILP
 * (baselines.h holds both baselines).
 *
 * FOV ("non-optimised"): the camera sees a window of fov_width_m along the row, centred on
 * the vehicle. The windows tile the row from the first reachable fruit: window k covers
 * y in [y0 + k w, y0 + (k+1) w), y0 = the smallest reachable fruit y; its stop is the
 * candidate stop nearest to the window centre y0 + (k + 1/2) w. At each window stop both
 * arms pick every fruit of their side in view that the stop reaches; the vehicle then
 * advances by w. A window with nothing in view is driven through (no stop, no tau).
 * A fruit in view that its window's stop cannot reach is not dropped: it is picked at the
 * nearest (in y; later on a tie) window stop that reaches it, and when no window stop
 * does, at an extra stop: the candidate stop nearest to the fruit that reaches it
 * (cheaper on a tie). The counts of both cases are reported.
 */
#ifndef HV_FOV_H
#define HV_FOV_H

#include <stddef.h>

#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_FOV_DEFAULT_WIDTH_M 0.25

typedef struct hv_fov_stats {
    size_t windows;     /* windows from the first to the last reachable fruit */
    size_t stops;       /* used stops */
    size_t moved;       /* fruits picked at another window's stop */
    size_t extra_stops; /* stops added for fruits no window stop reaches */
} hv_fov_stats_t;

/* FOV plan on `inst` into `out` (allocated by the caller for inst->n_fruits). `stats` may
 * be NULL. Errors: HV_ERR_ARG (width <= 0 or not finite), HV_ERR_PLAN_NOMEM. */
hv_status_t hv_fov_solve(const hv_instance_t *inst, double fov_width_m, hv_assignment_t *out,
                         hv_fov_stats_t *stats);

#ifdef __cplusplus
}
#endif
#endif /* HV_FOV_H */
