/* Branch-and-price (bp.h). Plugin "pricer": exact per-stop pricing (milp_pricing.h) at
 * Wentges-smoothed duals, with the subset-row cuts' penalties; the Lagrangian bound of
 * every round. */
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

/* Automatic smoothing (after Pessoa, Sadykov, Uchoa and Vanderbeck, 2018): the subgradient
 * at the duals just priced (1 - the times each fruit is covered by the stops' best
 * patterns) shows whether the bound rises towards the master's duals or back towards the
 * centre; the weight of the centre for the next round falls by SMOOTH_STEP in the first
 * case and rises by SMOOTH_STEP of what is left to 1 in the other. A child starts again
 * from SMOOTHING. Traced at alpha 2.5, a child's fixed weight of 0.8 held its bound far
 * below its master's value for 15 rounds (SOLVER.md's history). A weight of 0 adapts too:
 * kept at 0, a stalled master above the incumbent was priced at its own degenerate duals
 * for up to 1,400 rounds at alpha 4 seed 4. */
static void bp_smooth_adapt(bp_t *b, double alpha)
{
    double dot = 0.0;
    for (size_t f = 0; f < b->nf; ++f) {
        double g = (b->m.row_of_fruit[f] ? 1.0 : 0.0) - b->m.cover[f];
        dot += g * (b->m.pi_lp[f] - b->m.pi_c[f]);
    }
    b->m.smooth = dot > 0.0 ? fmax(0.0, alpha - SMOOTH_STEP)
                            : fmin(SMOOTH_MAX, alpha + SMOOTH_STEP * (1.0 - alpha));
}

/* One pricing round with Wentges smoothing: price at alpha * (the duals of the best bound
 * so far at this node) + (1 - alpha) * (the master's duals), which damps the master's
 * oscillating duals; when that finds no column (mis-pricing) price at the master's duals.
 * `lag_ms` is the best bound of the round. */
static hv_status_t bp_price_round(bp_t *b, int fresh_node, double *lag_ms, int *added)
{
    size_t ncr = b->m.n_crow;
    if (!bp_duals_read(b) ||
        !hv_grow((void **)&b->m.sg_c, &b->m.sgc_cap, ncr + 1, sizeof *b->m.sg_c) ||
        !hv_grow((void **)&b->m.sg_sep, &b->m.sgs_cap, ncr + 1, sizeof *b->m.sg_sep)) {
        return HV_ERR_PLAN_NOMEM;
    }
    if (fresh_node && !b->m.root_centre) {
        b->m.center_lag = -INFINITY;
        const basis_t *pb = b->tree.cur_basis >= 0 ? &b->tree.bases[b->tree.cur_basis] : NULL;
        if (pb != NULL && isfinite(pb->lag)) { /* start from the parent's centre */
            for (size_t f = 0; f < bp_n_pi(b); ++f) {
                b->m.pi_c[f] = f < pb->n_pi ? pb->pi[f] : 0.0;
            }
            for (size_t r = 0; r < ncr; ++r) {
                b->m.sg_c[r] = r < pb->n_sg ? pb->sg[r] : 0.0;
            }
            b->m.center_lag = pb->lag;
        }
    }
    b->m.root_centre = 0;
    if (fresh_node || !b->opt->auto_smoothing) {
        b->m.smooth = SMOOTHING;
    }
    double alpha = isfinite(b->m.center_lag) ? b->m.smooth : 0.0;
    *lag_ms = -INFINITY;
    int retry = 0; /* pricing again at the master's duals after a mis-pricing */
    for (;;) {
        for (size_t f = 0; f < bp_n_pi(b); ++f) {
            b->m.pi_sep[f] = alpha * b->m.pi_c[f] + (1.0 - alpha) * b->m.pi_lp[f];
        }
        for (size_t r = 0; r < ncr; ++r) {
            b->m.sg_sep[r] = alpha * b->m.sg_c[r] + (1.0 - alpha) * b->m.sg_lp[r];
        }
        double lag;
        hv_status_t st = bp_price_at(b, b->m.pi_sep, b->m.sg_sep, &lag, added);
        if (st != HV_OK) {
            return st;
        }
        *lag_ms = fmax(*lag_ms, lag);
        if (b->opt->auto_smoothing && !retry && isfinite(b->m.center_lag)) {
            bp_smooth_adapt(b, alpha);
        }
        if (lag > b->m.center_lag) {
            b->m.center_lag = lag;
            memcpy(b->m.pi_c, b->m.pi_sep, bp_n_pi(b) * sizeof *b->m.pi_c);
            memcpy(b->m.sg_c, b->m.sg_sep, ncr * sizeof *b->m.sg_c);
        }
        if (*added > 0) {
            return HV_OK;
        }
        if (alpha == 0.0) {
            return HV_OK;
        }
        alpha = 0.0; /* mis-pricing: the smoothed duals found nothing */
        retry = 1;
    }
}

/* BP_PRICE: one round at the node (fresh_node: its first). */
static hv_status_t pricer_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    return bp_price_round(b, call->fresh_node, &call->lag_ms, &call->added);
}

const bp_plugin_t bp_pricer = {"pricer", BP_PRICE, 100, 0, pricer_exec};
