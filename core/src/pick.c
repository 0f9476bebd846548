/* One pick as planner, checker and executor see it (hv/pick.h). */
#include <math.h>
#include <stddef.h>

#include "hv/pick.h"

const char *hv_pick_why_name(int why)
{
    static const char *const names[HV_PICK_WHY_COUNT] = {"ok", "height", "depth", "yaw"};
    return why >= 0 && why < HV_PICK_WHY_COUNT ? names[why] : "?";
}

void hv_pick_pose(hv_side_t side, double x_m, double y_rel_m, double z_m, double yaw_rad,
                  hv_pose_t *pose)
{
    pose->x_m = x_m;
    pose->y_m = y_rel_m;
    pose->z_m = z_m;
    pose->heading_rad = hv_side_normal_heading(side) + yaw_rad;
}

/* Joint 1 sets the height alone (hv_scara_ik: z = base z + ee z at zero joints + q1), so a
 * height outside its stroke is out of reach from every vehicle position. Same tolerance as
 * the IK's limit check. */
static int height_in_stroke(const hv_arm_t *arm, double z_m)
{
    double q1 = z_m - arm->base_m[2] - arm->origin_m[4][2];
    return q1 >= arm->limit[0].min - 1e-9 && q1 <= arm->limit[0].max + 1e-9;
}

hv_status_t hv_pick_solve(const hv_arm_t *arm, double x_m, double y_rel_m, double z_m,
                          double yaw_rad, double q[HV_NJOINTS], double *move_s, hv_pick_why_t *why)
{
    if (arm == NULL || move_s == NULL) {
        return HV_ERR_ARG;
    }
    hv_pose_t pose;
    hv_pick_pose(arm->side, x_m, y_rel_m, z_m, yaw_rad, &pose);
    double qs[HV_NJOINTS];
    hv_status_t st = hv_scara_ik(arm, &pose, qs);
    hv_pick_why_t w = HV_PICK_OK;
    if (st == HV_OK) {
        *move_s = hv_scara_move_time(arm, arm->home, qs);
        if (q != NULL) {
            for (int j = 0; j < HV_NJOINTS; j++) {
                q[j] = qs[j];
            }
        }
    } else if (st == HV_ERR_UNREACHABLE) {
        w = height_in_stroke(arm, z_m) ? HV_PICK_DEPTH : HV_PICK_HEIGHT;
    } else if (st == HV_ERR_JOINT_LIMIT) {
        w = HV_PICK_YAW;
    } else {
        w = HV_PICK_DEPTH; /* non-finite input: no position reaches it */
    }
    if (why != NULL) {
        *why = w;
    }
    return st;
}

hv_status_t hv_pick_reach_span(const hv_arm_t *arm, const hv_grid_t *area, double *y_rel_min,
                               double *y_rel_max)
{
    if (arm == NULL || area == NULL || y_rel_min == NULL || y_rel_max == NULL) {
        return HV_ERR_ARG;
    }
    const hv_axis_t *ax = &area->axis[HV_AX_X], *ay = &area->axis[HV_AX_Y],
                    *az = &area->axis[HV_AX_Z], *aw = &area->axis[HV_AX_YAW];
    /* the planar reach does not depend on the height: one height inside the stroke */
    double z = NAN;
    for (uint32_t iz = 0; iz < az->count && isnan(z); iz++) {
        double zi = az->origin + az->step * iz;
        if (height_in_stroke(arm, zi)) {
            z = zi;
        }
    }
    if (isnan(z)) {
        return HV_ERR_UNREACHABLE;
    }
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (uint32_t ix = 0; ix < ax->count; ix++) {
        double x = ax->origin + ax->step * ix;
        for (uint32_t iw = 0; iw < aw->count; iw++) {
            double yaw = aw->origin + aw->step * iw;
            for (uint32_t iy = 0; iy < ay->count; iy++) {
                double y = ay->origin + ay->step * iy;
                double t;
                if (hv_pick_solve(arm, x, y, z, yaw, NULL, &t, NULL) == HV_OK) {
                    lo = y < lo ? y : lo;
                    hi = y > hi ? y : hi;
                }
            }
        }
    }
    if (!(lo <= hi)) {
        return HV_ERR_UNREACHABLE;
    }
    *y_rel_min = lo - HV_PICK_SPAN_STEPS * ay->step;
    *y_rel_max = hi + HV_PICK_SPAN_STEPS * ay->step;
    return HV_OK;
}

double hv_pick_margin_of_spans(const double y_rel_min[2], const double y_rel_max[2], double step)
{
    double reach = 0.0;
    for (int s = 0; s < 2; s++) {
        reach = fmax(reach, fmax(y_rel_max[s], -y_rel_min[s]));
    }
    /* nm: so 70 steps of 0.01 m read back as 0.7 in a plan file */
    return round(ceil(reach / step - 1e-9) * step * 1e9) / 1e9;
}

hv_status_t hv_pick_stop_margin(const hv_config_t *cfg, double *margin_m)
{
    if (cfg == NULL || margin_m == NULL) {
        return HV_ERR_ARG;
    }
    double lo[2], hi[2];
    for (int s = 0; s < 2; s++) {
        hv_arm_t arm;
        hv_grid_t area;
        hv_config_arm(cfg, (hv_side_t)s, &arm);
        hv_config_grid(cfg, (hv_side_t)s, &area);
        hv_status_t st = hv_pick_reach_span(&arm, &area, &lo[s], &hi[s]);
        if (st != HV_OK) {
            return st;
        }
    }
    *margin_m = hv_pick_margin_of_spans(lo, hi, cfg->grid_step_m);
    return HV_OK;
}
