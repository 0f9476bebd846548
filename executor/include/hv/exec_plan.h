/* The plan as the executor holds it: fixed-capacity tables, no heap (DESIGN §7).
 *
 * Filled from a plan file (docs/PLAN_FORMAT.md) by hv_exec_plan_load_json() or directly by
 * tests, then completed by hv_exec_plan_prepare(), which solves the IK of every pick with
 * the arm of its side and derives the motion times the executor's timeouts and its
 * expected makespan are built on. Picks of one arm at one stop are contiguous, in the
 * plan's pick order; stops are in driving order.
 *
 * The executor's expected time (what "planned vs executed" compares against):
 *   pick cycle   = t(home -> fruit) + cut_s + t(fruit -> home) + release_s
 *                  (t: core's hv_pick_solve, the exact IK and move time the planner's
 *                   pick model uses, so the plan's G is the first term)
 *   stop time    = max over the two arms of the sum of their pick cycles at that stop
 *   vehicle time = trapezoid moves (vehicle speed, accel) from the course start (row start
 *                  - stop margin) to each stop in turn and from the last stop to the
 *                  course end (row end + stop margin)
 *   expected makespan = sum of stop times + sum of vehicle times.
 *
 * What the state machine reads at each step (setpoints, move times, stop positions, the
 * course, home poses) is in its real type (hv/exec_real.h: float in the firmware); the
 * plan's own data and the expected times stay double.
 */
#ifndef HV_EXEC_PLAN_H
#define HV_EXEC_PLAN_H

#include <stdint.h>

#include "hv/exec_real.h"
#include "hv/scara.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Capacities of the tables; a build may set smaller ones for all its code (firmware/). */
#ifndef HV_EXEC_MAX_STOPS
#define HV_EXEC_MAX_STOPS 1024u /* a 50 m row at the paper's densities takes ~600 */
#endif
#ifndef HV_EXEC_MAX_PICKS
#define HV_EXEC_MAX_PICKS 4096u /* both arms together */
#endif
#define HV_EXEC_ID_LEN 32u /* fruit id incl. its NUL */

typedef struct hv_exec_pick {
    char id[HV_EXEC_ID_LEN]; /* fruit id from the map */
    hv_side_t side;
    uint16_t stop;        /* index into hv_exec_plan_t.stops */
    double x_m, y_m, z_m; /* fruit position: x, z vehicle frame, y along the row */
    double yaw_rad;       /* pick heading relative to the side's inward normal */
    double cost_s;        /* the plan's G (home -> fruit) */
    double start_s;       /* the plan's start of this pick after arrival at the stop */
    /* filled by hv_exec_plan_prepare() */
    int reachable;                /* 1: IK found a solution within the joint limits */
    hv_status_t ik_status;        /* HV_OK or the IK's error when not reachable */
    hv_exec_real_t q[HV_NJOINTS]; /* joint setpoint at the fruit (m, rad) */
    hv_exec_real_t move_s;        /* rest-to-rest time home -> q (s, plan time) */
    double cycle_s;               /* expected pick cycle: 2 * move_s + cut_s + release_s */
} hv_exec_pick_t;

typedef struct hv_exec_stop {
    uint32_t plan_index; /* the plan's stop index p (grid index along the row) */
    hv_exec_real_t y_m;  /* stop position along the row */
    uint16_t first[2];   /* first pick of each arm (indexed by hv_side_t) */
    uint16_t count[2];   /* number of picks of each arm */
    /* filled by hv_exec_plan_prepare() */
    double arm_s[2];   /* expected busy time of each arm at this stop */
    double expected_s; /* max of arm_s */
    double drive_s;    /* expected vehicle move from the previous stop (or the course
                                start) */
} hv_exec_stop_t;

typedef struct hv_exec_plan {
    uint16_t n_stops;
    uint16_t n_picks;
    hv_exec_stop_t stops[HV_EXEC_MAX_STOPS];
    hv_exec_pick_t picks[HV_EXEC_MAX_PICKS];
    hv_exec_real_t row_start_m, row_length_m;
    hv_exec_real_t stop_margin_m; /* the course runs this far beyond both row ends (m) */
    double planned_makespan_s;    /* the plan's totals.makespan_s (paper's objective) */
    double planned_pick_s;        /* the plan's totals.pick_time_s */
    /* filled by hv_exec_plan_prepare() */
    hv_exec_real_t home[2][HV_NJOINTS]; /* home pose of each arm */
    double final_drive_s;               /* expected move from the last stop to the course end */
    double expected_makespan_s;         /* see the top of this file */
    unsigned n_unreachable;             /* picks the IK could not reach (they will be skipped) */
} hv_exec_plan_t;

/* Timing model of the pick cycle and the vehicle (plan time, s). */
typedef struct hv_exec_timing {
    double cut_s;              /* end effector cut, > 0 */
    double release_s;          /* end effector release into the container, > 0 */
    double vehicle_speed_mps;  /* > 0 */
    double vehicle_accel_mps2; /* > 0 */
} hv_exec_timing_t;

/* Solve every pick's IK with `arm[side]` (pose relative to its stop: y - stop y, heading =
 * side normal + yaw), and compute the expected times. A pick the IK cannot reach is kept
 * with reachable = 0 (the executor skips it with a reason); it does not fail the call. */
hv_status_t hv_exec_plan_prepare(hv_exec_plan_t *plan, const hv_arm_t arm[2],
                                 const hv_exec_timing_t *timing);

/* Where the vehicle's course starts and ends (m along the row): the row and the plan's
 * stop margin beyond each end. The vehicle starts the row at the start and leaves it at the
 * end. */
hv_exec_real_t hv_exec_course_start(const hv_exec_plan_t *plan);
hv_exec_real_t hv_exec_course_end(const hv_exec_plan_t *plan);

/* Online: append one stop at y_m (candidate index plan_index) after the last one, with
 * its picks (left ones first: n_left, then n_right; id, pose, cost_s and start_s are
 * taken, their stop is set). Stops already there never change. Refused: a stop behind the
 * last one or off the course, or a fruit already in the plan (HV_ERR_EXEC_PLAN_RANGE, the
 * plan unchanged), the tables full (HV_ERR_EXEC_PLAN_CAPACITY). Run
 * hv_exec_plan_prepare() afterwards. */
hv_status_t hv_exec_plan_append(hv_exec_plan_t *plan, uint32_t plan_index, hv_exec_real_t y_m,
                                const hv_exec_pick_t *picks, uint16_t n_left, uint16_t n_right);

/* Online: 1 when stop s of the plan is the stop (plan_index, y_m, its picks as for
 * hv_exec_plan_append: the same ids on the same sides in the same order, y within 1e-9 m),
 * else 0. A planner that commits again what the plan holds (after a restart of either
 * program) must commit the very same stops. */
int hv_exec_plan_stop_matches(const hv_exec_plan_t *plan, uint16_t s, uint32_t plan_index,
                              hv_exec_real_t y_m, const hv_exec_pick_t *picks, uint16_t n_left,
                              uint16_t n_right);

/* Index of a pick by (side, id); -1 when the plan has no such pick. */
int hv_exec_plan_find(const hv_exec_plan_t *plan, hv_side_t side, const char *id);

/* Rest-to-rest time (s) of a vehicle move over |dist_m| with speed and accel limits. */
hv_exec_real_t hv_exec_vehicle_move_s(hv_exec_real_t dist_m, hv_exec_real_t speed_mps,
                                      hv_exec_real_t accel_mps2);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_PLAN_H */
