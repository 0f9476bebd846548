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

hv_status_t hv_pick_model_ik(const hv_config_t *cfg, hv_ik_model_t *ik, hv_pick_model_t *model)
{
    if (cfg == NULL || ik == NULL || model == NULL) {
        return HV_ERR_ARG;
    }
    ik->cycle = cfg->pick_cycle;
    ik->cut_s = cfg->cut_s;
    ik->release_s = cfg->release_s;
    model->cost = ik_cost;
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
    }
    return HV_OK;
}

const char *hv_pick_model_name(const hv_config_t *cfg)
{
    return cfg->pick_cycle ? "cycle" : "one_way";
}
