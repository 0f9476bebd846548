/* Instance building (plan_instance.h): candidate stops and the sparse reachable pairs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/plan_instance.h"
#include "hv/plan_status.h"

static void diag_set(hv_diag_t *d, const char *field, const char *msg)
{
    if (d != NULL) {
        snprintf(d->field, sizeof d->field, "%s", field);
        snprintf(d->message, sizeof d->message, "%s", msg);
        d->line = 0;
    }
}

void hv_instance_params_from_config(const hv_config_t *cfg, hv_instance_params_t *params)
{
    params->row_start_m = 0.0;
    params->row_length_m = cfg->row_length_m;
    params->stop_step_m = cfg->grid_step_m;
    params->stop_penalty_s = cfg->stop_penalty_s;
    params->travel_time_s = hv_config_travel_time_s(cfg);
}

size_t hv_instance_params_stops(const hv_instance_params_t *pr)
{
    if (pr == NULL || !isfinite(pr->row_start_m) || !isfinite(pr->row_length_m) ||
        !isfinite(pr->stop_step_m) || pr->stop_step_m <= 0 || pr->row_length_m < 0) {
        return 0;
    }
    double n = floor(pr->row_length_m / pr->stop_step_m + 0.5) + 1.0;
    if (n > 1e7) { /* 100 km at 1 cm: anything larger is a units mistake */
        return 0;
    }
    return (size_t)n;
}

void hv_instance_free(hv_instance_t *inst)
{
    if (inst != NULL) {
        free(inst->fruits);
        free(inst->stop_y_m);
        free(inst->pairs);
        free(inst->fruit_begin);
        memset(inst, 0, sizeof *inst);
    }
}

size_t hv_instance_unreachable_count(const hv_instance_t *inst)
{
    size_t n = 0;
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        n += inst->fruit_begin[f] == inst->fruit_begin[f + 1];
    }
    return n;
}

hv_status_t hv_assignment_alloc(hv_assignment_t *a, size_t n_fruits)
{
    if (a == NULL) {
        return HV_ERR_ARG;
    }
    a->n_fruits = n_fruits;
    a->fruit_stop = malloc((n_fruits ? n_fruits : 1) * sizeof *a->fruit_stop);
    if (a->fruit_stop == NULL) {
        a->n_fruits = 0;
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < n_fruits; ++f) {
        a->fruit_stop[f] = HV_NO_STOP;
    }
    return HV_OK;
}

void hv_assignment_free(hv_assignment_t *a)
{
    if (a != NULL) {
        free(a->fruit_stop);
        a->fruit_stop = NULL;
        a->n_fruits = 0;
    }
}

hv_status_t hv_instance_build(const hv_instance_params_t *params, const hv_fruit_t *fruits,
                              size_t n_fruits, const hv_costtab_t *left,
                              const hv_costtab_t *right, hv_instance_t *inst,
                              hv_diag_t *diag)
{
    if (params == NULL || (fruits == NULL && n_fruits > 0) || left == NULL || right == NULL ||
        inst == NULL) {
        diag_set(diag, "args", "NULL argument");
        return HV_ERR_ARG;
    }
    memset(inst, 0, sizeof *inst);
    size_t n_stops = hv_instance_params_stops(params);
    if (n_stops == 0 || !isfinite(params->stop_penalty_s) || params->stop_penalty_s < 0 ||
        !isfinite(params->travel_time_s) || params->travel_time_s < 0) {
        diag_set(diag, "params", "row length, stop step, tau or T_travel invalid");
        return HV_ERR_PLAN_PARAMS;
    }
    inst->n_fruits = n_fruits;
    inst->n_stops = n_stops;
    inst->stop_penalty_s = params->stop_penalty_s;
    inst->travel_time_s = params->travel_time_s;
    inst->fruits = malloc((n_fruits ? n_fruits : 1) * sizeof *inst->fruits);
    inst->stop_y_m = malloc(n_stops * sizeof *inst->stop_y_m);
    inst->fruit_begin = malloc((n_fruits + 1) * sizeof *inst->fruit_begin);
    size_t cap = 1024;
    inst->pairs = malloc(cap * sizeof *inst->pairs);
    if (inst->fruits == NULL || inst->stop_y_m == NULL || inst->fruit_begin == NULL ||
        inst->pairs == NULL) {
        hv_instance_free(inst);
        diag_set(diag, "instance", "out of memory");
        return HV_ERR_PLAN_NOMEM;
    }
    if (n_fruits > 0) {
        memcpy(inst->fruits, fruits, n_fruits * sizeof *fruits);
    }
    for (size_t p = 0; p < n_stops; ++p) {
        inst->stop_y_m[p] = params->row_start_m + (double)p * params->stop_step_m;
    }

    for (size_t f = 0; f < n_fruits; ++f) {
        inst->fruit_begin[f] = inst->n_pairs;
        const hv_fruit_t *fr = &fruits[f];
        const hv_costtab_t *tab = fr->side == HV_SIDE_LEFT ? left : right;
        const uint8_t *row = NULL;
        if (hv_costtab_row(tab, fr->x_m, fr->z_m, fr->yaw_rad, &row) != HV_OK) {
            continue; /* outside the table's x/z/yaw grid: no stop reaches it */
        }
        const hv_axis_t *ay = &tab->grid.axis[HV_AX_Y];
        /* Only stops whose y_rel can fall inside the y-axis are visited (+-1 stop margin;
         * hv_axis_index has the last word on each). */
        double y_lo = fr->y_m - (ay->origin + ay->step * (ay->count - 1)) - ay->step;
        double y_hi = fr->y_m - ay->origin + ay->step;
        double p_lo = floor((y_lo - params->row_start_m) / params->stop_step_m) - 1;
        double p_hi = ceil((y_hi - params->row_start_m) / params->stop_step_m) + 1;
        size_t p0 = p_lo < 0 ? 0 : (size_t)p_lo;
        size_t p1 = p_hi >= (double)n_stops ? n_stops - 1 : (p_hi < 0 ? 0 : (size_t)p_hi);
        for (size_t p = p0; p <= p1 && p_hi >= 0; ++p) {
            long iy = hv_axis_index(ay, fr->y_m - inst->stop_y_m[p]);
            if (iy < 0) {
                continue;
            }
            uint16_t c = hv_costtab_row_at(row, (uint32_t)iy);
            if (c == HV_COST_UNREACHABLE) {
                continue;
            }
            if (inst->n_pairs == cap) {
                cap *= 2;
                hv_pair_t *np = realloc(inst->pairs, cap * sizeof *np);
                if (np == NULL) {
                    hv_instance_free(inst);
                    diag_set(diag, "instance", "out of memory (pairs)");
                    return HV_ERR_PLAN_NOMEM;
                }
                inst->pairs = np;
            }
            hv_pair_t *pr = &inst->pairs[inst->n_pairs++];
            pr->fruit = (uint32_t)f;
            pr->stop = (uint32_t)p;
            pr->cost_s = (double)c / 1000.0; /* table holds ms */
        }
    }
    inst->fruit_begin[n_fruits] = inst->n_pairs;
    return HV_OK;
}

hv_status_t hv_instance_subset(const hv_instance_t *full, size_t stop_begin, size_t stop_end,
                               const unsigned char *keep_fruit, int drop_unreachable,
                               hv_instance_t *sub, uint32_t *fruit_of_sub)
{
    if (full == NULL || sub == NULL || stop_begin > stop_end || stop_end > full->n_stops) {
        return HV_ERR_ARG;
    }
    memset(sub, 0, sizeof *sub);
    size_t ns = stop_end - stop_begin;
    sub->n_stops = ns;
    sub->stop_penalty_s = full->stop_penalty_s;
    sub->travel_time_s = full->travel_time_s;
    sub->stop_y_m = malloc((ns ? ns : 1) * sizeof *sub->stop_y_m);
    sub->fruits = malloc((full->n_fruits ? full->n_fruits : 1) * sizeof *sub->fruits);
    sub->fruit_begin = malloc((full->n_fruits + 1) * sizeof *sub->fruit_begin);
    sub->pairs = malloc((full->n_pairs ? full->n_pairs : 1) * sizeof *sub->pairs);
    if (sub->stop_y_m == NULL || sub->fruits == NULL || sub->fruit_begin == NULL ||
        sub->pairs == NULL) {
        hv_instance_free(sub);
        return HV_ERR_PLAN_NOMEM;
    }
    if (ns > 0) {
        memcpy(sub->stop_y_m, full->stop_y_m + stop_begin, ns * sizeof *sub->stop_y_m);
    }
    size_t nf = 0;
    for (size_t f = 0; f < full->n_fruits; ++f) {
        if (keep_fruit != NULL && !keep_fruit[f]) {
            continue;
        }
        size_t first = sub->n_pairs;
        for (size_t k = full->fruit_begin[f]; k < full->fruit_begin[f + 1]; ++k) {
            const hv_pair_t *pr = &full->pairs[k];
            if (pr->stop >= stop_begin && pr->stop < stop_end) {
                hv_pair_t *q = &sub->pairs[sub->n_pairs++];
                q->fruit = (uint32_t)nf;
                q->stop = (uint32_t)(pr->stop - stop_begin);
                q->cost_s = pr->cost_s;
            }
        }
        if (drop_unreachable && sub->n_pairs == first) {
            continue;
        }
        sub->fruit_begin[nf] = first;
        sub->fruits[nf] = full->fruits[f];
        if (fruit_of_sub != NULL) {
            fruit_of_sub[nf] = (uint32_t)f;
        }
        ++nf;
    }
    sub->n_fruits = nf;
    sub->fruit_begin[nf] = sub->n_pairs;
    return HV_OK;
}
