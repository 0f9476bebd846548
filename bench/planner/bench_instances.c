/* Paper-sized planner instances in the product's and the paper's model (bench_instances.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_instances.h"

const char *bench_model_name(bench_model_kind_t kind)
{
    return kind == BENCH_MODEL_PAPER ? "paper" : "product";
}

int bench_model_init(const hv_config_t *cfg, bench_model_kind_t kind, bench_model_t *m)
{
    m->kind = kind;
    m->cfg = *cfg;
    if (kind == BENCH_MODEL_PAPER) {
        m->cfg.pick_cycle = 0;
        m->cfg.stops_beyond_ends = 0;
    }
    hv_status_t st = hv_pick_model_ik(&m->cfg, &m->ik, &m->model);
    if (st != HV_OK) {
        fprintf(stderr, "bench: pick model: %s\n", hv_status_name(st));
        return -1;
    }
    return 0;
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

hv_fruit_t *bench_fruits_make(const hv_config_t *cfg, size_t n_left, size_t n_right, uint64_t seed)
{
    size_t n = n_left + n_right;
    hv_fruit_t *fr = calloc(n + 1, sizeof *fr);
    if (fr == NULL) {
        return NULL;
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
    return fr;
}

int bench_instance_make(const bench_model_t *m, size_t n_left, size_t n_right, uint64_t seed,
                        hv_instance_t *inst)
{
    size_t n = n_left + n_right;
    hv_fruit_t *fr = bench_fruits_make(&m->cfg, n_left, n_right, seed);
    if (fr == NULL) {
        return -1;
    }
    hv_instance_params_t par;
    hv_instance_params_from_config(&m->cfg, &m->model, &par);
    hv_diag_t diag;
    hv_status_t st = hv_instance_build(&par, fr, n, &m->model, inst, &diag);
    free(fr);
    if (st != HV_OK) {
        fprintf(stderr, "bench: instance: %s: %s\n", diag.field, diag.message);
        return -1;
    }
    return 0;
}
