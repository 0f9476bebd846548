/* The exact-IK pick model (pick_model.h). */
#include <math.h>

#include "hv/pick_model.h"

static hv_status_t ik_cost(const void *ctx, const hv_fruit_t *fr, double stop_y_m, double *cost_s,
                           hv_pick_why_t *why)
{
    const hv_ik_model_t *ik = ctx;
    double move_s = 0.0;
    hv_status_t st = hv_pick_solve(&ik->arm[fr->side], fr->x_m, fr->y_m - stop_y_m, fr->z_m,
                                   fr->yaw_rad, NULL, &move_s, why);
    /* back home takes the way out reversed: the same time */
    double t = ik->cycle ? 2.0 * move_s + ik->cut_s + ik->release_s : move_s;
    /* whole ms, as the paper's table: the solver then proves to the ms and prunes a node
     * whose bound is within 1 ms of the plan (milp.h ms_granularity); the executor's time
     * differs by 0.5 ms a pick at most */
    *cost_s = round(t * 1000.0) / 1000.0;
    return st;
}

/* plan.pick_cost_flat: reachability as the IK's, the cost the fruit's least over the
 * candidate stops that reach it (so a plan gains nothing from where it stops but reach) */
static hv_status_t flat_cost(const void *ctx, const hv_fruit_t *fr, double stop_y_m, double *cost_s,
                             hv_pick_why_t *why)
{
    const hv_ik_model_t *ik = ctx;
    hv_status_t st = ik_cost(ctx, fr, stop_y_m, cost_s, why);
    if (st != HV_OK) {
        return st;
    }
    double lo = fr->y_m - ik->y_rel_max[fr->side], hi = fr->y_m - ik->y_rel_min[fr->side];
    lo = lo > ik->course_lo_m ? lo : ik->course_lo_m;
    hi = hi < ik->course_hi_m ? hi : ik->course_hi_m;
    long k_lo = (long)ceil((lo - ik->course_lo_m) / ik->step_m - 1e-9);
    long k_hi = (long)floor((hi - ik->course_lo_m) / ik->step_m + 1e-9);
    for (long k = k_lo; k <= k_hi; ++k) {
        double c = 0.0;
        hv_pick_why_t w = HV_PICK_OK;
        if (ik_cost(ctx, fr, ik->course_lo_m + (double)k * ik->step_m, &c, &w) == HV_OK &&
            c < *cost_s) {
            *cost_s = c;
        }
    }
    return HV_OK;
}

hv_status_t hv_pick_model_ik(const hv_config_t *cfg, hv_ik_model_t *ik, hv_pick_model_t *model)
{
    if (cfg == NULL || ik == NULL || model == NULL) {
        return HV_ERR_ARG;
    }
    ik->cycle = cfg->pick_cycle;
    ik->cut_s = cfg->cut_s;
    ik->release_s = cfg->release_s;
    model->cost = cfg->pick_cost_flat ? flat_cost : ik_cost;
    model->ctx = ik;
    for (int s = 0; s < 2; ++s) {
        hv_grid_t area;
        hv_config_arm(cfg, (hv_side_t)s, &ik->arm[s]);
        hv_config_grid(cfg, (hv_side_t)s, &area);
        hv_status_t st =
            hv_pick_reach_span(&ik->arm[s], &area, &model->y_rel_min[s], &model->y_rel_max[s]);
        if (st != HV_OK) {
            return st;
        }
        ik->y_rel_min[s] = model->y_rel_min[s];
        ik->y_rel_max[s] = model->y_rel_max[s];
    }
    /* the candidate stops of the config's row, as hv_instance_params_from_config lays them */
    hv_instance_params_t row;
    hv_instance_params_from_config(cfg, model, &row);
    ik->flat = cfg->pick_cost_flat;
    ik->step_m = row.stop_step_m;
    ik->course_lo_m = row.row_start_m - row.stop_margin_m;
    ik->course_hi_m = ik->course_lo_m + hv_instance_params_course_m(&row);
    return HV_OK;
}

const char *hv_pick_model_name(const hv_config_t *cfg)
{
    if (cfg->pick_cost_flat) {
        return cfg->pick_cycle ? "cycle_flat" : "one_way_flat";
    }
    return cfg->pick_cycle ? "cycle" : "one_way";
}
