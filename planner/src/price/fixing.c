/* Branch-and-price (bp.h). Reduced-cost fixing: (fruit, stop) pairs that no plan better
 * than the incumbent can use, from the root's duals. */
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

/* Reduced-cost fixing of (fruit, stop) pairs from the root's duals pi (Lagrangian bound L):
 * a plan with fruit f at stop p costs at least L - min(0, v_p) + v_p(f), v_p(f) the best
 * pattern at p that contains f. Pairs for which that exceeds the incumbent less 1 ms (or
 * the relative gap) leave the pricing and their columns the master, for the whole tree. */
hv_status_t bp_fix_pairs(bp_t *b)
{
    const hv_instance_t *in = b->inst;
    const double *pi = b->fix.root_pi;
    const double big = 1e7; /* forces an item into the pattern */
    double slack =
        b->inc.ub_ms - b->fix.root_lag - (b->whole_ms ? 1.0 : b->opt->rel_gap * b->inc.ub_ms);
    double t0 = hv_milp_now_s();
    int stopped = 0;
    for (size_t p = 0; p < b->ns; ++p) {
        if (b->m.row_of_stop[p] == 0) {
            continue;
        }
        if (bp_must_stop(b)) {
            stopped = 1; /* every pair fixed so far stays fixed: each was proven alone */
            break;
        }
        size_t nl, nr;
        bp_stop_items(b, p, pi, 0, &nl, &nr); /* fixing is global: every pair not yet fixed */
        int overflow;
        const double *pen = bp_cut_bits(b, pi, nl, nr, &overflow);
        if (overflow) {
            continue; /* v_p would be below the root's own: fixing from it is not safe */
        }
        double vp, time;
        size_t n_sel;
        hv_status_t st = hv_pricer_best(&b->m.pricer, b->m.itl, nl, b->m.itr, nr, b->tau_ms, pen,
                                        0.0, &vp, b->m.sel, &n_sel, &time);
        if (st == HV_ERR_MILP_DEADLINE) {
            stopped = 1;
            break;
        }
        if (st != HV_OK) {
            return st;
        }
        for (size_t q = b->m.stop_begin[p]; q < b->m.stop_begin[p + 1] && !stopped; ++q) {
            size_t k = b->m.stop_pair[q];
            uint32_t f = in->pairs[k].fruit;
            if (b->fix.pair_dead[k]) {
                continue;
            }
            hv_price_item_t *it = NULL; /* f's item (fruits with pi <= 0 force nothing) */
            for (size_t i = 0; i < nl && it == NULL; ++i) {
                it = b->m.itl[i].fruit == f ? &b->m.itl[i] : NULL;
            }
            for (size_t i = 0; i < nr && it == NULL; ++i) {
                it = b->m.itr[i].fruit == f ? &b->m.itr[i] : NULL;
            }
            double thr = slack + vp; /* keep the pair if v_p(f) <= thr */
            double v;
            if (it != NULL) {
                it->profit += big;
                /* without the cuts' penalties: v_p(f) only gets lower, so fixing stays
                 * valid, and a forced item makes the pricing with cut states slow */
                st = hv_pricer_best(&b->m.pricer, b->m.itl, nl, b->m.itr, nr, b->tau_ms, NULL,
                                    fmin(0.0, thr - big + 1e-6), &v, b->m.sel, &n_sel, &time);
                it->profit -= big;
                if (st == HV_ERR_MILP_DEADLINE) {
                    stopped = 1;
                    break;
                }
                if (st != HV_OK) {
                    return st;
                }
                if (time >= 0.0) {
                    continue; /* a pattern with f at or below the threshold: keep */
                }
            } else {
                continue; /* f's dual is not positive: no forced pricing, keep */
            }
            b->fix.pair_dead[k] = 1;
            b->fix.pairs_fixed++;
        }
    }
    for (size_t j = 0; j < b->m.n_pat; ++j) {
        const pattern_t *pt = &b->m.pat[j];
        for (uint32_t q = 0; q < pt->n && !b->m.pat_dead[j]; ++q) {
            size_t k = hv_instance_pair_index(b->inst, b->m.pf[pt->first + q], pt->stop);
            b->m.pat_dead[j] = b->fix.pair_dead[k];
        }
        if (b->m.pat_dead[j]) {
            bp_col_open(b, j, 0);
        }
    }
    if (!stopped) {
        b->fix.fixed_ub = b->inc.ub_ms;
    }
    b->stats.t_fix += hv_milp_now_s() - t0;
    return HV_OK;
}
