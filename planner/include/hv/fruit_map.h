/* Fruit map (CSV, docs/FRAMES.md): header `id,side,x,y,z,yaw`, one fruit per line, SI units.
 *
 * Strict: each bad input has its own code (plan_status.h) and a one-line message
 * "<file>:<line>: <field>: <what>". Empty lines are skipped; everything else must parse.
 */
#ifndef HV_FRUIT_MAP_H
#define HV_FRUIT_MAP_H

#include <stddef.h>

#include "hv/config.h"
#include "hv/cost_table.h"
#include "hv/plan_instance.h"
#include "hv/plan_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_fruitmap {
    size_t n;
    hv_fruit_t *fruits; /* in file order */
} hv_fruitmap_t;

/* What a fruit's coordinates must lie in: x, z, yaw inside the cost-table grid of its side
 * (nearest-cell rule, as lookups), y inside [y_min_m, y_max_m] (the row). */
typedef struct hv_fruitmap_limits {
    hv_grid_t grid[2]; /* indexed by hv_side_t */
    double y_min_m, y_max_m;
} hv_fruitmap_limits_t;

/* Grids from hv_config_grid(), y over [row_start_m, row_start_m + row_length_m]. */
void hv_fruitmap_limits_from_config(const hv_config_t *cfg, double row_start_m, double row_length_m,
                                    hv_fruitmap_limits_t *lim);

/* Parse `len` bytes of CSV. `name` names the source in messages. `lim` may be NULL (no
 * range check). Codes: HV_ERR_PLAN_MAP_* ; HV_ERR_PLAN_NOMEM. On error *map is empty. */
hv_status_t hv_fruitmap_parse(const char *text, size_t len, const char *name,
                              const hv_fruitmap_limits_t *lim, hv_fruitmap_t *map, char *err,
                              size_t errlen);

/* Read and parse a file (HV_ERR_IO when it cannot be read). */
hv_status_t hv_fruitmap_load(const char *path, const hv_fruitmap_limits_t *lim, hv_fruitmap_t *map,
                             char *err, size_t errlen);

void hv_fruitmap_free(hv_fruitmap_t *map);

/* Write `n` fruits to `path` in this format, atomically (hv_file_write_atomic), each number
 * with 17 significant digits so that hv_fruitmap_load reads back the same doubles.
 * HV_ERR_IO with `err` naming the file; HV_ERR_PLAN_NOMEM. */
hv_status_t hv_fruitmap_save(const char *path, const hv_fruit_t *fruits, size_t n, char *err,
                             size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* HV_FRUIT_MAP_H */
