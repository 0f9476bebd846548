/* A harvest plan in memory: exactly what a plan file (docs/PLAN_FORMAT.md) holds.
 *
 * Built from a solved instance by hv_plan_build() (plan_build.c), written and read by
 * plan_io.h, verified by plan_check.h, run by the executor. Owns its arrays; free with
 * hv_plan_free(). Times in s, positions in m.
 */
#ifndef HV_PLAN_H
#define HV_PLAN_H

#include <stddef.h>
#include <stdint.h>

#include "hv/scara.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_PLAN_FORMAT_VERSION 2
#define HV_PLAN_PATH_LEN       1024
#define HV_PLAN_ID_LEN         32 /* same as HV_FRUIT_ID_LEN */
#define HV_PLAN_NAME_LEN       16
#define HV_PLAN_REASON_LEN     64

typedef struct hv_plan_pick {
    char id[HV_PLAN_ID_LEN];
    double x_m, y_m, z_m, yaw_rad; /* the fruit's pose as in the map */
    double cost_s;                 /* G: the pick model's time home -> fruit */
    double start_s;                /* planned start after arrival at the stop */
} hv_plan_pick_t;

typedef struct hv_plan_stop {
    uint32_t index; /* candidate stop index over the course:
                       y = row_start - stop_margin + index * step */
    double y_m;
    int pass; /* 0; 1 for Serial's second pass (right side) */
    double c_left_s, c_right_s, c_s, idle_left_s, idle_right_s;
    size_t n_left, n_right;
    hv_plan_pick_t *left, *right; /* in pick order */
} hv_plan_stop_t;

typedef struct hv_plan_unreachable {
    char id[HV_PLAN_ID_LEN];
    hv_side_t side;
    char reason[HV_PLAN_REASON_LEN];
} hv_plan_unreachable_t;

typedef struct hv_plan_horizon {
    int used;         /* 0: the row was planned in one window (the object is omitted) */
    double window_m;  /* H */
    double commit_m;  /* committed length per window */
    uint32_t windows; /* windows solved */
    uint32_t windows_optimal;
} hv_plan_horizon_t;

typedef struct hv_plan {
    char method[HV_PLAN_NAME_LEN]; /* "milp", "fov", "serial" */
    char fruit_map[HV_PLAN_PATH_LEN], cost_table_left[HV_PLAN_PATH_LEN],
        cost_table_right[HV_PLAN_PATH_LEN], config[HV_PLAN_PATH_LEN]; /* "" = none given */

    double stop_step_m, row_start_m, row_length_m, stop_penalty_s, vehicle_speed_mps,
        travel_time_s;                /* params: travel_time_s is one pass's T_travel */
    double stop_margin_m;             /* params: the course runs this far beyond both row ends */
    char pick_time[HV_PLAN_NAME_LEN]; /* params: "cycle" (a pick's cost_s is its whole
                                         cycle) or "one_way" (the paper's G); "_flat"
                                         after either: plan.pick_cost_flat's variant */

    char solver_status[HV_PLAN_NAME_LEN]; /* optimal feasible infeasible time_limit error
                                             heuristic */
    double gap;                           /* relative gap; < 0 = unknown (JSON null) */
    long nodes;
    double runtime_s, time_limit_s;

    /* totals */
    double makespan_s, pick_time_s, stop_time_s, total_travel_time_s;
    size_t n_stops_total, fruits_planned, fruits_unreachable;
    double throughput_fruit_per_s;

    hv_plan_horizon_t horizon;

    size_t n_stops;
    hv_plan_stop_t *stops; /* driving order: by pass, then y */
    size_t n_unreachable;
    hv_plan_unreachable_t *unreachable;
} hv_plan_t;

/* Free every array of `plan` and zero it. */
void hv_plan_free(hv_plan_t *plan);

/* Copy `src` (NUL-terminated) into dst[cap]; HV_ERR_ARG when it does not fit. */
hv_status_t hv_plan_copy_str(char *dst, size_t cap, const char *src);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_H */
