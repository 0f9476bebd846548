/* Paper-sized planner instances for the MILP benchmark (DESIGN §2, §10).
 *
 * Cost tables come from the real arm model: every cell of the configuration's grid is
 * hv_scara_pick_cost of the arm as mounted by config/harvest.cfg, written and re-opened
 * through the cost-table file format, so the planner reads them with the nearest-cell
 * convention it uses on real tables. Fruit is uniform in the canopy (docs/FRAMES.md).
 */
#ifndef HV_BENCH_INSTANCES_H
#define HV_BENCH_INSTANCES_H

#include <stddef.h>
#include <stdint.h>

#include "hv/config.h"
#include "hv/cost_table.h"
#include "hv/plan_instance.h"

typedef struct bench_tables {
    uint8_t *buf[2];
    hv_costtab_t tab[2]; /* [HV_SIDE_LEFT], [HV_SIDE_RIGHT] */
} bench_tables_t;

/* Build both tables from the arm model. 0 on success, else a message on stderr. */
int bench_tables_build(const hv_config_t *cfg, bench_tables_t *t);
void bench_tables_free(bench_tables_t *t);

/* The instance of (n_left, n_right, seed): fruit uniform in the canopy of each side. */
int bench_instance_make(const hv_config_t *cfg, const bench_tables_t *t, size_t n_left,
                        size_t n_right, uint64_t seed, hv_instance_t *inst);

#endif /* HV_BENCH_INSTANCES_H */
