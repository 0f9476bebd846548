/* The paper's FOV baseline (DESIGN §1, §5; paper §IV.B), on the same instance as the MILP
 * (baselines.h holds both baselines).
 *
 * FOV ("non-optimised"): each arm has a camera whose view is a window of width_m along the
 * row, smaller than the arm's reach, centred centre_y_m[side] from the vehicle (fov.width
 * and fov.offset of the configuration, docs/FRAMES.md). The vehicle's stop positions tile
 * the row at width_m apart: stop k is at s0 + k w, s0 the first position at which some
 * camera's window starts at the first reachable fruit of its side; window k of side s
 * covers y in [s0 + k w + c_s - w/2, s0 + k w + c_s + w/2), so each fruit is in view at
 * exactly one position. Position k's stop is the candidate stop nearest to s0 + k w. At
 * each stop both arms pick every fruit of their side in view that the stop reaches; the
 * vehicle then advances exactly w. A position with nothing in view is driven through (no
 * stop, no tau).
 * A fruit in view that its stop cannot reach ("moved") is not dropped: the fruit map is
 * known before the run (the paper plans every method on the same map), so it is picked at
 * the nearest (in y; later on a tie) window stop that reaches it, and when no window stop
 * does, at an extra stop: the candidate stop nearest to the fruit that reaches it
 * (cheaper on a tie). Both cases are counted.
 */
#ifndef HV_FOV_H
#define HV_FOV_H

#include <stddef.h>

#include "hv/config.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The single window centred on the vehicle that hv_fov_solve uses (a warm start's seed). */
#define HV_FOV_DEFAULT_WIDTH_M 0.25

typedef struct hv_fov_params {
    double width_m;       /* window length along the row, and the vehicle's advance (m, > 0) */
    double centre_y_m[2]; /* window centre along the row relative to the vehicle, by
                             hv_side_t (m) */
} hv_fov_params_t;

typedef struct hv_fov_stats {
    size_t windows;     /* vehicle positions from the first to the last reachable fruit */
    size_t stops;       /* used stops */
    size_t moved;       /* fruits in view that their stop cannot reach, picked at another
                           window's stop or at an extra stop */
    size_t extra_stops; /* stops added for fruits no window stop reaches */
} hv_fov_stats_t;

/* The paper's FOV from the configuration: width fov.width; each window's centre fov.offset
 * from its arm's base along the row, outward (ahead of the left base, behind the right
 * one: the arms are mirror images), the bases mount.base_spacing / 2 ahead of and behind
 * the vehicle. */
void hv_fov_params_from_config(const hv_config_t *cfg, hv_fov_params_t *params);

/* FOV plan on `inst` into `out` (allocated by the caller for inst->n_fruits). `stats` may
 * be NULL. Errors: HV_ERR_ARG (width <= 0, a value not finite), HV_ERR_PLAN_NOMEM. */
hv_status_t hv_fov_solve_params(const hv_instance_t *inst, const hv_fov_params_t *params,
                                hv_assignment_t *out, hv_fov_stats_t *stats);

/* One window of fov_width_m centred on the vehicle for both arms: a cheap feasible plan the
 * solvers start from, not the paper's baseline. Errors as hv_fov_solve_params. */
hv_status_t hv_fov_solve(const hv_instance_t *inst, double fov_width_m, hv_assignment_t *out,
                         hv_fov_stats_t *stats);

#ifdef __cplusplus
}
#endif
#endif /* HV_FOV_H */
