/* Makespan of an assignment (plan_eval.h). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hv/plan_eval.h"
#include "hv/plan_status.h"

size_t hv_instance_pair_index(const hv_instance_t *inst, uint32_t fruit, uint32_t stop)
{
    size_t lo = inst->fruit_begin[fruit], hi = inst->fruit_begin[fruit + 1];
    while (lo < hi) { /* pairs of one fruit are sorted by stop */
        size_t mid = lo + (hi - lo) / 2;
        if (inst->pairs[mid].stop < stop) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo < inst->fruit_begin[fruit + 1] && inst->pairs[lo].stop == stop ? lo : SIZE_MAX;
}

hv_status_t hv_instance_pair_cost(const hv_instance_t *inst, uint32_t fruit, uint32_t stop,
                                  double *cost_s)
{
    if (inst == NULL || cost_s == NULL || fruit >= inst->n_fruits) {
        return HV_ERR_ARG;
    }
    size_t k = hv_instance_pair_index(inst, fruit, stop);
    if (k == SIZE_MAX) {
        return HV_ERR_UNREACHABLE;
    }
    *cost_s = inst->pairs[k].cost_s;
    return HV_OK;
}

hv_status_t hv_assignment_eval_ws(const hv_instance_t *inst, const hv_assignment_t *a, double *work,
                                  hv_eval_t *ev)
{
    if (inst == NULL || a == NULL || work == NULL || ev == NULL || a->n_fruits != inst->n_fruits) {
        return HV_ERR_ARG;
    }
    memset(ev, 0, sizeof *ev);
    double *cl = work, *cr = work + inst->n_stops;
    /* C^L_p < 0 marks an unused stop, so a stop whose picks all cost 0 still counts */
    for (size_t p = 0; p < inst->n_stops; ++p) {
        cl[p] = -1.0;
        cr[p] = 0.0;
    }
    hv_status_t st = HV_OK;
    for (size_t f = 0; f < inst->n_fruits && st == HV_OK; ++f) {
        uint32_t p = a->fruit_stop[f];
        int reachable = inst->fruit_begin[f] != inst->fruit_begin[f + 1];
        if (p == HV_NO_STOP) {
            st = reachable ? HV_ERR_PLAN_UNASSIGNED : HV_OK;
            continue;
        }
        double c;
        if (p >= inst->n_stops || hv_instance_pair_cost(inst, (uint32_t)f, p, &c) != HV_OK) {
            st = HV_ERR_PLAN_BAD_PAIR;
            continue;
        }
        if (cl[p] < 0) {
            cl[p] = 0.0;
        }
        if (inst->fruits[f].side == HV_SIDE_LEFT) {
            cl[p] += c;
        } else {
            cr[p] += c;
        }
        ++ev->fruits_planned;
    }
    if (st == HV_OK) {
        for (size_t p = 0; p < inst->n_stops; ++p) {
            if (cl[p] < 0) {
                cl[p] = 0.0; /* report 0 for unused stops */
            } else {
                ev->stops++;
                ev->pick_time_s += cl[p] > cr[p] ? cl[p] : cr[p];
            }
        }
        ev->stop_time_s = inst->stop_penalty_s * (double)ev->stops;
        ev->travel_time_s = inst->travel_time_s;
        ev->makespan_s = ev->pick_time_s + ev->stop_time_s + ev->travel_time_s;
    }
    return st;
}

hv_status_t hv_assignment_eval(const hv_instance_t *inst, const hv_assignment_t *a, hv_eval_t *ev)
{
    if (inst == NULL) {
        return HV_ERR_ARG;
    }
    double *work = malloc((inst->n_stops ? 2 * inst->n_stops : 1) * sizeof *work);
    if (work == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    hv_status_t st = hv_assignment_eval_ws(inst, a, work, ev);
    free(work);
    return st;
}

hv_status_t hv_assignment_makespan(const hv_instance_t *inst, const hv_assignment_t *a,
                                   double *makespan_s)
{
    if (makespan_s == NULL) {
        return HV_ERR_ARG;
    }
    hv_eval_t ev;
    hv_status_t st = hv_assignment_eval(inst, a, &ev);
    if (st == HV_OK) {
        *makespan_s = ev.makespan_s;
    }
    return st;
}
