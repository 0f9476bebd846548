/* planner_synth_tables: write synthetic left/right cost tables (band model, tiny_tables.h)
 * on a configuration's grid, for the CLI tests.
 * usage: planner_synth_tables CONFIG OUT_DIR [REACH_M] */
#include <stdio.h>
#include <stdlib.h>

#include "hv/file_io.h"
#include "tiny_tables.h"

/* The band model with nothing reachable above z = 0.75 m, so tests can place a fruit
 * that no stop reaches. */
typedef struct capped {
    double z0_m, dz_m; /* the grid's z axis */
    tt_band_t band;
} capped_t;

static uint16_t capped_band(hv_side_t side, double y_rel, uint32_t ix, uint32_t iz, uint32_t iw,
                            void *ctx)
{
    const double z_top_m = 0.75;
    capped_t *c = ctx;
    if (c->z0_m + c->dz_m * iz > z_top_m + 1e-9) {
        return HV_COST_UNREACHABLE;
    }
    return tt_band_cost(side, y_rel, ix, iz, iw, &c->band);
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 4) {
        fprintf(stderr, "usage: planner_synth_tables CONFIG OUT_DIR [REACH_M]\n"
                        "writes OUT_DIR/left.bin and OUT_DIR/right.bin (band model, reach REACH_M\n"
                        "(default 0.30) along the row, nothing above z = 0.75 m)\n");
        return 2;
    }
    hv_config_t cfg;
    char err[512];
    if (hv_config_load(argv[1], &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    char *end = NULL;
    double reach = argc == 4 ? strtod(argv[3], &end) : 0.30;
    if (argc == 4 && (end == argv[3] || *end != '\0' || !(reach > 0))) {
        fprintf(stderr, "planner_synth_tables: REACH_M: expected a positive number\n");
        return 2;
    }
    hv_grid_t g;
    hv_config_grid(&cfg, HV_SIDE_LEFT, &g);
    capped_t ctx = {g.axis[HV_AX_Z].origin, g.axis[HV_AX_Z].step, {reach, 2000, 15, 10}};
    for (int side = 0; side < 2; ++side) {
        uint8_t *buf = NULL;
        size_t len = 0;
        hv_costtab_t tab;
        if (tt_make_table(&cfg, (hv_side_t)side, capped_band, &ctx, &buf, &len, &tab) != 0) {
            return 1;
        }
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.bin", argv[2], side == 0 ? "left" : "right");
        hv_status_t st = hv_file_write_atomic(path, buf, len, err, sizeof err);
        free(buf);
        if (st != HV_OK) {
            fprintf(stderr, "%s\n", err);
            return 1;
        }
    }
    return 0;
}
