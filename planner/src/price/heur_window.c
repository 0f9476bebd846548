/* Branch-and-price (bp.h). Primal heuristic "windows": row windows of the incumbent re-
 * planned exactly (milp_window.h) through the context's sub-solver, on the helper thread
 * (milp_helper.h) or after the root. */
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
#include "hv/milp_window.h"
#include "hv/plan_status.h"

/* Row windows of the incumbent re-planned exactly (milp_window.h), for up to WINDOW_SHARE of
 * the time left; a better plan becomes the incumbent. */
static hv_status_t bp_window_reopt(bp_t *b)
{
    double t0 = hv_milp_now_s();
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(a.fruit_stop, b->inc.best, b->nf * sizeof *b->inc.best);
    double t = b->inc.ub_ms / 1000.0;
    hv_window_stats_t ws;
    hv_status_t st =
        hv_window_improve(b->inst, b->opt, b->sub, (unsigned)b->opt->window_width, WINDOW_LIMIT_S,
                          t0 + WINDOW_SHARE * (b->t_deadline - t0), &a, &t, &ws, NULL, NULL, NULL);
    if (st == HV_OK) {
        st = bp_offer_plan(b, &a, t);
    }
    hv_assignment_free(&a);
    b->stats.t_window += hv_milp_now_s() - t0;
    b->stats.windows += ws.windows;
    b->stats.windows_better += ws.improved;
    return st;
}

/* BP_AT_START: with helper_thread, the second core polishes the plan and re-plans its
 * windows during the root. */
static hv_status_t window_start_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    (void)call;
    if (b->opt->window_width > 0 && b->opt->helper_thread && isfinite(b->inc.ub_ms)) {
        hv_assignment_t a = {b->nf, b->inc.best};
        return hv_helper_start(b->inst, b->opt, b->sub, &a, b->inc.ub_ms / 1000.0, b->t_deadline,
                               bp_polish_kicks(b), &b->inc.helper);
    }
    return HV_OK;
}

/* BP_AFTER_ROOT, after the dive: when the root leaves more than PRIMAL_ROOT_GAP and no
 * helper runs, the windows on a helper thread (this thread has polished) or here. */
static hv_status_t window_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    if (b->opt->window_width > 0 && b->inc.ub_ms - call->lb_ms > PRIMAL_ROOT_GAP * b->inc.ub_ms &&
        b->inc.helper == NULL) {
        if (b->opt->helper_thread) {
            hv_assignment_t a = {b->nf, b->inc.best};
            return hv_helper_start(b->inst, b->opt, b->sub, &a, b->inc.ub_ms / 1000.0,
                                   b->t_deadline, 0, &b->inc.helper);
        }
        return bp_window_reopt(b);
    }
    return HV_OK;
}

const bp_plugin_t bp_heur_window_start = {"windows-helper", BP_AT_START, 100, 0, window_start_exec};
const bp_plugin_t bp_heur_window = {"windows", BP_AFTER_ROOT, 100, 0, window_exec};
