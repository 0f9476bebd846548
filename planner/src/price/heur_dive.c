/* Branch-and-price (bp.h). Primal heuristic "column-dive": from the root, fix the heaviest
 * fractional pattern and re-solve until a plan or the incumbent's value. */
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

/* A primal dive by column fixing: from node `from` (just solved), repeatedly fix the master's
 * heaviest fractional pattern (its column at 1; its stop and its fruits in no other column)
 * and re-solve by column generation, until the master point is a plan or the dive's bound
 * reaches the incumbent. The dive's nodes are never queued: they take no part in the proof. */
static hv_status_t bp_column_dive(bp_t *b, int32_t from)
{
    int inexact = b->tree.inexact; /* a dive node closed as doubtful says nothing about the tree */
    double t0 = hv_milp_now_s();
    int32_t k = from;
    hv_status_t st = HV_OK;
    for (;;) {
        int32_t jbest = -1;
        double xbest = LAMBDA_EPS;
        for (size_t j = 0; j < b->m.n_pat; ++j) {
            double v = glp_get_col_prim(b->m.lp, b->m.pat[j].col);
            if (v > xbest && v < 1.0 - LAMBDA_EPS) {
                xbest = v;
                jbest = (int32_t)j;
            }
        }
        if (jbest < 0) {
            break;
        }
        k = bp_node_new(b, k, KIND_PATTERN, 0, b->m.pat[jbest].stop, b->m.pat[jbest].stop, jbest,
                        b->tree.nodes[k].lb_ms);
        if (k < 0) {
            return HV_ERR_PLAN_NOMEM;
        }
        node_end_t end;
        split_t sp;
        if ((st = bp_node_process(b, k, &end, &sp)) != HV_OK || end != NODE_BRANCH) {
            break;
        }
    }
    b->tree.inexact = inexact;
    b->stats.t_dive += hv_milp_now_s() - t0;
    b->stats.dives++;
    return st;
}

/* BP_AFTER_ROOT, first: the root's plan may be far from optimal, and a column-fixing dive
 * finds better ones than the branch dive (SOLVER.md's history); opt->column_dive says when. */
static hv_status_t dive_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    if (b->opt->column_dive == 2 ||
        (b->opt->column_dive == 1 && b->inc.ub_ms - call->lb_ms > PRIMAL_ROOT_GAP * b->inc.ub_ms &&
         b->inst->n_pairs < CENTRE_MIN_PAIRS)) {
        return bp_column_dive(b, call->node);
    }
    return HV_OK;
}

const bp_plugin_t bp_heur_dive = {"column-dive", BP_AFTER_ROOT, 200, 0, dive_exec};
