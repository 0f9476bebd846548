/* Relaxation-induced neighbourhoods of a plan (milp_rins.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_rins.h"
#include "hv/milp_subsolve.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* The sub-instance: the free fruits with their open pairs, then one stand-in per
 * (stop, arm) holding kept fruits. stand_stop[i] is the stop of stand-in i (sub fruit
 * n_free + i). */
typedef struct rins_sub {
    hv_instance_t inst;
    uint32_t *full_of; /* full index of each free sub fruit */
    size_t n_free;
    uint32_t *stand_stop;
} rins_sub_t;

static void sub_free(rins_sub_t *s)
{
    hv_instance_free(&s->inst);
    free(s->full_of);
    free(s->stand_stop);
}

static hv_status_t sub_build(const hv_instance_t *in, const unsigned char *free_fruit,
                             const unsigned char *pair_open, const hv_assignment_t *plan,
                             rins_sub_t *s)
{
    memset(s, 0, sizeof *s);
    size_t np = in->n_stops, nf = in->n_fruits;
    /* the kept load per (stop, arm) in whole ms: the tables hold ms, and a sum of
     * thousandths in floating point would not be a whole number of them */
    long *load = calloc(2 * np + 1, sizeof *load);
    unsigned char *held = calloc(2 * np + 1, 1);
    if (load == NULL || held == NULL) {
        free(load);
        free(held);
        return HV_ERR_PLAN_NOMEM;
    }
    size_t n_free = 0, n_free_pairs = 0;
    for (size_t f = 0; f < nf; ++f) {
        uint32_t p = plan->fruit_stop[f];
        if (p == HV_NO_STOP) {
            continue; /* unreachable: in neither part */
        }
        if (free_fruit[f]) {
            n_free++;
            n_free_pairs += in->fruit_begin[f + 1] - in->fruit_begin[f];
            continue;
        }
        size_t k = hv_instance_pair_index(in, (uint32_t)f, p);
        if (k == SIZE_MAX) {
            free(load);
            free(held);
            return HV_ERR_ARG; /* the plan puts a fruit where it cannot be picked */
        }
        size_t at = 2 * p + (in->fruits[f].side == HV_SIDE_RIGHT);
        load[at] += lround(1000.0 * in->pairs[k].cost_s);
        held[at] = 1;
    }
    size_t n_stand = 0;
    for (size_t i = 0; i < 2 * np; ++i) {
        n_stand += held[i];
    }
    size_t n = n_free + n_stand;
    hv_instance_t *o = &s->inst;
    o->n_stops = np;
    o->stop_penalty_s = in->stop_penalty_s;
    o->travel_time_s = in->travel_time_s;
    o->stop_y_m = malloc((np ? np : 1) * sizeof *o->stop_y_m);
    o->fruits = calloc(n + 1, sizeof *o->fruits);
    o->fruit_begin = malloc((n + 1) * sizeof *o->fruit_begin);
    o->pairs = malloc((n_free_pairs + n_stand + 1) * sizeof *o->pairs);
    s->full_of = malloc((n_free + 1) * sizeof *s->full_of);
    s->stand_stop = malloc((n_stand + 1) * sizeof *s->stand_stop);
    if (o->stop_y_m == NULL || o->fruits == NULL || o->fruit_begin == NULL || o->pairs == NULL ||
        s->full_of == NULL || s->stand_stop == NULL) {
        free(load);
        free(held);
        sub_free(s);
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(o->stop_y_m, in->stop_y_m, np * sizeof *o->stop_y_m);
    for (size_t f = 0; f < nf; ++f) {
        if (plan->fruit_stop[f] == HV_NO_STOP || !free_fruit[f]) {
            continue;
        }
        size_t q = o->n_fruits++;
        o->fruits[q] = in->fruits[f];
        o->fruit_begin[q] = o->n_pairs;
        s->full_of[q] = (uint32_t)f;
        for (size_t k = in->fruit_begin[f]; k < in->fruit_begin[f + 1]; ++k) {
            if (pair_open != NULL && !pair_open[k] && in->pairs[k].stop != plan->fruit_stop[f]) {
                continue;
            }
            o->pairs[o->n_pairs] = in->pairs[k];
            o->pairs[o->n_pairs++].fruit = (uint32_t)q;
        }
    }
    s->n_free = o->n_fruits;
    for (size_t i = 0; i < 2 * np; ++i) {
        if (!held[i]) {
            continue;
        }
        size_t q = o->n_fruits++;
        uint32_t p = (uint32_t)(i / 2);
        hv_fruit_t *fr = &o->fruits[q];
        strcpy(fr->id, "kept-load");
        fr->side = i % 2 ? HV_SIDE_RIGHT : HV_SIDE_LEFT;
        fr->y_m = in->stop_y_m[p];
        o->fruit_begin[q] = o->n_pairs;
        s->stand_stop[q - s->n_free] = p;
        hv_pair_t *pr = &o->pairs[o->n_pairs++];
        pr->fruit = (uint32_t)q;
        pr->stop = p;
        pr->cost_s = (double)load[i] / 1000.0;
    }
    o->fruit_begin[o->n_fruits] = o->n_pairs;
    free(load);
    free(held);
    return HV_OK;
}

hv_status_t hv_rins_improve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                            const hv_milp_subsolver_t *sub, const unsigned char *free_fruit,
                            const unsigned char *pair_open, double limit_s, hv_assignment_t *plan,
                            double *t_s, int *better, hv_milp_result_t *res_out)
{
    if (better != NULL) {
        *better = 0;
    }
    if (inst == NULL || opt == NULL || free_fruit == NULL || plan == NULL || t_s == NULL ||
        better == NULL || !(limit_s > 0.0)) {
        return HV_ERR_ARG;
    }
    rins_sub_t s;
    hv_status_t st = sub_build(inst, free_fruit, pair_open, plan, &s);
    if (st != HV_OK) {
        return st;
    }
    size_t n = s.inst.n_fruits;
    hv_assignment_t inc, out;
    if (hv_assignment_alloc(&inc, n) != HV_OK) {
        sub_free(&s);
        return HV_ERR_PLAN_NOMEM;
    }
    if (hv_assignment_alloc(&out, n) != HV_OK) {
        hv_assignment_free(&inc);
        sub_free(&s);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t q = 0; q < n; ++q) {
        inc.fruit_stop[q] =
            q < s.n_free ? plan->fruit_stop[s.full_of[q]] : s.stand_stop[q - s.n_free];
    }
    hv_milp_options_t so;
    hv_milp_subsolve_options(opt, limit_s, &so);
    hv_milp_result_t res;
    st = sub->solve(sub, &s.inst, &so, &inc, &out, &res);
    double t;
    if (st == HV_OK && hv_assignment_makespan(&s.inst, &out, &t) == HV_OK && t < *t_s - 1e-4) {
        /* the sub's makespan is the plan's; re-evaluated on the whole instance all the same,
         * inc keeping the free fruits' old stops should it differ */
        for (size_t q = 0; q < s.n_free; ++q) {
            plan->fruit_stop[s.full_of[q]] = out.fruit_stop[q];
        }
        if (hv_assignment_makespan(inst, plan, &t) == HV_OK && t < *t_s - 1e-4) {
            *t_s = t;
            *better = 1;
        } else {
            for (size_t q = 0; q < s.n_free; ++q) {
                plan->fruit_stop[s.full_of[q]] = inc.fruit_stop[q];
            }
        }
    }
    if (st == HV_OK && res_out != NULL) {
        *res_out = res;
    }
    hv_assignment_free(&inc);
    hv_assignment_free(&out);
    sub_free(&s);
    return st;
}
