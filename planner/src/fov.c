/* FOV baseline (baselines.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/fov.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* Candidate stop nearest to y (stops ascending). */
static uint32_t nearest_stop(const hv_instance_t *inst, double y)
{
    size_t lo = 0, hi = inst->n_stops; /* first stop with stop_y >= y */
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (inst->stop_y_m[mid] < y) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    if (lo == inst->n_stops) {
        return (uint32_t)(inst->n_stops - 1);
    }
    if (lo > 0 && y - inst->stop_y_m[lo - 1] <= inst->stop_y_m[lo] - y) {
        return (uint32_t)(lo - 1);
    }
    return (uint32_t)lo;
}

void hv_fov_params_from_config(const hv_config_t *cfg, hv_fov_params_t *params)
{
    double half = 0.5 * cfg->base_spacing_m;
    params->width_m = cfg->fov_width_m;
    params->centre_y_m[HV_SIDE_LEFT] = half + cfg->fov_offset_m;
    params->centre_y_m[HV_SIDE_RIGHT] = -half - cfg->fov_offset_m;
}

hv_status_t hv_fov_solve(const hv_instance_t *inst, double fov_width_m, hv_assignment_t *out,
                         hv_fov_stats_t *stats)
{
    hv_fov_params_t p = {fov_width_m, {0.0, 0.0}};
    return hv_fov_solve_params(inst, &p, out, stats);
}

/* The fruit's window: where its side's camera sees it, from position s0. */
static size_t window_of(const hv_fruit_t *fr, const hv_fov_params_t *p, double s0)
{
    double k = floor((fr->y_m - p->centre_y_m[fr->side] - s0 + 0.5 * p->width_m) / p->width_m);
    return k > 0 ? (size_t)k : 0; /* >= 0 by s0's choice; guards the rounding */
}

hv_status_t hv_fov_solve_params(const hv_instance_t *inst, const hv_fov_params_t *params,
                                hv_assignment_t *out, hv_fov_stats_t *stats)
{
    if (inst == NULL || params == NULL || out == NULL || out->n_fruits != inst->n_fruits ||
        !isfinite(params->width_m) || params->width_m <= 0 || !isfinite(params->centre_y_m[0]) ||
        !isfinite(params->centre_y_m[1]) || inst->n_stops == 0) {
        return HV_ERR_ARG;
    }
    const double w = params->width_m;
    hv_fov_stats_t stt;
    memset(&stt, 0, sizeof stt);
    /* s0: the first vehicle position at which a window starts at its side's first fruit */
    double s0 = INFINITY;
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        out->fruit_stop[f] = HV_NO_STOP;
        if (inst->fruit_begin[f] != inst->fruit_begin[f + 1]) {
            const hv_fruit_t *fr = &inst->fruits[f];
            s0 = fmin(s0, fr->y_m - params->centre_y_m[fr->side] + 0.5 * w);
        }
    }
    if (s0 == INFINITY) { /* nothing reachable: an empty plan */
        if (stats) {
            *stats = stt;
        }
        return HV_OK;
    }
    size_t nw = 0;
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (inst->fruit_begin[f] != inst->fruit_begin[f + 1]) {
            size_t k = window_of(&inst->fruits[f], params, s0);
            nw = k + 1 > nw ? k + 1 : nw;
        }
    }
    uint32_t *wstop = malloc(nw * sizeof *wstop);
    unsigned char *used = calloc(inst->n_stops, 1);
    if (wstop == NULL || used == NULL) {
        free(wstop);
        free(used);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t k = 0; k < nw; ++k) {
        wstop[k] = nearest_stop(inst, s0 + (double)k * w);
    }
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (inst->fruit_begin[f] == inst->fruit_begin[f + 1]) {
            continue;
        }
        const hv_fruit_t *fr = &inst->fruits[f];
        size_t k = window_of(fr, params, s0);
        double c;
        if (hv_instance_pair_cost(inst, (uint32_t)f, wstop[k], &c) == HV_OK) {
            out->fruit_stop[f] = wstop[k];
            continue;
        }
        stt.moved++;
        /* nearest window stop that reaches it (later one on a tie) */
        double best_d = INFINITY;
        uint32_t best = HV_NO_STOP;
        for (size_t q = 0; q < nw; ++q) {
            if (hv_instance_pair_cost(inst, (uint32_t)f, wstop[q], &c) != HV_OK) {
                continue;
            }
            double d = fabs(inst->stop_y_m[wstop[q]] - fr->y_m);
            if (d <= best_d) {
                best_d = d;
                best = wstop[q];
            }
        }
        if (best != HV_NO_STOP) {
            out->fruit_stop[f] = best;
            continue;
        }
        /* an extra stop: the nearest reaching candidate stop, cheaper on a tie */
        double best_c = INFINITY;
        for (size_t k2 = inst->fruit_begin[f]; k2 < inst->fruit_begin[f + 1]; ++k2) {
            const hv_pair_t *pr = &inst->pairs[k2];
            double d = fabs(inst->stop_y_m[pr->stop] - fr->y_m);
            if (d < best_d - 1e-12 || (fabs(d - best_d) <= 1e-12 && pr->cost_s < best_c)) {
                best_d = d;
                best_c = pr->cost_s;
                best = pr->stop;
            }
        }
        if (!used[best]) {
            stt.extra_stops++;
        }
        used[best] = 1; /* later fruits in the same situation share this stop */
        out->fruit_stop[f] = best;
    }
    /* extra_stops above counts distinct extra stops only when they are not window stops */
    memset(used, 0, inst->n_stops);
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (out->fruit_stop[f] != HV_NO_STOP && !used[out->fruit_stop[f]]) {
            used[out->fruit_stop[f]] = 1;
            stt.stops++;
        }
    }
    stt.windows = nw;
    free(wstop);
    free(used);
    if (stats) {
        *stats = stt;
    }
    return HV_OK;
}
