/* Branch-and-price (bp.h). Dominated stops: stops no optimal plan needs, left out before
 * the root.
 *
 * Stop q dominates stop p when q reaches every fruit p reaches, each at a pick cost no
 * higher. Then any plan using p is matched by one that does not: p's pattern moves to q
 * when q is unused (no arm's time rises), or joins q's pattern (each arm's time is at most
 * the sum of the two, max(a + b, c + d) <= max(a, c) + max(b, d), and one tau is saved).
 * Of stops that dominate each other (equal costs to the ms on the same fruits) the lowest
 * keeps its pairs; every other dominated stop's pairs are fixed out for the whole search,
 * as reduced-cost fixing fixes pairs, so the optimum is unchanged. */
#include <stdlib.h>

#include "bp.h"

/* q dominates p: every pair of p has one at q with a cost no higher (pairs of a stop come
 * in ascending fruit order). */
static int dominates(const bp_t *b, size_t q, size_t p)
{
    const hv_pair_t *pr = b->inst->pairs;
    size_t i = b->m.stop_begin[p], j = b->m.stop_begin[q];
    size_t ie = b->m.stop_begin[p + 1], je = b->m.stop_begin[q + 1];
    if (je - j < ie - i) {
        return 0;
    }
    for (; i < ie; ++i) {
        const hv_pair_t *a = &pr[b->m.stop_pair[i]];
        while (j < je && pr[b->m.stop_pair[j]].fruit < a->fruit) {
            ++j;
        }
        if (j == je || pr[b->m.stop_pair[j]].fruit != a->fruit ||
            pr[b->m.stop_pair[j]].cost_s > a->cost_s) {
            return 0;
        }
    }
    return 1;
}

long bp_fix_dominated_stops(bp_t *b)
{
    long n_stops = 0;
    for (size_t p = 0; p < b->ns; ++p) {
        if (b->m.stop_begin[p] == b->m.stop_begin[p + 1]) {
            continue;
        }
        int out = 0;
        for (size_t q = 0; q < b->ns && !out; ++q) {
            /* strictly, or equal with q lower: one of a class of equal stops stays */
            out = q != p && dominates(b, q, p) && (q < p || !dominates(b, p, q));
        }
        if (out) {
            for (size_t i = b->m.stop_begin[p]; i < b->m.stop_begin[p + 1]; ++i) {
                if (!b->fix.pair_dead[b->m.stop_pair[i]]) {
                    b->fix.pair_dead[b->m.stop_pair[i]] = 1;
                    b->fix.pairs_fixed++;
                }
            }
            n_stops++;
        }
    }
    return n_stops;
}
