/* Branch-and-price (bp.h). Branching rule "count": the number of stops used in an interval
 * of the row (interval branching), first when it is far from integral. */
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

/* m: prefix sums of the master's mass per stop (choose_count) */
static int bp_stop_has_mass(const double *m, size_t p)
{
    return m[p + 1] - m[p] >= LAMBDA_EPS;
}

/* Branching on the number of stops: the LP likes two stops at 0.8 with a third between
 * them at 0.2; "at most k stops" / "at least k + 1" separates those. First over the whole
 * row; when that count is (nearly) integral, over intervals [lo, hi] of up to
 * opt->interval_branching stops. An interval qualifies when both its end stops carry
 * master mass and its count is at least IV_MIN_FRAC from an integer; among those the score
 * q + IV_GAP_WEIGHT * g prefers the most fractional count q, then the interval with the
 * widest run g of empty stops on its sides: a cluster of stops the LP mixes, isolated from
 * the rest (SOLVER.md's history: of the rules tried, this one proved the most instances). With
 * opt->iv_pseudocost, once both kinds of count child have been solved somewhere, that
 * score is multiplied, per child, by the rise its interval's pseudocost predicts at this
 * count over the rise of an average interval's: the same intervals come back in many
 * subtrees, and those whose children rose steeply are branched on sooner (an interval
 * not yet branched on keeps its score). score 0 when no count is fractional. */
static void bp_choose_count(bp_t *b, const double *x, split_t *best)
{
    double *m = b->tree.stop_mass; /* m[p + 1] - m[p]: the master's mass at stop p */
    memset(m, 0, (b->ns + 1) * sizeof *m);
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        m[b->m.pat[k].stop + 1] += x[b->m.pat[k].col];
    }
    for (size_t p = 0; p < b->ns; ++p) {
        m[p + 1] += m[p];
    }
    double tot = m[b->ns], ft = tot - floor(tot), sc = fmin(ft, 1.0 - ft);
    *best = (split_t){KIND_COUNT_LE,
                      0,
                      0,
                      0,
                      (uint32_t)(b->ns - 1),
                      (int32_t)floor(tot),
                      sc > LAMBDA_EPS ? sc : 0.0,
                      ft >= 0.5,
                      0.0,
                      0.0};
    if (best->score >= COUNT_MIN_SCORE || b->opt->interval_branching <= 0) {
        return;
    }
    /* el[p]: the run of stops without mass that ends at p (p included), IV_EDGE_GAP when
     * it reaches the start of the row; er[p] the same from the right */
    uint32_t *el = b->tree.stop_empty, *er = b->tree.stop_empty + b->ns;
    for (size_t p = 0; p < b->ns; ++p) {
        uint32_t before = p == 0 ? IV_EDGE_GAP : el[p - 1];
        el[p] = bp_stop_has_mass(m, p) ? 0 : (before == IV_EDGE_GAP ? IV_EDGE_GAP : before + 1);
    }
    for (size_t p = b->ns; p-- > 0;) {
        uint32_t after = p + 1 == b->ns ? IV_EDGE_GAP : er[p + 1];
        er[p] = bp_stop_has_mass(m, p) ? 0 : (after == IV_EDGE_GAP ? IV_EDGE_GAP : after + 1);
    }
    size_t wmax = (size_t)b->opt->interval_branching;
    double bs = 0.0, bc = 0.0, bsc = 0.0;
    int use_pc = b->opt->iv_pseudocost && b->tree.ivpc.all_n[0] > 0 && b->tree.ivpc.all_n[1] > 0;
    double avg[2] = {0.0, 0.0};
    for (int d = 0; d < 2 && use_pc; ++d) {
        avg[d] = b->tree.ivpc.all[d] / (double)b->tree.ivpc.all_n[d];
    }
    /* narrowest first, then leftmost: the first of equal scores is kept */
    for (size_t w = 1; w <= wmax && w <= b->ns; ++w) {
        for (size_t a = 0, e = w - 1; e < b->ns; ++a, ++e) {
            if (!bp_stop_has_mass(m, a) || !bp_stop_has_mass(m, e)) {
                continue;
            }
            double c = m[e + 1] - m[a], f = c - floor(c), q = fmin(f, 1.0 - f);
            if (q < IV_MIN_FRAC) {
                continue;
            }
            uint32_t gl = a == 0 ? IV_EDGE_GAP : el[a - 1];
            uint32_t gr = e + 1 == b->ns ? IV_EDGE_GAP : er[e + 1];
            double s = q + IV_GAP_WEIGHT * (double)(gl < gr ? gl : gr), sc = s;
            for (int d = 0; d < 2 && use_pc; ++d) {
                /* each child's estimated rise over an average interval's at this count */
                double pc = bp_pc_mean(&b->tree.ivpc, a * b->tree.ivpc_w + (e - a), d, avg[d]);
                double dist = d == 0 ? f : 1.0 - f;
                sc *= fmax(IV_PC_FLOOR_MS, pc * dist) / fmax(IV_PC_FLOOR_MS, avg[d] * dist);
            }
            if (sc > bsc * (1.0 + 1e-9) + 1e-12) {
                bsc = sc;
                bs = s;
                bc = c;
                best->lo = (uint32_t)a;
                best->hi = (uint32_t)e;
            }
        }
    }
    if (bs > 0.0) {
        best->rhs = (int32_t)floor(bc);
        best->score = bs;
        best->up = bc - floor(bc) >= 0.5;
        best->mass_lo = bc - floor(bc);
        best->mass_hi = 1.0 - best->mass_lo;
    }
}

/* BP_BRANCH, first: the interval count, which ends the choice when it is at least
 * COUNT_MIN_SCORE from an integer. */
static hv_status_t count_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    bp_choose_count(b, call->x, call->split);
    call->done = call->split->score >= COUNT_MIN_SCORE;
    return HV_OK;
}

const bp_plugin_t bp_branch_count = {"count", BP_BRANCH, 200, 0, count_exec};
