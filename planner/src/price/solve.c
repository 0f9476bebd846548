/* Branch-and-price (bp.h). hv_price_solve and hv_price_bound (milp_price.h): the plugins
 * registered, the root's centre, the search, the result. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bp.h"
#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_price.h"
#include "hv/milp_status.h"
#include "hv/plan_status.h"
#include "plugins.h"

/* bp_init, and the solve's clock started towards t_deadline_s. */
static hv_status_t bp_start(bp_t *b, const hv_instance_t *inst, const hv_milp_options_t *opt,
                            const hv_milp_subsolver_t *sub, double t_deadline_s)
{
    hv_status_t st = bp_init(b, inst, opt);
    size_t n;
    const bp_plugin_t *const *all = bp_plugins_all(&n);
    bp_plugins_include(b, all, n);
    b->sub = sub;
    b->t_deadline = b->m.pricer.t_deadline_s = t_deadline_s;
    b->t_start = b->t_print = hv_milp_now_s();
    if (st == HV_OK) {
        long n = bp_fix_dominated_stops(b);
        if (opt->verbose >= 1) {
            fprintf(stderr, "price: %ld of %zu stops dominated (%ld pairs fixed)\n", n, b->ns,
                    b->fix.pairs_fixed);
        }
    }
    return st;
}

hv_status_t hv_price_solve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                           const hv_milp_subsolver_t *sub, const hv_assignment_t *inc, double inc_t,
                           double t_deadline_s, hv_assignment_t *out, hv_milp_result_t *res)
{
    bp_t b;
    hv_status_t st = bp_start(&b, inst, opt, sub, t_deadline_s);
    if (st == HV_OK && inc != NULL) {
        memcpy(b.inc.best, inc->fruit_stop, b.nf * sizeof *b.inc.best);
        b.inc.ub_ms = 1000.0 * inc_t;
        if (bp_add_assignment_columns(&b, inc->fruit_stop) < 0) {
            st = HV_ERR_PLAN_NOMEM;
        }
    }
    if (st == HV_OK && bp_add_start_columns(&b) < 0) {
        st = HV_ERR_PLAN_NOMEM;
    }
    double root_lb = -INFINITY;
    long nodes = 0;
    if (st == HV_OK && opt->ascent_steps > 0) {
        st = bp_ascent_centre(&b, opt->ascent_steps);
    } else if (st == HV_OK && inst->n_pairs >= CENTRE_MIN_PAIRS) {
        bp_compact_centre(&b, 0.25 * (t_deadline_s - hv_milp_now_s()));
    }
    if (st == HV_OK) {
        st = bp_search(&b, &root_lb, &nodes);
    }
    double open_lb = INFINITY; /* of the nodes the second worker left open */
    size_t n_open = 0;
    if (b.tree.worker != NULL) {
        hv_status_t stw = bp_worker_join(&b, st != HV_OK, &open_lb, &n_open);
        st = st != HV_OK ? st : stw;
        nodes += b.tree.nodes_done;
    }
    if (b.inc.helper != NULL) { /* also after an error */
        hv_status_t sth = bp_helper_finish(&b, st == HV_OK);
        st = st != HV_OK ? st : sth;
    }
    if (st == HV_OK) {
        size_t n_main;
        double lb = fmin(fmin(b.inc.ub_ms, open_lb), bp_open_bound(&b, &n_main));
        bp_progress(&b, lb, 1);
        if (opt->verbose >= 1) {
            fprintf(stderr,
                    "price: %ld LP rounds in %.2f s (%d iterations, %ld restarts, %ld stalls), "
                    "pricing %.2f s (%llu stops, %.1f points each), heuristic %ld runs "
                    "(%ld better) in %.2f s, %ld column dives in %.2f s, %ld windows (%ld better) "
                    "in %.2f s, %ld plans from the helper thread, %ld of %zu pairs fixed in "
                    "%.2f s, "
                    "%zu subset-row cuts in %d rounds (%ld dropped; %.1f with a negative dual "
                    "per priced stop, %ld stops over 64), %ld interval count branches, %ld "
                    "nodes branched tailing off, second tree worker %ld nodes (%ld "
                    "nodes passed between the workers, %ld with a warm start)\n",
                    b.stats.cg_iters, b.stats.t_lp, glp_get_it_cnt(b.m.lp), b.stats.lp_restarts,
                    b.stats.lp_stalls, b.stats.t_price, b.m.pricer.calls,
                    (double)b.m.pricer.points / (double)(b.m.pricer.calls ? b.m.pricer.calls : 1),
                    b.stats.heur_runs, b.stats.heur_wins, b.stats.t_heur, b.stats.dives,
                    b.stats.t_dive, b.stats.windows, b.stats.windows_better, b.stats.t_window,
                    b.inc.helper_plans, b.fix.pairs_fixed, inst->n_pairs, b.stats.t_fix,
                    b.cuts.src.n, b.cuts.sr_rounds, b.cuts.sr_dropped,
                    (double)b.cuts.src_bits / (double)(b.cuts.src_stops ? b.cuts.src_stops : 1),
                    b.cuts.src_overflow, b.stats.iv_branches, b.stats.tailed, b.tree.nodes_done,
                    b.tree.given, b.tree.taken_warm);
        }
        if (opt->verbose >= 1) {
            fprintf(stderr,
                    "price: %ld relaxation-induced neighbourhoods (%ld better, %.1f "
                    "fruits freed each) in %.2f s; %ld regional bounds (%ld proofs, %ld nodes) "
                    "in %.2f s\n",
                    b.stats.rins.calls, b.stats.rins.better,
                    (double)b.stats.rins.freed /
                        (double)(b.stats.rins.calls ? b.stats.rins.calls : 1),
                    b.stats.rins.t_s, b.region.region_tries, b.region.region_proofs,
                    b.region.region_nodes, b.region.t_region);
        }
        res->nodes = nodes;
        res->worker_nodes = b.tree.nodes_done;
        res->columns = (long)b.m.n_pat;
        res->interval_branches = b.stats.iv_branches;
        res->tailed_nodes = b.stats.tailed;
        res->passed_nodes = b.tree.given;
        res->passed_warm = b.tree.taken_warm;
        res->cuts = (long)b.cuts.src.n;
        res->root_bound_s = root_lb / 1000.0;
        if (!isfinite(b.inc.ub_ms)) {
            res->status = b.tree.heap_len == 0 ? HV_SOLVE_INFEASIBLE : HV_SOLVE_NO_SOLUTION;
        } else {
            memcpy(out->fruit_stop, b.inc.best, b.nf * sizeof *b.inc.best);
            res->objective_s = b.inc.ub_ms / 1000.0;
            res->bound_s = fmin(lb, b.inc.ub_ms) / 1000.0;
            res->gap = (res->objective_s - res->bound_s) / fmax(res->objective_s, DBL_EPSILON);
            res->status = n_main == 0 && n_open == 0 && !b.tree.inexact ? HV_SOLVE_OPTIMAL
                                                                        : HV_SOLVE_FEASIBLE;
            if (res->status == HV_SOLVE_OPTIMAL) {
                res->bound_s = res->objective_s; /* every open node was pruned */
                res->gap = 0.0;
            }
        }
    }
    bp_free(&b);
    return st;
}

hv_status_t hv_price_bound(const hv_instance_t *inst, const hv_milp_options_t *opt,
                           const hv_milp_subsolver_t *sub, const double *skip_ms, double cutoff_ms,
                           double t_deadline_s, uint32_t *plan, hv_price_bound_result_t *res)
{
    hv_milp_options_t o; /* what the virtual stops and the cutoff allow */
    hv_milp_subsolve_options(opt, t_deadline_s - hv_milp_now_s(), &o);
    o.column_dive = 0;   /* it fixes patterns of b.inc.best, which may not be a plan yet */
    o.rel_gap = 0.0;     /* the cutoff is what may be left */
    o.helper_thread = 0; /* its plans cover every fruit */
    bp_t b;
    hv_status_t st = bp_start(&b, inst, &o, sub, t_deadline_s);
    b.skip_ms = skip_ms;
    b.whole_ms = 0;          /* the skip costs are duals, not whole ms */
    b.inc.ub_ms = cutoff_ms; /* no plan yet: b.inc.best is written by a better one only */
    *res = (hv_price_bound_result_t){-INFINITY, -INFINITY, 0, 0, 0};
    if (st == HV_OK && bp_add_start_columns(&b) < 0) {
        st = HV_ERR_PLAN_NOMEM;
    }
    if (st == HV_OK) {
        st = bp_search(&b, &res->root_lb_ms, &res->nodes);
    }
    if (st == HV_OK) {
        size_t n_open;
        res->lb_ms = fmin(b.inc.ub_ms, bp_open_bound(&b, &n_open));
        res->finished = n_open == 0;
        res->has_plan = b.inc.ub_ms < cutoff_ms;
        if (res->has_plan && plan != NULL) {
            memcpy(plan, b.inc.best, b.nf * sizeof *plan);
        }
    }
    bp_free(&b);
    return st;
}
