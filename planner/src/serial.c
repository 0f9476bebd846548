/* Serial baseline (baselines.h): each side alone, solved exactly by the MILP. */
#include <stdlib.h>
#include <string.h>

#include "hv/baselines.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

hv_status_t hv_serial_solve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                            hv_assignment_t *out, unsigned char *passes, hv_serial_result_t *res)
{
    if (inst == NULL || opt == NULL || out == NULL || passes == NULL || res == NULL ||
        out->n_fruits != inst->n_fruits) {
        return HV_ERR_ARG;
    }
    memset(res, 0, sizeof *res);
    res->optimal = 1;
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        out->fruit_stop[f] = HV_NO_STOP;
        passes[f] = inst->fruits[f].side == HV_SIDE_LEFT ? 0 : 1;
    }
    unsigned char *keep = malloc(inst->n_fruits ? inst->n_fruits : 1);
    uint32_t *back = malloc((inst->n_fruits ? inst->n_fruits : 1) * sizeof *back);
    if (keep == NULL || back == NULL) {
        free(keep);
        free(back);
        return HV_ERR_PLAN_NOMEM;
    }
    hv_status_t st = HV_OK;
    for (int side = 0; side < 2 && st == HV_OK; ++side) {
        for (size_t f = 0; f < inst->n_fruits; ++f) {
            keep[f] = (int)inst->fruits[f].side == side;
        }
        hv_instance_t sub;
        st = hv_instance_subset(inst, 0, inst->n_stops, keep, 1, &sub, back);
        if (st != HV_OK) {
            break;
        }
        hv_milp_result_t *r = &res->side[side];
        if (sub.n_fruits == 0) { /* nothing to pick on this side: the pass only drives */
            r->status = HV_SOLVE_OPTIMAL;
            r->objective_s = r->bound_s = sub.travel_time_s;
            hv_instance_free(&sub);
            continue;
        }
        hv_assignment_t warm = {0, NULL}, best = {0, NULL};
        st = hv_assignment_alloc(&warm, sub.n_fruits);
        if (st == HV_OK) {
            st = hv_assignment_alloc(&best, sub.n_fruits);
        }
        if (st == HV_OK) {
            st = hv_fov_solve(&sub, HV_FOV_DEFAULT_WIDTH_M, &warm, NULL);
        }
        if (st == HV_OK) {
            st = hv_milp_solve(&sub, opt, &warm, &best, r);
        }
        if (st == HV_OK && r->status != HV_SOLVE_OPTIMAL && r->status != HV_SOLVE_FEASIBLE) {
            st = HV_ERR_PLAN_NO_SOLUTION;
        }
        if (st == HV_OK) {
            double t;
            st = hv_assignment_makespan(&sub, &best, &t); /* trust, but verify */
        }
        if (st == HV_OK) {
            for (size_t g = 0; g < sub.n_fruits; ++g) {
                out->fruit_stop[back[g]] = best.fruit_stop[g];
            }
            res->optimal &= r->status == HV_SOLVE_OPTIMAL;
            if (r->gap > res->gap) {
                res->gap = r->gap;
            }
            res->nodes += r->nodes;
            res->runtime_s += r->runtime_s;
        }
        hv_assignment_free(&warm);
        hv_assignment_free(&best);
        hv_instance_free(&sub);
    }
    free(keep);
    free(back);
    if (st != HV_OK) {
        return st;
    }
    /* Both passes: each side's own makespan (sum C + tau * stops + T_travel). */
    res->makespan_s = 0.0;
    for (int side = 0; side < 2 && st == HV_OK; ++side) {
        unsigned char *k2 = malloc(inst->n_fruits ? inst->n_fruits : 1);
        uint32_t *map = malloc((inst->n_fruits ? inst->n_fruits : 1) * sizeof *map);
        hv_assignment_t one_a = {0, NULL};
        hv_instance_t one;
        st = (k2 && map) ? hv_assignment_alloc(&one_a, inst->n_fruits) : HV_ERR_PLAN_NOMEM;
        if (st == HV_OK) {
            for (size_t f = 0; f < inst->n_fruits; ++f) {
                k2[f] = (int)inst->fruits[f].side == side;
            }
            st = hv_instance_subset(inst, 0, inst->n_stops, k2, 0, &one, map);
        }
        if (st == HV_OK) {
            hv_eval_t ev;
            one_a.n_fruits = one.n_fruits;
            for (size_t g = 0; g < one.n_fruits; ++g) {
                one_a.fruit_stop[g] = out->fruit_stop[map[g]];
            }
            st = hv_assignment_eval(&one, &one_a, &ev);
            res->makespan_s += ev.makespan_s;
            hv_instance_free(&one);
        }
        hv_assignment_free(&one_a);
        free(map);
        free(k2);
    }
    return st;
}
