/* One pick as the planner, the plan checker and the executor all see it.
 *
 * A fruit at (x, y, z, yaw) (docs/FRAMES.md: x, z in the vehicle frame, y along the row,
 * yaw relative to the side's inward normal) is picked from the vehicle stopped at y_stop by
 * the arm of the fruit's side. Whether that arm reaches it, the joint setpoint and the time
 * of the move home -> fruit all come from the exact IK (hv_scara_ik) of that one pose, so
 * a plan never assigns a fruit that the executor would refuse at the same stop, and the
 * plan's pick time is the time the executor expects. No allocation, no OS calls.
 */
#ifndef HV_PICK_H
#define HV_PICK_H

#include "hv/config.h"
#include "hv/cost_table.h"
#include "hv/scara.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Why a fruit cannot be picked from a vehicle position (or from any). */
typedef enum hv_pick_why {
    HV_PICK_OK = 0,
    HV_PICK_HEIGHT, /* z outside joint 1's stroke: no vehicle position helps */
    HV_PICK_DEPTH,  /* the wrist (fruit minus the last link at the pick heading) lies outside
                       the annulus of the two inner links: too deep, too near or too far
                       along the row */
    HV_PICK_YAW,    /* within the annulus, but no solution inside the joint limits at the
                       pick heading */
    HV_PICK_WHY_COUNT
} hv_pick_why_t;

/* "ok", "height", "depth", "yaw"; "?" out of range. */
const char *hv_pick_why_name(int why);

/* The end-effector pose for a fruit seen from a stop: y relative to the stop (fruit y minus
 * stop y, m) and the heading = the side's inward normal + yaw. */
void hv_pick_pose(hv_side_t side, double x_m, double y_rel_m, double z_m, double yaw_rad,
                  hv_pose_t *pose);

/* Solve the pick of a fruit by `arm` (its side gives the heading) at y_rel_m from the stop.
 * HV_OK with q (joint setpoint; may be NULL) and *move_s (rest-to-rest time home -> q, s;
 * the way back takes the same time); else HV_ERR_NAN, HV_ERR_UNREACHABLE or
 * HV_ERR_JOINT_LIMIT, and *why (may be NULL) says which of height, depth, yaw. */
hv_status_t hv_pick_solve(const hv_arm_t *arm, double x_m, double y_rel_m, double z_m,
                          double yaw_rad, double q[HV_NJOINTS], double *move_s, hv_pick_why_t *why);

/* Samples between the grid's hide the extremes by less than a step in y; x and yaw samples
 * shift them by a few mm more. Spans are widened by this many y steps to cover both. */
#define HV_PICK_SPAN_STEPS 2

/* The span of y_rel (fruit y minus stop y, m) over which `arm` reaches some sample of the
 * fruit area `area` (a cost-table grid: its x and yaw axes, the first z of its z axis inside
 * joint 1's stroke; y_rel on its y axis), widened by HV_PICK_SPAN_STEPS y steps each way.
 * Outside it the arm reaches no fruit of the area. HV_ERR_UNREACHABLE when it reaches no
 * sample at all. */
hv_status_t hv_pick_reach_span(const hv_arm_t *arm, const hv_grid_t *area, double *y_rel_min,
                               double *y_rel_max);

/* How far beyond each end of the row (m) an arm still reaches into the fruit area, given
 * both arms' reach spans (hv_pick_reach_span, indexed by hv_side_t): a fruit at the row's
 * start is reached from stops down to start - y_rel_max, one at its end from stops up to
 * end - y_rel_min. The larger of the two, rounded up to a whole number of `step`. */
double hv_pick_margin_of_spans(const double y_rel_min[2], const double y_rel_max[2], double step);

/* hv_pick_margin_of_spans() of the configured arms over their fruit areas: the distance the
 * candidate stops extend beyond each row end when row.stops_beyond_ends is set. */
hv_status_t hv_pick_stop_margin(const hv_config_t *cfg, double *margin_m);

#ifdef __cplusplus
}
#endif
#endif /* HV_PICK_H */
