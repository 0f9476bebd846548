/* Test support: synthetic cost tables (tiny_tables.h). */
#include "tiny_tables.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/file_io.h"

uint16_t tt_band_cost(hv_side_t side, double y_rel_m, uint32_t ix, uint32_t iz, uint32_t iyaw,
                      void *ctx)
{
    (void)side;
    (void)ix;
    (void)iyaw;
    const tt_band_t *b = ctx;
    double cm = fabs(y_rel_m) * 100.0;
    if (fabs(y_rel_m) > b->reach_m + 1e-9) {
        return HV_COST_UNREACHABLE;
    }
    return (uint16_t)(b->base_ms + (unsigned)lround(cm) * b->slope_ms_per_cm + iz * b->z_ms);
}

int tt_load_config(hv_config_t *cfg)
{
    const char *src = getenv("HV_SOURCE_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/config/harvest.cfg", src ? src : HV_TEST_SOURCE_DIR);
    char err[256];
    if (hv_config_load(path, cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    cfg->stops_beyond_ends = 0;
    cfg->pick_cycle = 0;
    return 0;
}

static hv_status_t table_cost(const void *ctx, const hv_fruit_t *fr, double stop_y_m,
                              double *cost_s, hv_pick_why_t *why)
{
    const hv_costtab_t *tab = ctx;
    uint16_t ms = 0;
    hv_status_t st =
        hv_costtab_lookup(&tab[fr->side], fr->x_m, fr->y_m - stop_y_m, fr->z_m, fr->yaw_rad, &ms);
    *cost_s = ms / 1000.0;
    *why = st == HV_OK ? HV_PICK_OK : HV_PICK_DEPTH;
    return st;
}

void tt_table_model(const hv_costtab_t tab[2], hv_pick_model_t *model)
{
    model->cost = table_cost;
    model->ctx = tab;
    for (int s = 0; s < 2; ++s) {
        const hv_axis_t *ay = &tab[s].grid.axis[HV_AX_Y];
        model->y_rel_min[s] = ay->origin;
        model->y_rel_max[s] = ay->origin + ay->step * (ay->count - 1);
    }
}

int tt_make_table(const hv_config_t *cfg, hv_side_t side, tt_cost_fn fn, void *ctx, uint8_t **buf,
                  size_t *len, hv_costtab_t *tab)
{
    hv_grid_t g;
    hv_config_grid(cfg, side, &g);
    size_t cells = hv_grid_cells(&g);
    uint16_t *costs = malloc(cells * sizeof *costs);
    size_t bytes = hv_costtab_file_bytes(&g);
    uint8_t *out = malloc(bytes);
    if (costs == NULL || out == NULL) {
        free(costs);
        free(out);
        return -1;
    }
    const uint32_t nx = g.axis[HV_AX_X].count, ny = g.axis[HV_AX_Y].count,
                   nz = g.axis[HV_AX_Z].count, nyaw = g.axis[HV_AX_YAW].count;
    for (uint32_t ix = 0; ix < nx; ++ix) {
        for (uint32_t iz = 0; iz < nz; ++iz) {
            for (uint32_t iw = 0; iw < nyaw; ++iw) {
                for (uint32_t iy = 0; iy < ny; ++iy) {
                    double y = g.axis[HV_AX_Y].origin + g.axis[HV_AX_Y].step * iy;
                    costs[((size_t)(ix * nz + iz) * nyaw + iw) * ny + iy] =
                        fn(side, y, ix, iz, iw, ctx);
                }
            }
        }
    }
    hv_arm_t arm;
    hv_config_arm(cfg, side, &arm);
    hv_diag_t d;
    int rc = 0;
    if (hv_costtab_write(&g, &arm, 1u, costs, out, bytes, &d) != HV_OK ||
        hv_costtab_open(tab, out, bytes, &d) != HV_OK) {
        fprintf(stderr, "tiny table: %s: %s\n", d.field, d.message);
        rc = -1;
        free(out);
        out = NULL;
    }
    free(costs);
    *buf = out;
    *len = bytes;
    return rc;
}

int tt_fixture_init(tt_fixture_t *fx, tt_cost_fn fn, void *ctx)
{
    memset(fx, 0, sizeof *fx);
    if (tt_load_config(&fx->cfg) != 0) {
        return -1;
    }
    for (int s = 0; s < 2; ++s) {
        size_t len;
        if (tt_make_table(&fx->cfg, (hv_side_t)s, fn, ctx, &fx->buf[s], &len, &fx->tab[s]) != 0) {
            return -1;
        }
    }
    tt_table_model(fx->tab, &fx->model);
    return 0;
}

void tt_fixture_free(tt_fixture_t *fx)
{
    free(fx->buf[0]);
    free(fx->buf[1]);
    fx->buf[0] = fx->buf[1] = NULL;
}

hv_fruit_t tt_fruit(const char *id, hv_side_t side, double y_m, double z_m)
{
    hv_fruit_t f;
    memset(&f, 0, sizeof f);
    snprintf(f.id, sizeof f.id, "%s", id);
    f.side = side;
    f.x_m = side == HV_SIDE_LEFT ? -0.42 : 0.42;
    f.y_m = y_m;
    f.z_m = z_m;
    return f;
}
