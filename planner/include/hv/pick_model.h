/* Where the instance builder and the plan checker get a pick's cost and reachability.
 *
 * A small interface (one function and its context), so the product computes every pick
 * by the exact IK the executor uses (hv_pick_model_ik, core's hv/pick.h), while tests can
 * supply synthetic costs whose optima they know.
 */
#ifndef HV_PICK_MODEL_H
#define HV_PICK_MODEL_H

#include "hv/config.h"
#include "hv/pick.h"
#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_pick_model {
    /* Cost (s) of picking `fruit` with its side's arm from the vehicle stopped at
     * stop_y_m: HV_OK with *cost_s, or an error status with *why (HV_PICK_HEIGHT, _DEPTH
     * or _YAW) saying why it cannot. */
    hv_status_t (*cost)(const void *ctx, const hv_fruit_t *fruit, double stop_y_m, double *cost_s,
                        hv_pick_why_t *why);
    const void *ctx;
    /* Per side (hv_side_t): fruit y minus stop y (m) outside [y_rel_min, y_rel_max] is out
     * of reach; the builder and the checker try only stops inside. */
    double y_rel_min[2], y_rel_max[2];
} hv_pick_model_t;

/* The product's model: exact IK of each pair with the configured arms (hv_pick_solve).
 * The cost is the pick's whole cycle, 2 move_s + cut_s + release_s (the executor's), with
 * plan.pick_cycle; the paper's G = move_s (home -> fruit) without; rounded to whole ms
 * (the solver's proofs are to the ms). Must outlive `model`. */
typedef struct hv_ik_model {
    hv_arm_t arm[2]; /* [HV_SIDE_LEFT], [HV_SIDE_RIGHT] */
    int cycle;       /* plan.pick_cycle */
    double cut_s, release_s;
    /* plan.pick_cost_flat: a reachable pair costs the least cost of its fruit over the
     * candidate stops of the config's row, [course_lo_m, course_hi_m] every step_m (m) */
    int flat;
    double course_lo_m, course_hi_m, step_m;
    double y_rel_min[2], y_rel_max[2];
} hv_ik_model_t;

/* Fill `ik` from the configuration and `model` on it; the reach spans come from
 * hv_pick_reach_span over each side's fruit area. HV_ERR_UNREACHABLE when an arm reaches
 * none of its area. */
hv_status_t hv_pick_model_ik(const hv_config_t *cfg, hv_ik_model_t *ik, hv_pick_model_t *model);

/* "cycle" or "one_way", with "_flat" under plan.pick_cost_flat: the plan file's
 * params.pick_time for a configuration. */
const char *hv_pick_model_name(const hv_config_t *cfg);

#ifdef __cplusplus
}
#endif
#endif /* HV_PICK_MODEL_H */
