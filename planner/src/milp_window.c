/* Row-window re-optimisation of a plan (milp_window.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_clock.h"
#include "hv/milp_subsolve.h"
#include "hv/milp_window.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* The plan's fruits per stop into count[], its used stops, ascending, into used[];
 * returns their number. */
static size_t used_stops(const hv_instance_t *inst, const hv_assignment_t *plan, uint32_t *count,
                         uint32_t *used)
{
    memset(count, 0, inst->n_stops * sizeof *count);
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (plan->fruit_stop[f] != HV_NO_STOP) {
            count[plan->fruit_stop[f]]++;
        }
    }
    size_t k = 0;
    for (size_t p = 0; p < inst->n_stops; ++p) {
        if (count[p] > 0) {
            used[k++] = (uint32_t)p;
        }
    }
    return k;
}

/* The candidate stops [*lo, *hi) of the window of used[i .. i + width): those strictly
 * between its neighbouring used stops (the row's ends where it has none). */
static void window_range(const hv_instance_t *inst, const uint32_t *used, size_t k, size_t i,
                         unsigned width, size_t *lo, size_t *hi)
{
    *lo = i > 0 ? used[i - 1] + 1u : 0u;
    *hi = i + width < k ? used[i + width] : inst->n_stops;
}

hv_status_t hv_window_memo_init(hv_window_memo_t *memo, size_t cap)
{
    if (memo == NULL) {
        return HV_ERR_ARG;
    }
    memset(memo, 0, sizeof *memo);
    if (cap == 0) {
        return HV_ERR_ARG;
    }
    memo->keys = malloc(cap * sizeof *memo->keys);
    if (memo->keys == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    memo->cap = cap;
    return HV_OK;
}

void hv_window_memo_free(hv_window_memo_t *memo)
{
    free(memo->keys);
    memset(memo, 0, sizeof *memo);
}

static int memo_has(const hv_window_memo_t *memo, uint64_t key)
{
    for (size_t j = 0; j < memo->n; ++j) {
        if (memo->keys[j] == key) {
            return 1;
        }
    }
    return 0;
}

static void memo_add(hv_window_memo_t *memo, uint64_t key)
{
    memo->keys[memo->next] = key;
    memo->next = (memo->next + 1) % memo->cap;
    if (memo->n < memo->cap) {
        memo->n++;
    }
}

/* FNV-1a over 32-bit words */
static uint64_t key_mix(uint64_t h, uint32_t w)
{
    return (h ^ w) * 0x100000001b3ull;
}

/* Re-plan the fruits of stops used[i .. i + width) over the stops strictly between
 * used[i - 1] and used[i + width]. *better = 1 when the plan was improved (and updated).
 * Skipped when the memo holds the window; recorded there when solved without gain. */
static hv_status_t window_once(const hv_instance_t *inst, const hv_milp_options_t *so,
                               const hv_milp_subsolver_t *solver, const uint32_t *used, size_t k,
                               size_t i, unsigned width, unsigned char *keep, uint32_t *back,
                               hv_assignment_t *plan, int *better, hv_window_stats_t *stats,
                               hv_window_memo_t *memo, int full_limit)
{
    *better = 0;
    size_t lo, hi;
    window_range(inst, used, k, i, width, &lo, &hi);
    uint32_t first = used[i], last = used[i + width - 1];
    uint64_t key = key_mix(key_mix(0xcbf29ce484222325ull, (uint32_t)lo), (uint32_t)hi);
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        uint32_t s = plan->fruit_stop[f];
        keep[f] = s != HV_NO_STOP && s >= first && s <= last;
        if (keep[f]) {
            key = key_mix(key_mix(key, (uint32_t)f), s);
        }
    }
    if (memo_has(memo, key)) {
        stats->repeats++;
        return HV_OK;
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
        st = solver->solve(solver, &sub, so, &inc, &out, &res);
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
        } else if (full_limit || res.status == HV_SOLVE_OPTIMAL) {
            memo_add(memo, key); /* a shortened limit may have cut the sub-solve short */
        }
    }
    hv_assignment_free(&inc);
    hv_assignment_free(&out);
    hv_instance_free(&sub);
    return st;
}

/* The order of a pass: the windows' starts (advancing by half the width, so each stop is
 * re-planned twice a pass), the cheapest sub-problem first (candidate stops times fruits): a
 * window at alpha 2.5-4 takes 0.02-0.5 s, and the dear ones often run out their limit
 * without a gain (SOLVER.md's history). Returns the number of windows. */
static size_t pass_order(const hv_instance_t *inst, const uint32_t *count, const uint32_t *used,
                         size_t k, unsigned width, uint32_t *order, double *cost)
{
    if (k <= width) {
        return 0;
    }
    size_t step = width > 1 ? width / 2 : 1, n = 0;
    for (size_t i = 0; i + width <= k; i += step) {
        size_t lo, hi;
        window_range(inst, used, k, i, width, &lo, &hi);
        double fruits = 0.0;
        for (size_t j = i; j < i + width; ++j) {
            fruits += count[used[j]];
        }
        double c = (double)(hi - lo) * fruits;
        size_t at = n++;
        for (; at > 0 && cost[at - 1] > c; --at) { /* insertion: a pass has 5-20 */
            cost[at] = cost[at - 1];
            order[at] = order[at - 1];
        }
        cost[at] = c;
        order[at] = (uint32_t)i;
    }
    return n;
}

hv_status_t hv_window_improve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                              const hv_milp_subsolver_t *sub, unsigned width, double window_limit_s,
                              double t_deadline_s, hv_assignment_t *plan, double *t_s,
                              hv_window_stats_t *stats, hv_window_memo_t *memo,
                              hv_window_better_fn better_fn, void *better_ctx)
{
    hv_window_stats_t dummy;
    if (stats == NULL) {
        stats = &dummy;
    }
    memset(stats, 0, sizeof *stats);
    if (inst == NULL || opt == NULL || sub == NULL || plan == NULL || t_s == NULL || width == 0) {
        return HV_ERR_ARG;
    }
    size_t ns = inst->n_stops + 1;
    uint32_t *used = malloc(ns * sizeof *used);
    uint32_t *count = malloc(ns * sizeof *count);
    uint32_t *order = malloc(ns * sizeof *order);
    double *cost = malloc(ns * sizeof *cost);
    unsigned char *keep = malloc(inst->n_fruits + 1);
    uint32_t *back = malloc((inst->n_fruits + 1) * sizeof *back);
    hv_window_memo_t own = {NULL, 0, 0, 0}; /* the call's own, when the caller keeps none */
    hv_assignment_t saved;
    hv_status_t st = HV_ERR_PLAN_NOMEM;
    if (used != NULL && count != NULL && order != NULL && cost != NULL && keep != NULL &&
        back != NULL && (memo != NULL || hv_window_memo_init(&own, 4 * ns) == HV_OK) &&
        hv_assignment_alloc(&saved, inst->n_fruits) == HV_OK) {
        st = HV_OK;
        if (memo == NULL) {
            memo = &own;
        }
        hv_milp_options_t so; /* its limit set per window below */
        hv_milp_subsolve_options(opt, window_limit_s, &so);
        int again = 1;
        /* after a better window the pass starts again in the new plan's order; the memo
         * skips the windows it did not change */
        while (again && st == HV_OK && hv_milp_now_s() < t_deadline_s &&
               !(opt->stop != NULL && opt->stop(opt->stop_ctx))) {
            again = 0;
            size_t k = used_stops(inst, plan, count, used);
            size_t n = pass_order(inst, count, used, k, width, order, cost);
            for (size_t w = 0; w < n && st == HV_OK && !again; ++w) {
                double left = t_deadline_s - hv_milp_now_s();
                if (left <= 0.0 || (opt->stop != NULL && opt->stop(opt->stop_ctx))) {
                    break;
                }
                so.time_limit_s = fmin(window_limit_s, left);
                int full_limit = left >= window_limit_s;
                memcpy(saved.fruit_stop, plan->fruit_stop,
                       inst->n_fruits * sizeof *saved.fruit_stop);
                int better;
                st = window_once(inst, &so, sub, used, k, order[w], width, keep, back, plan,
                                 &better, stats, memo, full_limit);
                double t;
                if (st == HV_OK && better && hv_assignment_makespan(inst, plan, &t) == HV_OK &&
                    t < *t_s) {
                    *t_s = t;
                    again = 1;
                    if (better_fn != NULL) {
                        better_fn(better_ctx, plan, t);
                    }
                } else if (better) {
                    /* cannot happen when the window's change is the plan's; keep the old */
                    memcpy(plan->fruit_stop, saved.fruit_stop,
                           inst->n_fruits * sizeof *saved.fruit_stop);
                }
            }
        }
        hv_assignment_free(&saved);
    }
    hv_window_memo_free(&own);
    free(used);
    free(count);
    free(order);
    free(cost);
    free(keep);
    free(back);
    return st;
}
