/* Paper-sized planner instances for the MILP benchmark (DESIGN §2, §10).
 *
 * Pick costs come from the product's pick model: the exact IK and move time of the arms as
 * mounted by the configuration (hv_pick_model_ik). The paper's model: G one way home ->
 * fruit and tau = vehicle.stop_penalty (plan.pick_cycle taken as 0), N = 201 candidate stops
 * over the row (row.stops_beyond_ends taken as 0), so the solver is measured on the paper's
 * instances. Fruit is uniform in the canopy (docs/FRAMES.md).
 */
#ifndef HV_BENCH_INSTANCES_H
#define HV_BENCH_INSTANCES_H

#include <stddef.h>
#include <stdint.h>

#include "hv/config.h"
#include "hv/pick_model.h"
#include "hv/plan_instance.h"

typedef struct bench_model {
    hv_ik_model_t ik;
    hv_pick_model_t model; /* points at ik: do not copy */
} bench_model_t;

/* The pick model of the configuration. 0 on success, else a message on stderr. */
int bench_model_init(const hv_config_t *cfg, bench_model_t *m);

/* n_left + n_right fruits (ids L0.., R0..) uniform in the canopy of each side over
 * [0, cfg->row_length_m], from `seed`; malloc'd (free it), NULL when out of memory. */
hv_fruit_t *bench_fruits_make(const hv_config_t *cfg, size_t n_left, size_t n_right, uint64_t seed);

/* The instance of (n_left, n_right, seed): fruit uniform in the canopy of each side. */
int bench_instance_make(const hv_config_t *cfg, const bench_model_t *m, size_t n_left,
                        size_t n_right, uint64_t seed, hv_instance_t *inst);

#endif /* HV_BENCH_INSTANCES_H */
