/* The exact-IK pick model (pick_model.h). */
#include "hv/pick_model.h"

static hv_status_t ik_cost(const void *ctx, const hv_fruit_t *fr, double stop_y_m,
                           double *cost_s, hv_pick_why_t *why)
{
    const hv_ik_arms_t *arms = ctx;
    return hv_pick_solve(&arms->arm[fr->side], fr->x_m, fr->y_m - stop_y_m, fr->z_m,
                         fr->yaw_rad, NULL, cost_s, why);
}

hv_status_t hv_pick_model_ik(const hv_config_t *cfg, hv_ik_arms_t *arms,
                             hv_pick_model_t *model)
{
    if (cfg == NULL || arms == NULL || model == NULL) {
        return HV_ERR_ARG;
    }
    model->cost = ik_cost;
    model->ctx = arms;
    for (int s = 0; s < 2; ++s) {
        hv_grid_t area;
        hv_config_arm(cfg, (hv_side_t)s, &arms->arm[s]);
        hv_config_grid(cfg, (hv_side_t)s, &area);
        hv_status_t st = hv_pick_reach_span(&arms->arm[s], &area, &model->y_rel_min[s],
                                            &model->y_rel_max[s]);
        if (st != HV_OK) {
            return st;
        }
    }
    return HV_OK;
}
