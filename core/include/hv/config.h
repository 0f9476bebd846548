/* The harvest configuration: the arm, its mount, the row, the vehicle and the grids.
 *
 * One text file (config/harvest.cfg) holds every geometric and timing parameter, so the
 * choices DESIGN §2 leaves open are made in one place. Format: `key = value [value...]`
 * per line, `#` starts a comment, SI units unless the key ends in `_deg`. Every key is
 * required; unknown and duplicate keys are errors. See config/harvest.cfg for the keys.
 *
 * Parsing works on a caller-supplied text buffer: no OS calls, no allocation.
 */
#ifndef HV_CONFIG_H
#define HV_CONFIG_H

#include <stddef.h>

#include "hv/cost_table.h"
#include "hv/scara.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_config {
    /* arm as built (both arms are the same model) */
    double origin_m[5][3];              /* arm.origin.{j1,j2,j3,j4,ee} */
    hv_joint_limit_t limit[HV_NJOINTS]; /* joint{1..4}.{min,max,vmax,amax} */
    double home[HV_NJOINTS];            /* arm.home */
    int elbow_free;                     /* arm.elbow_free (0/1) */

    /* mount (DESIGN §2 and docs/FRAMES.md) */
    double base_height_m;  /* mount.base_height */
    double base_spacing_m; /* mount.base_spacing: along the row, left base ahead (+y) */
    double offset_m;       /* mount.offset: the paper's D, lateral distance of each base
                                from its canopy's near face (towards the aisle centre) */
    double theta_rad[2];   /* mount.theta_left_deg / theta_right_deg: base rotation from
                                the side's inward normal, clockwise seen from above for
                                the right arm (the left arm is the right one turned half
                                a turn about z) */

    /* row and fruit-planted area */
    double row_length_m;     /* row.length */
    double aisle_width_m;    /* row.aisle_width: between the two canopies' near faces */
    double canopy_depth_m;   /* row.canopy_depth */
    double canopy_z_min_m;   /* row.canopy_z_min: lowest fruit height above the floor */
    double canopy_height_m;  /* row.canopy_height */
    double pick_yaw_max_rad; /* row.pick_yaw_max_deg: stem cutting needs |yaw| <= this */
    int stops_beyond_ends;   /* row.stops_beyond_ends (0/1): 1 lets the vehicle stop beyond
                                 the row's ends as far as an arm reaches into the row
                                 (hv_pick_stop_margin); 0 keeps stops in [0, row.length] */

    /* vehicle */
    double vehicle_speed_mps;  /* vehicle.speed */
    double vehicle_accel_mps2; /* vehicle.accel */
    double stop_penalty_s;     /* vehicle.stop_penalty: the paper's tau */

    /* the pick cycle: home -> fruit, cut, fruit -> home, release */
    double cut_s;       /* pick.cut_time (s) */
    double release_s;   /* pick.release_time (s) */
    int pick_cycle;     /* plan.pick_cycle (0/1): 1 plans in the robot's time (a pick
                                  costs its whole cycle, a stop what the drive loses
                                  stopping: hv_config_stop_time_s); 0 in the paper's (G one
                                  way home -> fruit, tau = vehicle.stop_penalty) */
    int pick_cost_flat; /* plan.pick_cost_flat (0/1): 1 gives each fruit, from every stop
                           that reaches it, the cost of its best stop (experiments only:
                           what the plans owe to the pick cost varying with the stop) */

    /* online mode: the camera's view along the row, relative to the vehicle's position */
    double camera_lead_m;   /* camera.lead: near edge of the view ahead of the vehicle (m) */
    double camera_window_m; /* camera.window: length of the view along the row (m, > 0) */
    /* the FOV baseline (planner fov.h, docs/FRAMES.md): each arm's camera window */
    double fov_width_m;  /* fov.width: window length along the row, also the vehicle's
                            advance between FOV stops (m, > 0) */
    double fov_offset_m; /* fov.offset: window centre from its arm's base along the row,
                            outward (ahead of the left base, behind the right), m */
    /* online mode: a horizon's solve may take half the robot time committed ahead, within
     * [online.horizon_limit_min, online.horizon_limit_max] (s) */
    double online_limit_min_s, online_limit_max_s;
    /* online mode: the executor's longest wait for the planner's next stop before it makes a
     * controlled stop (real s, >= online.horizon_limit_max) */
    double online_wait_plan_timeout_s;

    /* grids */
    double grid_step_m;        /* grid.step: stops and x, y, z of the cost table */
    double grid_yaw_step_rad;  /* grid.yaw_step_deg */
    double grid_y_half_span_m; /* grid.y_half_span: table covers y_rel in [-s, s] */

    /* installation-pose search (mountopt) */
    double search_offset_min_m, search_offset_max_m, search_offset_step_m;
    double search_theta_min_rad, search_theta_max_rad, search_theta_step_rad;
} hv_config_t;

/* Parse `text` (len bytes, need not be NUL-terminated). On error diag names the key and
 * the line. Codes: HV_ERR_CFG_SYNTAX, _UNKNOWN, _MISSING, _RANGE, _DUPLICATE. */
hv_status_t hv_config_parse(const char *text, size_t len, hv_config_t *cfg, hv_diag_t *diag);

/* The arm of one side as mounted by this configuration (mount.offset/theta as given). */
void hv_config_arm(const hv_config_t *cfg, hv_side_t side, hv_arm_t *arm);

/* Same, with an explicit mount offset D (m) and theta (rad): used by the mount search. */
void hv_config_arm_mounted(const hv_config_t *cfg, hv_side_t side, double offset_m,
                           double theta_rad, hv_arm_t *arm);

/* The cost-table grid of one side: x over the canopy depth (negative x for the left side),
 * y_rel over [-y_half_span, y_half_span], z over the canopy height, yaw over
 * [-pick_yaw_max, pick_yaw_max], all at the configured steps. */
void hv_config_grid(const hv_config_t *cfg, hv_side_t side, hv_grid_t *grid);

/* The planner's cost of one stop (s): with plan.pick_cycle the time the drive loses by
 * stopping (vehicle.speed / vehicle.accel, the trapezoid's extra over driving through),
 * else the paper's tau (vehicle.stop_penalty). */
double hv_config_stop_time_s(const hv_config_t *cfg);

#ifdef __cplusplus
}
#endif
#endif /* HV_CONFIG_H */
