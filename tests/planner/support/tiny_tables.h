/* Test support: synthetic cost tables on the configuration's real grid, with costs from a
 * hand-chosen function, so tests know every cost (and brute force can check optima). */
#ifndef HV_TEST_TINY_TABLES_H
#define HV_TEST_TINY_TABLES_H

#include <stddef.h>
#include <stdint.h>

#include "hv/config.h"
#include "hv/cost_table.h"

/* Cost (ms, or HV_COST_UNREACHABLE) of a cell; y_rel_m is the cell's y value. */
typedef uint16_t (*tt_cost_fn)(hv_side_t side, double y_rel_m, uint32_t ix, uint32_t iz,
                               uint32_t iyaw, void *ctx);

/* The band model: reachable iff |y_rel| <= reach_m (+ half a cell), cost =
 * base_ms + slope_ms_per_cm * |y_rel in cm| + z_ms * iz. */
typedef struct tt_band {
    double reach_m;
    unsigned base_ms, slope_ms_per_cm, z_ms;
} tt_band_t;
uint16_t tt_band_cost(hv_side_t side, double y_rel_m, uint32_t ix, uint32_t iz, uint32_t iyaw,
                      void *ctx);

/* Load config/harvest.cfg from $HV_SOURCE_DIR (or the path compiled in), with the paper's
 * model: row.stops_beyond_ends = 0 (the tests' instances lay their stops over the row
 * alone) and plan.pick_cycle = 0 (costs one way, tau = vehicle.stop_penalty). 0 on success. */
int tt_load_config(hv_config_t *cfg);

/* Build a table of `side` on the config's grid: *buf (malloc'd, free it) holds the file
 * bytes (*len), *tab is opened on it. 0 on success. */
int tt_make_table(const hv_config_t *cfg, hv_side_t side, tt_cost_fn fn, void *ctx, uint8_t **buf,
                  size_t *len, hv_costtab_t *tab);

#include "hv/pick_model.h"
/* A pick model whose costs are the tables' nearest cells (tab[HV_SIDE_LEFT], [RIGHT]; they
 * must outlive the model); a fruit no cell reaches is "depth". */
void tt_table_model(const hv_costtab_t tab[2], hv_pick_model_t *model);

/* Config + both tables + the model on them, for a test binary (do not copy it: the model
 * points at its tables). */
typedef struct tt_fixture {
    hv_config_t cfg;
    uint8_t *buf[2];
    hv_costtab_t tab[2]; /* [HV_SIDE_LEFT], [HV_SIDE_RIGHT] */
    hv_pick_model_t model;
} tt_fixture_t;
int tt_fixture_init(tt_fixture_t *fx, tt_cost_fn fn, void *ctx);
void tt_fixture_free(tt_fixture_t *fx);

#include "hv/plan_instance.h"
/* A fruit at x = -+0.42 (by side), yaw 0. */
hv_fruit_t tt_fruit(const char *id, hv_side_t side, double y_m, double z_m);

#endif /* HV_TEST_TINY_TABLES_H */
