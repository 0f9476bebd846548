/* Branch-and-price (bp.h). The incumbent: plans offered by the heuristics, the helper
 * thread and the other tree worker; integral master points; the local-search polish budget;
 * progress lines. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bp.h"
#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_local_search.h"
#include "hv/milp_status.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* Plan `a` (makespan t_s) is the incumbent, and the helper and the other tree worker hear
 * of it: a worker prunes by its own incumbent, so the plan it prunes by must reach the
 * result. */
void bp_set_incumbent(bp_t *b, const hv_assignment_t *a, double t_s)
{
    b->inc.ub_ms = 1000.0 * t_s;
    memcpy(b->inc.best, a->fruit_stop, b->nf * sizeof *b->inc.best);
    if (b->inc.helper != NULL) {
        hv_helper_offer(b->inc.helper, a, t_s);
    }
    if (b->tree.share != NULL) {
        hv_share_offer(b->tree.share, b->inc.best, b->inc.ub_ms);
    }
}

/* A master solution in which every column is 0 or 1 as an assignment, into b->inc.best when it
 * is better. Returns 1 when the master point was integral. */
int bp_take_integral(bp_t *b, const double *x)
{
    double skipped_ms = 0.0; /* hv_price_bound: the fruits left uncovered */
    for (size_t f = 0; f < b->nf; ++f) {
        double v = b->m.row_of_fruit[f] ? x[b->m.row_of_fruit[f]] : 0.0;
        if (v > LAMBDA_EPS && !(bp_skip_open(b, f) && v > 1.0 - LAMBDA_EPS)) {
            return 0;
        }
        skipped_ms += v > LAMBDA_EPS ? b->skip_ms[f] : 0.0;
    }
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        if (x[b->m.crow[r].art] > LAMBDA_EPS) {
            return 0;
        }
    }
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        double v = x[b->m.pat[k].col];
        if (v > LAMBDA_EPS && v < 1.0 - LAMBDA_EPS) {
            return 0;
        }
    }
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return 0;
    }
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        if (x[b->m.pat[k].col] > 0.5) {
            for (uint32_t q = 0; q < b->m.pat[k].n; ++q) {
                a.fruit_stop[b->m.pf[b->m.pat[k].first + q]] = b->m.pat[k].stop;
            }
        }
    }
    double t;
    if (b->skip_ms != NULL) { /* a plan with uncovered fruits: the master's own value */
        t = b->travel_ms + skipped_ms;
        for (size_t k = 0; k < b->m.n_pat; ++k) {
            t += x[b->m.pat[k].col] > 0.5 ? b->m.pat[k].cost_ms : 0.0;
        }
        if (t < b->inc.ub_ms) {
            bp_set_incumbent(b, &a, t / 1000.0);
        }
    } else if (hv_assignment_makespan(b->inst, &a, &t) == HV_OK && 1000.0 * t < b->inc.ub_ms) {
        bp_set_incumbent(b, &a, t);
    }
    hv_assignment_free(&a);
    return 1;
}

/* Plan `a` (makespan t_s) becomes the incumbent when it beats the incumbent, with its
 * patterns as columns unless `defer_cols` (then they join once the root is solved). */
static hv_status_t bp_offer_plan_cols(bp_t *b, const hv_assignment_t *a, double t_s, int defer_cols)
{
    if (1000.0 * t_s < b->inc.ub_ms - 1e-6) {
        b->stats.heur_wins++;
        bp_set_incumbent(b, a, t_s);
        b->inc.plan_cols_due = defer_cols;
        if (!defer_cols && bp_add_assignment_columns(b, b->inc.best) < 0) {
            return HV_ERR_PLAN_NOMEM;
        }
    }
    return HV_OK;
}

hv_status_t bp_offer_plan(bp_t *b, const hv_assignment_t *a, double t_s)
{
    return bp_offer_plan_cols(b, a, t_s, 0);
}

/* Local search from plan `a` with `kicks` kicks; kept when it beats the incumbent. */
hv_status_t bp_improve_plan(bp_t *b, hv_assignment_t *a, unsigned kicks)
{
    hv_ls_options_t lo;
    hv_ls_options_default(&lo);
    lo.kicks = kicks;
    lo.seed = 0x9e3779b97f4a7c15ull * (uint64_t)(b->stats.heur_runs + 1);
    double t;
    hv_status_t st = hv_local_search(b->inst, &lo, a, &t);
    b->stats.heur_runs++;
    return st == HV_OK ? bp_offer_plan(b, a, t) : st;
}

/* The polish's length: polish_work * 100 / n^2 kicks (a descent costs ~n^2), at least
 * POLISH_CHUNK, at most POLISH_MAX_KICKS; 0 when polish_work is 0. */
unsigned bp_polish_kicks(const bp_t *b)
{
    if (b->opt->polish_work <= 0) {
        return 0;
    }
    size_t n = b->nf ? b->nf : 1;
    size_t kicks = (size_t)b->opt->polish_work * 100u / (n * n);
    return (unsigned)(kicks < POLISH_CHUNK ? POLISH_CHUNK
                                           : (kicks > POLISH_MAX_KICKS ? POLISH_MAX_KICKS : kicks));
}

void bp_progress(bp_t *b, double lb_ms, int force)
{
    double t = hv_milp_now_s();
    if (b->opt->verbose < 1 || b->tree.is_worker || (!force && t - b->t_print < 1.0)) {
        return;
    }
    b->t_print = t;
    double g = isfinite(b->inc.ub_ms) ? (b->inc.ub_ms - lb_ms) / b->inc.ub_ms : INFINITY;
    fprintf(stderr,
            "price: %6.2f s  nodes %zu open %zu  columns %zu  T %.3f s  bound %.3f s  gap %.2e\n",
            t - b->t_start, b->tree.n_nodes, b->tree.heap_len, b->m.n_pat, b->inc.ub_ms / 1000.0,
            lb_ms / 1000.0, g);
}

/* The helper's (from_helper) or else the other tree worker's better plan, if there is one,
 * becomes the incumbent. */
hv_status_t bp_take_plan(bp_t *b, int from_helper)
{
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    double t = 0.0, ub_ms = 0.0;
    int got = from_helper ? hv_helper_take(b->inc.helper, b->inc.ub_ms / 1000.0, &a, &t)
                          : hv_share_take(b->tree.share, b->inc.ub_ms - 1e-6, a.fruit_stop, &ub_ms);
    if (from_helper) {
        b->inc.helper_plans += got;
    } else {
        t = ub_ms / 1000.0;
    }
    /* the helper's plans reach the root at times its thread sets: as columns they made the
     * root's column generation take 275-620 rounds at alpha 4 seed 8 instead of 376
     * (SOLVER.md's history), so they wait until the root is solved */
    hv_status_t st =
        got ? bp_offer_plan_cols(b, &a, t, from_helper && !isfinite(b->fix.root_lag)) : HV_OK;
    hv_assignment_free(&a);
    bp_region_floor(b);
    return st;
}

/* The helper's last plan (with `take`), then stop it. */
hv_status_t bp_helper_finish(bp_t *b, int take)
{
    hv_status_t sth = take ? bp_take_plan(b, 1) : HV_OK;
    hv_window_stats_t ws;
    double tj = hv_milp_now_s();
    hv_status_t stj = hv_helper_stop(b->inc.helper, &ws);
    if (b->opt->verbose >= 1) {
        fprintf(stderr,
                "price: helper thread joined after %.2f s in %.3f s: %ld windows (%ld better, "
                "%ld proven), %ld repeated windows skipped\n",
                tj - b->t_start, hv_milp_now_s() - tj, ws.windows, ws.improved, ws.proven,
                ws.repeats);
    }
    b->inc.helper = NULL;
    b->stats.windows += ws.windows;
    b->stats.windows_better += ws.improved;
    return sth != HV_OK ? sth : stj;
}
