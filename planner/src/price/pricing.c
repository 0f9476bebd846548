/* Branch-and-price (bp.h). The pricing problem: every stop priced exactly (milp_pricing.h)
 * at given duals, with the subset-row cuts' penalties; the Lagrangian bound, and the columns
 * that enter the master. */
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

/* sigma(p) of count-row duals sg into out[p]: the sum over the rows counting stop p. */
static void bp_sigma_per_stop(const bp_t *b, const double *sg, double *out)
{
    for (size_t p = 0; p < b->ns; ++p) {
        out[p] = 0.0;
    }
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        for (uint32_t p = b->m.crow[r].lo; sg[r] != 0.0 && p <= b->m.crow[r].hi; ++p) {
            out[p] += sg[r];
        }
    }
}

/* The pricing items of stop p at duals pi into itl / itr: its reachable fruits with a
 * positive dual and a pair not fixed out, and when node_only those the current node allows
 * there. Records each fruit's pair at p in pair_at. */
void bp_stop_items(bp_t *b, size_t p, const double *pi, int node_only, size_t *nl, size_t *nr)
{
    const hv_instance_t *in = b->inst;
    *nl = *nr = 0;
    for (size_t q = b->m.stop_begin[p]; q < b->m.stop_begin[p + 1]; ++q) {
        size_t k = b->m.stop_pair[q];
        uint32_t f = in->pairs[k].fruit;
        b->m.pair_at[f] = k;
        if (pi[f] <= 1e-9 || b->fix.pair_dead[k] ||
            (node_only && (b->tree.lo[f] > p || b->tree.hi[f] < p))) {
            continue;
        }
        hv_price_item_t it = {f, 1000.0 * in->pairs[k].cost_s, pi[f], 0};
        if (in->fruits[f].side == HV_SIDE_LEFT) {
            b->m.itl[(*nl)++] = it;
        } else {
            b->m.itr[(*nr)++] = it;
        }
    }
}

/* The penalty the subset-row cuts at the duals pi put on a pattern of the fruits
 * f[0 .. n): -pi of every cut holding two or more of them. */
static double bp_cut_penalty(bp_t *b, const uint32_t *f, size_t n, const double *pi)
{
    double s = 0.0;
    size_t nh = hv_src_hits(&b->cuts.src, f, n, b->cuts.src_hit);
    for (size_t h = 0; h < nh; ++h) {
        s -= pi[b->nf + b->cuts.src_hit[h]];
    }
    return s;
}

/* The cut bits of the stop's items itl[0 .. nl), itr[0 .. nr) (milp_pricing.h): one per
 * cut with a negative dual in pi that holds two or more of them, its penalty in b->cuts.pen.
 * Beyond 64 such cuts the rest are left out (*overflow = 1), which can only lower the
 * pricing's v, so bounds stay valid. Returns b->cuts.pen, or NULL when no item has a bit. */
const double *bp_cut_bits(bp_t *b, const double *pi, size_t nl, size_t nr, int *overflow)
{
    const hv_src_t *sr = &b->cuts.src;
    size_t n_touched = 0;
    int nbits = 0;
    *overflow = 0;
    for (size_t i = 0; i < nl + nr && sr->n > 0; ++i) {
        uint32_t f = i < nl ? b->m.itl[i].fruit : b->m.itr[i - nl].fruit;
        for (size_t q = sr->fbeg[f]; q < sr->fbeg[f + 1]; ++q) {
            uint32_t c = sr->fcut[q];
            if (pi[b->nf + c] >= 0.0) {
                continue;
            }
            if (b->cuts.src_bit[c] == -1) { /* met once */
                b->cuts.src_bit[c] = -2;
                b->cuts.src_hit[n_touched++] = c;
            } else if (b->cuts.src_bit[c] == -2) { /* twice: it can bite here */
                if (nbits < 64) {
                    b->cuts.pen[nbits] = -pi[b->nf + c];
                    b->cuts.src_bit[c] = nbits++;
                } else {
                    *overflow = 1;
                }
            }
        }
    }
    for (size_t i = 0; i < nl + nr && nbits > 0; ++i) { /* stop_items left every mask 0 */
        hv_price_item_t *it = i < nl ? &b->m.itl[i] : &b->m.itr[i - nl];
        for (size_t q = sr->fbeg[it->fruit]; q < sr->fbeg[it->fruit + 1]; ++q) {
            int32_t bit = b->cuts.src_bit[sr->fcut[q]];
            it->cuts |= bit >= 0 ? (uint64_t)1 << bit : 0;
        }
    }
    for (size_t t = 0; t < n_touched; ++t) {
        b->cuts.src_bit[b->cuts.src_hit[t]] = -1;
    }
    b->cuts.src_bits += nbits;
    b->cuts.src_stops += sr->n > 0;
    return nbits > 0 ? b->cuts.pen : NULL;
}

/* Price every stop at the duals (pi, sg): the Lagrangian bound
 *     T_travel + sum_f pi_f + sum_c pi_c + sum_r sg_r rhs_r + sum_p min(0, v_p)
 * with v_p the least tau + max(W_L, W_R) - pi(S) - sigma(p) + (the cut penalties) over the
 * patterns the node allows at p (pi_c <= 0: the subset-row cuts' duals); valid for any pi
 * and any sg of the right signs. Each stop's best pattern is
 * added to the master when its reduced cost at the master's own duals (pi_lp, mu_lp,
 * sg_lp) is negative. */
hv_status_t bp_price_at(bp_t *b, const double *pi, const double *sg, double *lag_ms, int *added)
{
    const hv_instance_t *in = b->inst;
    double sum = b->travel_ms;
    for (size_t f = 0; f < bp_n_pi(b); ++f) {
        sum += pi[f]; /* the fruits' duals, then the cuts' (right-hand sides 1) */
    }
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        if (sg[r] != 0.0) {
            sum += sg[r] * (sg[r] < 0.0 ? b->m.crow[r].max : b->m.crow[r].min);
        }
    }
    bp_sigma_per_stop(b, sg, b->m.sigma_stop);
    bp_sigma_per_stop(b, b->m.sg_lp, b->m.sigma_lp);
    *added = 0;
    b->m.cf_len = 0;
    for (size_t p = 0; p < b->ns; ++p) {
        b->m.cand[p].rc = 0.0;
    }
    memset(b->m.cover, 0, b->nf * sizeof *b->m.cover);
    for (size_t f = 0; b->skip_ms != NULL && f < b->nf; ++f) {
        if (b->m.row_of_fruit[f] != 0 && bp_skip_open(b, f) && b->skip_ms[f] < pi[f]) {
            sum += b->skip_ms[f] - pi[f]; /* left uncovered in the Lagrangian's optimum */
            b->m.cover[f] += 1.0;
        }
    }
    for (size_t p = 0; p < b->ns; ++p) {
        b->m.stop_v[p] = 0.0;
        if (b->m.row_of_stop[p] == 0) {
            continue;
        }
        if (b->m.fixed_pat[p] >= 0) {
            /* the one pattern allowed here, and it must be used: no min with 0 */
            const pattern_t *pt = &b->m.pat[b->m.fixed_pat[p]];
            double v = pt->cost_ms - b->m.sigma_stop[p] +
                       bp_cut_penalty(b, b->m.pf + pt->first, pt->n, pi);
            for (uint32_t q = 0; q < pt->n; ++q) {
                v -= pi[b->m.pf[pt->first + q]];
                b->m.cover[b->m.pf[pt->first + q]] += 1.0;
            }
            sum += v;
            b->m.stop_v[p] = v;
            continue;
        }
        size_t nl, nr;
        bp_stop_items(b, p, pi, 1, &nl, &nr);
        int overflow;
        const double *pen = bp_cut_bits(b, pi, nl, nr, &overflow);
        b->cuts.src_overflow += overflow;
        /* last round's best pattern here, at today's duals: a threshold for the pricing */
        double offset = b->tau_ms - b->m.sigma_stop[p], v0 = INFINITY, t0 = 0.0;
        size_t *warm = b->m.warm_pair + b->m.stop_begin[p];
        if (b->m.warm_n[p] != SIZE_MAX) {
            double wl = 0.0, wr = 0.0, prof = 0.0;
            int ok = 1;
            for (size_t q = 0; q < b->m.warm_n[p] && ok; ++q) {
                const hv_pair_t *pa = &in->pairs[warm[q]];
                ok = b->tree.lo[pa->fruit] <= p && p <= b->tree.hi[pa->fruit] &&
                     !b->fix.pair_dead[warm[q]];
                *(in->fruits[pa->fruit].side == HV_SIDE_LEFT ? &wl : &wr) += 1000.0 * pa->cost_s;
                prof += pi[pa->fruit];
                b->m.sel[q] = pa->fruit;
            }
            if (ok) {
                t0 = fmax(wl, wr);
                v0 = offset + t0 - prof + bp_cut_penalty(b, b->m.sel, b->m.warm_n[p], pi);
            }
        }
        double v, time;
        size_t n_sel;
        hv_status_t st = hv_pricer_best(&b->m.pricer, b->m.itl, nl, b->m.itr, nr, offset, pen,
                                        fmin(0.0, v0), &v, b->m.sel, &n_sel, &time);
        if (st != HV_OK) {
            return st;
        }
        if (time >= 0.0) {
            b->m.warm_n[p] = n_sel;
            for (size_t q = 0; q < n_sel; ++q) {
                warm[q] = b->m.pair_at[b->m.sel[q]];
            }
        } else if (v0 < 0.0) {
            v = v0; /* nothing beats the warm pattern: it is the best */
            time = t0;
            n_sel = b->m.warm_n[p];
            for (size_t q = 0; q < n_sel; ++q) {
                b->m.sel[q] = in->pairs[warm[q]].fruit;
            }
        }
        sum += v; /* v <= 0 by construction */
        b->m.stop_v[p] = v;
        if (time < 0.0) {
            continue;
        }
        for (size_t q = 0; q < n_sel; ++q) {
            b->m.cover[b->m.sel[q]] += 1.0;
        }
        double cost = b->tau_ms + time, rc = cost - b->m.mu_lp[p] - b->m.sigma_lp[p] +
                                             bp_cut_penalty(b, b->m.sel, n_sel, b->m.pi_lp);
        for (size_t q = 0; q < n_sel; ++q) {
            rc -= b->m.pi_lp[b->m.sel[q]];
        }
        if (rc < -RC_EPS_MS) {
            if (!hv_grow((void **)&b->m.cf, &b->m.cf_cap, b->m.cf_len + n_sel + 1,
                         sizeof *b->m.cf)) {
                return HV_ERR_PLAN_NOMEM;
            }
            b->m.cand[p] = (cand_t){rc, cost, (uint32_t)b->m.cf_len, (uint32_t)n_sel};
            memcpy(b->m.cf + b->m.cf_len, b->m.sel, n_sel * sizeof *b->m.sel);
            b->m.cf_len += n_sel;
        }
    }
    /* neighbouring stops price near-identical patterns: add a stop's pattern only where
     * its reduced cost is the least within +-CAND_WINDOW stops */
    long w = CAND_WINDOW;
    for (size_t p = 0; p < b->ns; ++p) {
        double rc = b->m.cand[p].rc;
        int best = rc < -RC_EPS_MS;
        for (long d = -w; best && d <= w; ++d) {
            long q = (long)p + d;
            if (d != 0 && q >= 0 && q < (long)b->ns &&
                (b->m.cand[q].rc < rc || (b->m.cand[q].rc == rc && d < 0))) {
                best = 0;
            }
        }
        if (best) {
            const cand_t *c = &b->m.cand[p];
            memcpy(b->m.sel, b->m.cf + c->first, c->n * sizeof *b->m.sel);
            int r = bp_pattern_add(b, (uint32_t)p, b->m.sel, c->n, c->cost);
            if (r < 0) {
                return HV_ERR_PLAN_NOMEM;
            }
            *added += r;
        }
    }
    *lag_ms = sum;
    return HV_OK;
}
