/* Paper-sized planner instances from the real arm model (bench_instances.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_instances.h"

static double axis_value(const hv_axis_t *a, uint32_t i) { return a->origin + a->step * (double)i; }

int bench_tables_build(const hv_config_t *cfg, bench_tables_t *t)
{
    memset(t, 0, sizeof *t);
    for (int sd = 0; sd < 2; ++sd) {
        hv_side_t side = sd ? HV_SIDE_RIGHT : HV_SIDE_LEFT;
        hv_arm_t arm;
        hv_grid_t g;
        hv_config_arm(cfg, side, &arm);
        hv_config_grid(cfg, side, &g);
        size_t cells = hv_grid_cells(&g);
        uint16_t *ms = malloc(cells * sizeof *ms);
        size_t bytes = hv_costtab_file_bytes(&g);
        t->buf[sd] = malloc(bytes);
        if (ms == NULL || t->buf[sd] == NULL || cells == 0) {
            free(ms);
            fprintf(stderr, "bench: out of memory for the cost table\n");
            return -1;
        }
        const hv_axis_t *ax = g.axis;
        for (uint32_t ix = 0; ix < ax[HV_AX_X].count; ++ix) {
            for (uint32_t iz = 0; iz < ax[HV_AX_Z].count; ++iz) {
                for (uint32_t iw = 0; iw < ax[HV_AX_YAW].count; ++iw) {
                    for (uint32_t iy = 0; iy < ax[HV_AX_Y].count; ++iy) {
                        hv_pose_t pose = {axis_value(&ax[HV_AX_X], ix),
                                          axis_value(&ax[HV_AX_Y], iy),
                                          axis_value(&ax[HV_AX_Z], iz),
                                          hv_side_normal_heading(side) +
                                              axis_value(&ax[HV_AX_YAW], iw)};
                        double c;
                        size_t cell =
                            (((size_t)ix * ax[HV_AX_Z].count + iz) * ax[HV_AX_YAW].count + iw) *
                                ax[HV_AX_Y].count + iy;
                        if (hv_scara_pick_cost(&arm, &pose, &c, NULL) != HV_OK) {
                            ms[cell] = HV_COST_UNREACHABLE;
                        } else {
                            double v = round(c * 1000.0);
                            ms[cell] = (uint16_t)(v > HV_COST_MAX_MS ? HV_COST_MAX_MS : v);
                        }
                    }
                }
            }
        }
        hv_diag_t diag;
        hv_status_t st = hv_costtab_write(&g, &arm, 1u, ms, t->buf[sd], bytes, &diag);
        free(ms);
        if (st == HV_OK) {
            st = hv_costtab_open(&t->tab[sd], t->buf[sd], bytes, &diag);
        }
        if (st == HV_OK) {
            st = hv_costtab_expect(&t->tab[sd], side, &g, &diag);
        }
        if (st != HV_OK) {
            fprintf(stderr, "bench: cost table %s: %s: %s\n", sd ? "right" : "left", diag.field,
                    diag.message);
            return -1;
        }
    }
    return 0;
}

void bench_tables_free(bench_tables_t *t)
{
    free(t->buf[0]);
    free(t->buf[1]);
    memset(t, 0, sizeof *t);
}

/* splitmix64: a reproducible stream per seed */
static double uniform(uint64_t *s, double lo, double hi)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return lo + (hi - lo) * ((double)(z >> 11) * 0x1.0p-53);
}

int bench_instance_make(const hv_config_t *cfg, const bench_tables_t *t, size_t n_left,
                        size_t n_right, uint64_t seed, hv_instance_t *inst)
{
    size_t n = n_left + n_right;
    hv_fruit_t *fr = calloc(n + 1, sizeof *fr);
    if (fr == NULL) {
        return -1;
    }
    uint64_t s = seed * 1000003u + 17u;
    double x0 = cfg->aisle_width_m / 2, x1 = x0 + cfg->canopy_depth_m;
    double z0 = cfg->canopy_z_min_m, z1 = z0 + cfg->canopy_height_m;
    for (size_t i = 0; i < n; ++i) {
        int right = i >= n_left;
        snprintf(fr[i].id, sizeof fr[i].id, "%c%zu", right ? 'R' : 'L', right ? i - n_left : i);
        fr[i].side = right ? HV_SIDE_RIGHT : HV_SIDE_LEFT;
        double x = uniform(&s, x0, x1);
        fr[i].x_m = right ? x : -x;
        fr[i].y_m = uniform(&s, 0.0, cfg->row_length_m);
        fr[i].z_m = uniform(&s, z0, z1);
        fr[i].yaw_rad = uniform(&s, -cfg->pick_yaw_max_rad, cfg->pick_yaw_max_rad);
    }
    hv_instance_params_t par;
    hv_instance_params_from_config(cfg, &par);
    hv_diag_t diag;
    hv_status_t st = hv_instance_build(&par, fr, n, &t->tab[0], &t->tab[1], inst, &diag);
    free(fr);
    if (st != HV_OK) {
        fprintf(stderr, "bench: instance: %s: %s\n", diag.field, diag.message);
        return -1;
    }
    return 0;
}
