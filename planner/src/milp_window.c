/* Row-window re-optimisation of a plan (milp_window.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_clock.h"
#include "hv/milp_subsolve.h"
#include "hv/milp_window.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* The plan's used stops, ascending, into used[]; returns their number. */
static size_t used_stops(const hv_instance_t *inst, const hv_assignment_t *plan,
                         unsigned char *mark, uint32_t *used)
{
    memset(mark, 0, inst->n_stops);
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (plan->fruit_stop[f] != HV_NO_STOP) {
            mark[plan->fruit_stop[f]] = 1;
        }
    }
    size_t k = 0;
    for (size_t p = 0; p < inst->n_stops; ++p) {
        if (mark[p]) {
            used[k++] = (uint32_t)p;
        }
    }
    return k;
}

/* Re-plan the fruits of stops used[i .. i + width) over the stops strictly between
 * used[i - 1] and used[i + width]. *better = 1 when the plan was improved (and updated). */
static hv_status_t window_once(const hv_instance_t *inst, const hv_milp_options_t *so,
                               const uint32_t *used, size_t k, size_t i, unsigned width,
                               unsigned char *keep, uint32_t *back, hv_assignment_t *plan,
                               int *better, hv_window_stats_t *stats)
{
    *better = 0;
    size_t lo = i > 0 ? used[i - 1] + 1u : 0u;
    size_t hi = i + width < k ? used[i + width] : inst->n_stops; /* exclusive */
    uint32_t first = used[i], last = used[i + width - 1];
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        uint32_t s = plan->fruit_stop[f];
        keep[f] = s != HV_NO_STOP && s >= first && s <= last;
    }
    hv_instance_t sub;
    hv_status_t st = hv_instance_subset(inst, lo, hi, keep, 1, &sub, back);
    if (st != HV_OK) {
        return st;
    }
    hv_assignment_t inc, out;
    st = hv_assignment_alloc(&inc, sub.n_fruits);
    if (st == HV_OK && (st = hv_assignment_alloc(&out, sub.n_fruits)) != HV_OK) {
        hv_assignment_free(&inc);
    }
    if (st != HV_OK) {
        hv_instance_free(&sub);
        return st;
    }
    for (size_t f = 0; f < sub.n_fruits; ++f) {
        inc.fruit_stop[f] = plan->fruit_stop[back[f]] - (uint32_t)lo;
    }
    double cur;
    hv_milp_result_t res;
    st = hv_assignment_makespan(&sub, &inc, &cur);
    if (st == HV_OK) {
        st = hv_milp_solve(&sub, so, &inc, &out, &res);
    }
    if (st == HV_OK) {
        stats->windows++;
        stats->proven += res.status == HV_SOLVE_OPTIMAL;
        /* the sub-solve's plan, re-evaluated: whole ms apart when better */
        double t;
        if (hv_assignment_makespan(&sub, &out, &t) == HV_OK && t < cur - 1e-4) {
            for (size_t f = 0; f < sub.n_fruits; ++f) {
                plan->fruit_stop[back[f]] = out.fruit_stop[f] + (uint32_t)lo;
            }
            stats->improved++;
            *better = 1;
        }
    }
    hv_assignment_free(&inc);
    hv_assignment_free(&out);
    hv_instance_free(&sub);
    return st;
}

hv_status_t hv_window_improve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                              unsigned width, double window_limit_s, double t_deadline_s,
                              hv_assignment_t *plan, double *t_s, hv_window_stats_t *stats,
                              hv_window_better_fn better_fn, void *better_ctx)
{
    hv_window_stats_t dummy;
    if (stats == NULL) {
        stats = &dummy;
    }
    memset(stats, 0, sizeof *stats);
    if (inst == NULL || opt == NULL || plan == NULL || t_s == NULL || width == 0) {
        return HV_ERR_ARG;
    }
    unsigned char *mark = malloc(inst->n_stops + 1);
    uint32_t *used = malloc((inst->n_stops + 1) * sizeof *used);
    unsigned char *keep = malloc(inst->n_fruits + 1);
    uint32_t *back = malloc((inst->n_fruits + 1) * sizeof *back);
    hv_assignment_t saved;
    hv_status_t st = HV_ERR_PLAN_NOMEM;
    if (mark != NULL && used != NULL && keep != NULL && back != NULL &&
        hv_assignment_alloc(&saved, inst->n_fruits) == HV_OK) {
        st = HV_OK;
        hv_milp_options_t so; /* its limit set per window below */
        hv_milp_subsolve_options(opt, window_limit_s, &so);
        int again = 1;
        while (again && st == HV_OK && hv_milp_now_s() < t_deadline_s &&
               !(opt->stop != NULL && opt->stop(opt->stop_ctx))) {
            again = 0;
            size_t k = used_stops(inst, plan, mark, used);
            /* windows advance by half their width: each stop is re-planned twice a pass */
            size_t step = width > 1 ? width / 2 : 1;
            for (size_t i = 0; i + width <= k && k > width && st == HV_OK; i += step) {
                double left = t_deadline_s - hv_milp_now_s();
                if (left <= 0.0 || (opt->stop != NULL && opt->stop(opt->stop_ctx))) {
                    break;
                }
                so.time_limit_s = fmin(window_limit_s, left);
                memcpy(saved.fruit_stop, plan->fruit_stop,
                       inst->n_fruits * sizeof *saved.fruit_stop);
                int better;
                st = window_once(inst, &so, used, k, i, width, keep, back, plan, &better, stats);
                double t;
                if (st == HV_OK && better && hv_assignment_makespan(inst, plan, &t) == HV_OK &&
                    t < *t_s) {
                    *t_s = t;
                    again = 1;
                    if (better_fn != NULL) {
                        better_fn(better_ctx, plan, t);
                    }
                    k = used_stops(inst, plan, mark, used); /* stops may have merged */
                } else if (better) {
                    /* cannot happen when the window's change is the plan's; keep the old */
                    memcpy(plan->fruit_stop, saved.fruit_stop,
                           inst->n_fruits * sizeof *saved.fruit_stop);
                }
            }
        }
        hv_assignment_free(&saved);
    }
    free(mark);
    free(used);
    free(keep);
    free(back);
    return st;
}
