/* Branch-and-price (bp.h). Primal heuristic "polish": a local search from the incumbent
 * once the root is solved, when the root leaves more than PRIMAL_ROOT_GAP and no helper
 * thread polishes. */
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

/* Without a helper thread (which polishes from the start of the solve), when the root
 * leaves more than PRIMAL_ROOT_GAP: a long local search from the incumbent, before the pair
 * fixing, which a better incumbent makes stronger. */
static hv_status_t bp_polish_incumbent(bp_t *b)
{
    unsigned kicks = bp_polish_kicks(b);
    if (kicks == 0 || !isfinite(b->inc.ub_ms)) {
        return HV_OK;
    }
    double t0 = hv_milp_now_s();
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(a.fruit_stop, b->inc.best, b->nf * sizeof *b->inc.best);
    hv_status_t st = HV_OK;
    /* in chunks, between which the clock is read: the local search does not poll it, and
     * at alpha 4 (250 fruits) 1000 kicks took 0.8 s, past a 10 s limit */
    for (unsigned done = 0; done < kicks && st == HV_OK && !bp_must_stop(b); done += POLISH_CHUNK) {
        st = bp_improve_plan(b, &a, kicks - done < POLISH_CHUNK ? kicks - done : POLISH_CHUNK);
    }
    hv_assignment_free(&a);
    b->stats.t_heur += hv_milp_now_s() - t0;
    return st;
}

/* BP_ROOT_SOLVED: when the root leaves more than PRIMAL_ROOT_GAP and no helper thread
 * polishes. */
static hv_status_t polish_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    (void)call;
    if (b->inc.ub_ms - b->fix.root_lag > PRIMAL_ROOT_GAP * b->inc.ub_ms && b->inc.helper == NULL) {
        return bp_polish_incumbent(b);
    }
    return HV_OK;
}

const bp_plugin_t bp_heur_polish = {"polish", BP_ROOT_SOLVED, 100, 0, polish_exec};
