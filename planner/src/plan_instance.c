/* Instance building (plan_instance.h): candidate stops and the sparse reachable pairs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/pick_model.h"
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

void hv_instance_params_from_config(const hv_config_t *cfg, const hv_pick_model_t *model,
                                    hv_instance_params_t *params)
{
    params->row_start_m = 0.0;
    params->row_length_m = cfg->row_length_m;
    params->stop_step_m = cfg->grid_step_m;
    params->stop_penalty_s = hv_config_stop_time_s(cfg);
    params->stop_margin_m =
        cfg->stops_beyond_ends
            ? hv_pick_margin_of_spans(model->y_rel_min, model->y_rel_max, cfg->grid_step_m)
            : 0.0;
    params->travel_time_s = hv_instance_params_course_m(params) / cfg->vehicle_speed_mps;
}

double hv_instance_params_course_m(const hv_instance_params_t *params)
{
    return params->row_length_m + 2.0 * params->stop_margin_m;
}

size_t hv_instance_params_stops(const hv_instance_params_t *pr)
{
    if (pr == NULL || !isfinite(pr->row_start_m) || !isfinite(pr->row_length_m) ||
        !isfinite(pr->stop_step_m) || pr->stop_step_m <= 0 || pr->row_length_m < 0 ||
        !isfinite(pr->stop_margin_m) || pr->stop_margin_m < 0) {
        return 0;
    }
    double n = floor(hv_instance_params_course_m(pr) / pr->stop_step_m + 0.5) + 1.0;
    if (n > 1e7) { /* 100 km at 1 cm: anything larger is a units mistake */
        return 0;
    }
    return (size_t)n;
}

const char *hv_instance_why_name(int why)
{
    return why == HV_WHY_ROW_END ? "row_end" : hv_pick_why_name(why);
}

void hv_instance_free(hv_instance_t *inst)
{
    if (inst != NULL) {
        free(inst->fruits);
        free(inst->stop_y_m);
        free(inst->pairs);
        free(inst->fruit_begin);
        free(inst->why);
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

/* Append one pair, growing the array by doubling. */
static hv_status_t push_pair(hv_instance_t *inst, size_t *cap, uint32_t f, uint32_t p,
                             double cost_s)
{
    if (inst->n_pairs == *cap) {
        hv_pair_t *np = realloc(inst->pairs, 2 * *cap * sizeof *np);
        if (np == NULL) {
            return HV_ERR_PLAN_NOMEM;
        }
        inst->pairs = np;
        *cap *= 2;
    }
    hv_pair_t *pr = &inst->pairs[inst->n_pairs++];
    pr->fruit = f;
    pr->stop = p;
    pr->cost_s = cost_s;
    return HV_OK;
}

/* The pairs of fruit f, and why it has none. Stop index k (may be negative or beyond the
 * candidates) is at y0 + k * step; only k in [k_lo, k_hi] can be within the arm's span.
 * Positions beyond the candidate stops are tried only to tell "row_end" from the rest. */
static hv_status_t fruit_pairs(hv_instance_t *inst, size_t *cap, const hv_pick_model_t *m,
                               const hv_instance_params_t *params, uint32_t f)
{
    const hv_fruit_t *fr = &inst->fruits[f];
    double y0 = params->row_start_m - params->stop_margin_m, step = params->stop_step_m;
    long k_lo = (long)ceil((fr->y_m - m->y_rel_max[fr->side] - y0) / step - 1e-9);
    long k_hi = (long)floor((fr->y_m - m->y_rel_min[fr->side] - y0) / step + 1e-9);
    long n = (long)inst->n_stops;
    int height = 0, yaw = 0, beyond = 0;
    for (int outside = 0; outside < 2 && inst->n_pairs == inst->fruit_begin[f]; ++outside) {
        for (long k = k_lo; k <= k_hi; ++k) {
            if ((k >= 0 && k < n) == outside) {
                continue;
            }
            double cost = 0.0;
            hv_pick_why_t why = HV_PICK_OK;
            double y = outside ? y0 + (double)k * step : inst->stop_y_m[k];
            if (m->cost(m->ctx, fr, y, &cost, &why) == HV_OK) {
                if (outside) {
                    beyond = 1;
                    break;
                }
                hv_status_t st = push_pair(inst, cap, f, (uint32_t)k, cost);
                if (st != HV_OK) {
                    return st;
                }
            } else {
                height |= why == HV_PICK_HEIGHT;
                yaw |= why == HV_PICK_YAW;
            }
        }
    }
    if (inst->n_pairs == inst->fruit_begin[f]) {
        inst->why[f] = beyond   ? HV_WHY_ROW_END
                       : height ? (unsigned char)HV_PICK_HEIGHT
                       : yaw    ? (unsigned char)HV_PICK_YAW
                                : (unsigned char)HV_PICK_DEPTH;
    }
    return HV_OK;
}

hv_status_t hv_instance_build(const hv_instance_params_t *params, const hv_fruit_t *fruits,
                              size_t n_fruits, const hv_pick_model_t *model, hv_instance_t *inst,
                              hv_diag_t *diag)
{
    if (params == NULL || (fruits == NULL && n_fruits > 0) || model == NULL ||
        model->cost == NULL || inst == NULL) {
        diag_set(diag, "args", "NULL argument");
        return HV_ERR_ARG;
    }
    memset(inst, 0, sizeof *inst);
    size_t n_stops = hv_instance_params_stops(params);
    if (n_stops == 0 || !isfinite(params->stop_penalty_s) || params->stop_penalty_s < 0 ||
        !isfinite(params->travel_time_s) || params->travel_time_s < 0) {
        diag_set(diag, "params", "row length, stop margin, stop step, tau or T_travel invalid");
        return HV_ERR_PLAN_PARAMS;
    }
    inst->n_fruits = n_fruits;
    inst->n_stops = n_stops;
    inst->stop_penalty_s = params->stop_penalty_s;
    inst->travel_time_s = params->travel_time_s;
    inst->fruits = malloc((n_fruits ? n_fruits : 1) * sizeof *inst->fruits);
    inst->stop_y_m = malloc(n_stops * sizeof *inst->stop_y_m);
    inst->fruit_begin = malloc((n_fruits + 1) * sizeof *inst->fruit_begin);
    inst->why = calloc(n_fruits ? n_fruits : 1, 1);
    size_t cap = 1024;
    inst->pairs = malloc(cap * sizeof *inst->pairs);
    if (inst->fruits == NULL || inst->stop_y_m == NULL || inst->fruit_begin == NULL ||
        inst->why == NULL || inst->pairs == NULL) {
        hv_instance_free(inst);
        diag_set(diag, "instance", "out of memory");
        return HV_ERR_PLAN_NOMEM;
    }
    if (n_fruits > 0) {
        memcpy(inst->fruits, fruits, n_fruits * sizeof *fruits);
    }
    for (size_t p = 0; p < n_stops; ++p) {
        inst->stop_y_m[p] =
            params->row_start_m - params->stop_margin_m + (double)p * params->stop_step_m;
    }
    for (size_t f = 0; f < n_fruits; ++f) {
        inst->fruit_begin[f] = inst->n_pairs;
        if (fruit_pairs(inst, &cap, model, params, (uint32_t)f) != HV_OK) {
            hv_instance_free(inst);
            diag_set(diag, "instance", "out of memory (pairs)");
            return HV_ERR_PLAN_NOMEM;
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
    sub->why = full->why ? calloc(full->n_fruits ? full->n_fruits : 1, 1) : NULL;
    if (sub->stop_y_m == NULL || sub->fruits == NULL || sub->fruit_begin == NULL ||
        sub->pairs == NULL || (full->why != NULL && sub->why == NULL)) {
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
        if (sub->why != NULL) {
            sub->why[nf] = full->why[f];
        }
        if (fruit_of_sub != NULL) {
            fruit_of_sub[nf] = (uint32_t)f;
        }
        ++nf;
    }
    sub->n_fruits = nf;
    sub->fruit_begin[nf] = sub->n_pairs;
    return HV_OK;
}
