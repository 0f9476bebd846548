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

hv_status_t hv_fov_solve(const hv_instance_t *inst, double fov_width_m, hv_assignment_t *out,
                         hv_fov_stats_t *stats)
{
    if (inst == NULL || out == NULL || out->n_fruits != inst->n_fruits || !isfinite(fov_width_m) ||
        fov_width_m <= 0 || inst->n_stops == 0) {
        return HV_ERR_ARG;
    }
    hv_fov_stats_t stt;
    memset(&stt, 0, sizeof stt);
    double y0 = INFINITY, y1 = -INFINITY;
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        out->fruit_stop[f] = HV_NO_STOP;
        if (inst->fruit_begin[f] != inst->fruit_begin[f + 1]) {
            y0 = fmin(y0, inst->fruits[f].y_m);
            y1 = fmax(y1, inst->fruits[f].y_m);
        }
    }
    if (y0 > y1) { /* nothing reachable: an empty plan */
        if (stats) {
            *stats = stt;
        }
        return HV_OK;
    }
    size_t nw = (size_t)floor((y1 - y0) / fov_width_m) + 1;
    uint32_t *wstop = malloc(nw * sizeof *wstop);
    unsigned char *used = calloc(inst->n_stops, 1);
    if (wstop == NULL || used == NULL) {
        free(wstop);
        free(used);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t k = 0; k < nw; ++k) {
        wstop[k] = nearest_stop(inst, y0 + ((double)k + 0.5) * fov_width_m);
    }
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (inst->fruit_begin[f] == inst->fruit_begin[f + 1]) {
            continue;
        }
        const hv_fruit_t *fr = &inst->fruits[f];
        size_t k = (size_t)floor((fr->y_m - y0) / fov_width_m);
        if (k >= nw) {
            k = nw - 1;
        }
        double c;
        if (hv_instance_pair_cost(inst, (uint32_t)f, wstop[k], &c) == HV_OK) {
            out->fruit_stop[f] = wstop[k];
            continue;
        }
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
            stt.moved++;
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
