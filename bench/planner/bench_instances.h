/* Paper-sized planner instances for the MILP benchmark (DESIGN §2, §10), in two models.
 *
 * The product's model (BENCH_MODEL_PRODUCT) is the configuration's as harvest-plan builds
 * it: the exact IK pick model of hv_pick_model_ik, hv_instance_params_from_config (stops
 * beyond the row's ends with row.stops_beyond_ends, T_travel over the whole course), pick
 * costs of the whole cycle and tau = the drive's v / a with plan.pick_cycle. The paper's
 * model (BENCH_MODEL_PAPER) is the same arms with the paper's choices: G one way home ->
 * fruit, tau = vehicle.stop_penalty (plan.pick_cycle = 0) and N = 201 candidate stops over
 * the row (row.stops_beyond_ends = 0). Fruit is uniform in the canopy (docs/FRAMES.md).
 */
#ifndef HV_BENCH_INSTANCES_H
#define HV_BENCH_INSTANCES_H

#include <stddef.h>
#include <stdint.h>

#include "hv/config.h"
#include "hv/pick_model.h"
#include "hv/plan_instance.h"

typedef enum bench_model_kind { BENCH_MODEL_PRODUCT, BENCH_MODEL_PAPER } bench_model_kind_t;

typedef struct bench_model {
    bench_model_kind_t kind;
    hv_config_t cfg; /* the configuration as the model reads it */
    hv_ik_model_t ik;
    hv_pick_model_t model; /* points at ik: do not copy */
} bench_model_t;

/* "product" or "paper". */
const char *bench_model_name(bench_model_kind_t kind);

/* The pick model of the configuration in the model `kind`. 0 on success, else a message
 * on stderr. */
int bench_model_init(const hv_config_t *cfg, bench_model_kind_t kind, bench_model_t *m);

/* n_left + n_right fruits (ids L0.., R0..) uniform in the canopy of each side over
 * [0, cfg->row_length_m], from `seed`; malloc'd (free it), NULL when out of memory. */
hv_fruit_t *bench_fruits_make(const hv_config_t *cfg, size_t n_left, size_t n_right, uint64_t seed);

/* The instance of (n_left, n_right, seed) in model m: fruit uniform in the canopy of each
 * side (the same fruit in either model). */
int bench_instance_make(const bench_model_t *m, size_t n_left, size_t n_right, uint64_t seed,
                        hv_instance_t *inst);

#endif /* HV_BENCH_INSTANCES_H */
