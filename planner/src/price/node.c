/* Branch-and-price (bp.h). One node: column generation until its master converges, then the
 * root's separators, fixing, the branching rules and the primal heuristics, all through the
 * plugin records. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bp.h"
#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_status.h"
#include "hv/plan_status.h"

/* Column generation at node k until the master is optimal, the node is pruned, or time is
 * up. On NODE_BRANCH `sp` says where. */
hv_status_t bp_node_process(bp_t *b, int32_t k, node_end_t *end, split_t *sp)
{
    if (b->inc.helper != NULL || b->tree.share != NULL) {
        hv_status_t stp = bp_take_plan(b, b->inc.helper != NULL);
        if (stp != HV_OK) {
            return stp;
        }
    }
    if (isfinite(b->fix.root_lag) && b->inc.ub_ms < b->fix.fixed_ub - 0.5) {
        hv_status_t stf = bp_fix_pairs(b); /* a better incumbent fixes more */
        if (stf != HV_OK) {
            return stf;
        }
    }
    int infeasible;
    hv_status_t st0 = bp_node_apply(b, k, &infeasible);
    if (st0 != HV_OK || infeasible) {
        if (infeasible) {
            b->tree.nodes[k].lb_ms = INFINITY; /* what the pseudocosts learn from it */
        }
        *end = NODE_PRUNED;
        return st0;
    }
    /* tailing off (opt->tail_off_ms): below the root, a master whose value has not fallen
     * for TAIL_ROUNDS rounds and is within tail_off_ms of the node's Lagrangian bound is
     * branched on as it is; the children start from that bound, which is valid at any
     * round. With opt->tail_off_open, so is a stalled master that the incumbent does not
     * prune, however far that bound lies below: the node's LP value is at most the
     * master's, so no bound its column generation could reach would prune it (SOLVER.md's history:
     * such nodes priced one degenerate column a round for hundreds of rounds). When that
     * point cannot be branched on (integral, or no fractional count or fruit), the column
     * generation goes on to convergence, so nothing is closed on it. */
    double tail_ms = b->tree.nodes[k].parent >= 0 ? (double)b->opt->tail_off_ms : 0.0;
    double best_master = INFINITY;
    int last_fall = 0, tailed = 0;
    for (int round = 0;; ++round) {
        if (bp_must_stop(b)) {
            *end = NODE_TIMEOUT;
            return HV_OK;
        }
        hv_status_t st = bp_lp_solve(b, round == 0 || b->m.lp_dual_next);
        b->m.lp_dual_next = 0;
        if (st != HV_OK) {
            return st;
        }
        if (bp_must_stop(b)) {
            *end = NODE_TIMEOUT;
            return HV_OK;
        }
        if (round > 0 && b->inc.helper != NULL && (st = bp_take_plan(b, 1)) != HV_OK) {
            return st; /* the root can take seconds: take better plans as they come */
        }
        bp_call_t pc = {.node = k, .fresh_node = round == 0};
        double tp = hv_milp_now_s();
        st = bp_plugins_run(b, BP_PRICE, &pc);
        b->stats.t_price += hv_milp_now_s() - tp;
        double lag = pc.lag_ms;
        int added = pc.added;
        if (st == HV_ERR_MILP_DEADLINE) {
            *end = NODE_TIMEOUT; /* this round's bound is unfinished: the node stays open */
            return HV_OK;
        }
        if (st != HV_OK) {
            return st;
        }
        b->stats.cg_iters++;
        if ((st = bp_give_if_hungry(b)) != HV_OK) {
            return st; /* an idle worker waited out whole nodes of 0.3-1 s (SOLVER.md's history) */
        }
        if (lag > b->tree.nodes[k].lb_ms) {
            b->tree.nodes[k].lb_ms = lag;
        }
        bp_region_floor(b);
        if (bp_prunable(b, b->tree.nodes[k].lb_ms)) {
            *end = NODE_PRUNED;
            return HV_OK;
        }
        double open_lb = b->tree.heap_len ? b->tree.nodes[b->tree.heap[0]].lb_ms : INFINITY;
        bp_progress(b, fmin(b->tree.nodes[k].lb_ms, open_lb), 0);
        double master_ms = glp_get_obj_val(b->m.lp) + b->travel_ms;
        if (master_ms < best_master - TAIL_FALL_MS) {
            best_master = master_ms;
            last_fall = round;
        }
        tailed = added > 0 && tail_ms > 0.0 && round - last_fall >= TAIL_ROUNDS &&
                 (best_master - b->tree.nodes[k].lb_ms <= tail_ms ||
                  (b->opt->tail_off_open && !bp_prunable(b, best_master)));
        if (added > 0 && !tailed) {
            continue;
        }
        /* the master is optimal over all columns of this node (or tails off, below it) */
        if (b->tree.nodes[k].parent < 0 && !isfinite(b->fix.root_lag)) {
            bp_call_t rc = {.node = k}; /* the root's separators: new rows solve again */
            if ((st = bp_plugins_run(b, BP_ROOT_LP, &rc)) != HV_OK) {
                return st;
            }
            if (rc.added) {
                continue;
            }
        }
        if (b->tree.nodes[k].parent < 0 && !isfinite(b->fix.root_lag)) {
            /* the root is solved: its best duals fix pairs for the whole tree */
            memcpy(b->fix.root_pi, b->m.pi_c, bp_n_pi(b) * sizeof *b->fix.root_pi);
            b->fix.root_lag = b->m.center_lag;
            if (b->inc.plan_cols_due && bp_add_assignment_columns(b, b->inc.best) < 0) {
                return HV_ERR_PLAN_NOMEM;
            }
            b->inc.plan_cols_due = 0;
            bp_call_t sc = {.node = k};
            if ((st = bp_plugins_run(b, BP_ROOT_SOLVED, &sc)) != HV_OK) {
                return st;
            }
            if ((st = bp_fix_pairs(b)) != HV_OK) {
                return st;
            }
        }
        int ncol = glp_get_num_cols(b->m.lp);
        double *x = malloc(((size_t)ncol + 1) * sizeof *x);
        if (x == NULL) {
            return HV_ERR_PLAN_NOMEM;
        }
        for (int j = 1; j <= ncol; ++j) {
            x[j] = glp_get_col_prim(b->m.lp, j);
        }
        if (bp_take_integral(b, x)) {
            free(x); /* the node's LP optimum is a plan: the node is solved */
            if (tailed) {
                tail_ms = 0.0; /* ... unless the master was not optimal yet */
                continue;
            }
            *end = NODE_INTEGRAL;
            return HV_OK;
        }
        /* x covers the columns up to now: choose the branch before the rounding adds any */
        bp_call_t bc = {.node = k, .x = x, .ncol = ncol, .split = sp};
        st = bp_plugins_run(b, BP_BRANCH, &bc);
        /* the primal heuristics, told whether the plan is more than PRIMAL_ROOT_GAP above
         * the root's bound (node 0's; the second worker's node 0 is a copy of the root) */
        bp_call_t hc = {.node = k, .x = x, .ncol = ncol};
        hc.far = b->inc.ub_ms - b->tree.nodes[0].lb_ms > PRIMAL_ROOT_GAP * b->inc.ub_ms;
        if (st == HV_OK) {
            st = bp_plugins_run(b, BP_NODE_LP, &hc);
        }
        free(x);
        if (st != HV_OK) {
            return st;
        }
        if (sp->score <= 0.0 && tailed) {
            tail_ms = 0.0;
            continue;
        }
        if (sp->score <= 0.0) {
            /* every fruit sits at one stop, so the point is integral up to round-off:
             * close the node, but do not claim a proof on it */
            b->tree.inexact = 1;
            *end = NODE_PRUNED;
            return HV_OK;
        }
        b->stats.tailed += tailed;
        *end = NODE_BRANCH;
        return HV_OK;
    }
}
