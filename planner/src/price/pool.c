/* Branch-and-price (bp.h). The column pool: stop patterns, their hash, their master
 * columns, and a plan's patterns. */
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

static uint64_t bp_pattern_hash(uint32_t stop, const uint32_t *f, uint32_t n)
{
    uint64_t h = 1469598103934665603ull ^ stop;
    for (uint32_t k = 0; k < n; ++k) {
        h = (h ^ f[k]) * 1099511628211ull;
        h ^= h >> 29;
    }
    return h;
}

static int bp_pattern_equal(const bp_t *b, int32_t k, uint32_t stop, const uint32_t *f, uint32_t n)
{
    const pattern_t *p = &b->m.pat[k];
    return p->stop == stop && p->n == n && memcmp(b->m.pf + p->first, f, n * sizeof *f) == 0;
}

int bp_iv_reserve(bp_t *b, size_t n)
{
    size_t ci = b->m.iv_cap, cv = b->m.iv_cap;
    if (!hv_grow((void **)&b->m.ind, &ci, n + 1, sizeof *b->m.ind) ||
        !hv_grow((void **)&b->m.val, &cv, n + 1, sizeof *b->m.val)) {
        return 0;
    }
    b->m.iv_cap = ci < cv ? ci : cv;
    return 1;
}

static int bp_hash_insert(bp_t *b, int32_t k);

int bp_hash_rebuild(bp_t *b, size_t cap)
{
    free(b->m.hslot);
    b->m.hslot = malloc(cap * sizeof *b->m.hslot);
    if (b->m.hslot == NULL) {
        return 0;
    }
    b->m.hcap = cap;
    for (size_t s = 0; s < cap; ++s) {
        b->m.hslot[s] = -1;
    }
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        bp_hash_insert(b, (int32_t)k);
    }
    return 1;
}

static int bp_hash_insert(bp_t *b, int32_t k)
{
    const pattern_t *p = &b->m.pat[k];
    size_t s = (size_t)(bp_pattern_hash(p->stop, b->m.pf + p->first, p->n) & (b->m.hcap - 1));
    while (b->m.hslot[s] >= 0) {
        s = (s + 1) & (b->m.hcap - 1);
    }
    b->m.hslot[s] = k;
    return 1;
}

/* The index of the pattern (stop, f[0..n)) in the pool, -1 when new. */
int32_t bp_pattern_find(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n)
{
    size_t s = (size_t)(bp_pattern_hash(stop, f, n) & (b->m.hcap - 1));
    for (; b->m.hslot[s] >= 0; s = (s + 1) & (b->m.hcap - 1)) {
        if (bp_pattern_equal(b, b->m.hslot[s], stop, f, n)) {
            return b->m.hslot[s];
        }
    }
    return -1;
}

/* open: 0 closed (fixed at 0), 1 open, 2 fixed at 1 */
void bp_col_open(bp_t *b, size_t j, unsigned char open)
{
    if (open != b->m.pat_open[j]) {
        b->m.pat_open[j] = open;
        double v = open == 2 ? 1.0 : 0.0;
        glp_set_col_bnds(b->m.lp, b->m.pat[j].col, open == 1 ? GLP_LO : GLP_FX, v, v);
    }
}

static int bp_cmp_u32(const void *a, const void *c)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)c;
    return x < y ? -1 : x > y;
}

/* Cost of the pair (fruit f, stop p) in ms, or -1 when not reachable. */
static double bp_pair_ms(const bp_t *b, uint32_t f, uint32_t p)
{
    size_t k = hv_instance_pair_index(b->inst, f, p);
    return k == SIZE_MAX ? -1.0 : 1000.0 * b->inst->pairs[k].cost_s;
}

/* The arms' times (ms) per stop of the assignment stop_of (HV_NO_STOP: none), added into
 * arm[2 p] (left) and arm[2 p + 1] (right), and the stops it uses marked in used[]. */
void bp_stop_arms(const bp_t *b, const uint32_t *stop_of, double *arm, unsigned char *used)
{
    for (size_t f = 0; f < b->nf; ++f) {
        uint32_t p = stop_of[f];
        if (p != HV_NO_STOP) {
            arm[2 * p + (b->inst->fruits[f].side == HV_SIDE_LEFT ? 0 : 1)] +=
                bp_pair_ms(b, (uint32_t)f, p);
            used[p] = 1;
        }
    }
}

/* Stop p's cost (ms) from stop_arms' arrays: tau + its slower arm's time, 0 when unused. */
double bp_stop_cost_ms(const bp_t *b, const double *arm, const unsigned char *used, size_t p)
{
    return used[p] ? b->tau_ms + fmax(arm[2 * p], arm[2 * p + 1]) : 0.0;
}

/* The arms' pick times (ms, indexed by hv_side_t) of the pattern of fruits f[0 .. n) at
 * `stop` into w. Returns 0 when one of the fruits is not reachable from there. */
int bp_pattern_times(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n, double w[2])
{
    w[0] = w[1] = 0.0;
    for (uint32_t q = 0; q < n; ++q) {
        double c = bp_pair_ms(b, f[q], stop);
        if (c < 0.0) {
            return 0;
        }
        w[b->inst->fruits[f[q]].side] += c;
    }
    return 1;
}

/* Which arms bind in the pattern of fruits f[0 .. n) at `stop`: bit s set when side s's
 * time is the larger (both when equal). */
static unsigned char bp_pattern_binds(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n)
{
    double w[2];
    bp_pattern_times(b, stop, f, n, w);
    return (unsigned char)((w[HV_SIDE_LEFT] >= w[HV_SIDE_RIGHT] ? 1u << HV_SIDE_LEFT : 0u) |
                           (w[HV_SIDE_RIGHT] >= w[HV_SIDE_LEFT] ? 1u << HV_SIDE_RIGHT : 0u));
}

/* Add the pattern (stop, fruits f[0..n), sorted here) as a master column unless known.
 * Returns 1 added, 0 known, -1 out of memory. */
int bp_pattern_add(bp_t *b, uint32_t stop, uint32_t *f, uint32_t n, double cost_ms)
{
    qsort(f, n, sizeof *f, bp_cmp_u32);
    int32_t known = bp_pattern_find(b, stop, f, n);
    if (known >= 0) {
        return 0;
    }
    if (!hv_grow((void **)&b->m.pat, &b->m.pat_cap, b->m.n_pat + 1, sizeof *b->m.pat) ||
        !hv_grow((void **)&b->m.pf, &b->m.pf_cap, b->m.pf_len + n, sizeof *b->m.pf)) {
        return -1;
    }
    if (!hv_grow((void **)&b->m.pat_open, &b->m.open_cap, b->m.n_pat + 1, 1) ||
        !hv_grow((void **)&b->m.pat_dead, &b->m.dead_cap, b->m.n_pat + 1, 1)) {
        return -1;
    }
    b->m.pat_dead[b->m.n_pat] = 0;
    b->m.pat[b->m.n_pat] =
        (pattern_t){stop, (uint32_t)b->m.pf_len, n, cost_ms, 0, bp_pattern_binds(b, stop, f, n)};
    memcpy(b->m.pf + b->m.pf_len, f, n * sizeof *f);
    b->m.pf_len += n;
    b->m.pat_open[b->m.n_pat] = 1;
    int32_t k = (int32_t)b->m.n_pat++;
    if (2 * b->m.n_pat > b->m.hcap) {
        if (!bp_hash_rebuild(b, 2 * b->m.hcap)) {
            return -1;
        }
    } else {
        bp_hash_insert(b, k);
    }
    if (!bp_iv_reserve(b, n + 2 + b->m.n_crow + b->cuts.src.n)) {
        return -1;
    }
    int j = glp_add_cols(b->m.lp, 1);
    b->m.pat[k].col = j;
    int len = 0;
    for (uint32_t q = 0; q < n; ++q) {
        b->m.ind[++len] = b->m.row_of_fruit[f[q]];
        b->m.val[len] = 1.0;
    }
    b->m.ind[++len] = b->m.row_of_stop[stop];
    b->m.val[len] = 1.0;
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        if (b->m.crow[r].lo <= stop && stop <= b->m.crow[r].hi) {
            b->m.ind[++len] = b->m.crow[r].row;
            b->m.val[len] = 1.0;
        }
    }
    size_t nh = hv_src_hits(&b->cuts.src, f, n, b->cuts.src_hit);
    for (size_t h = 0; h < nh; ++h) {
        b->m.ind[++len] = b->cuts.src_row[b->cuts.src_hit[h]];
        b->m.val[len] = 1.0;
    }
    glp_set_mat_col(b->m.lp, j, len, b->m.ind, b->m.val);
    glp_set_col_bnds(b->m.lp, j, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(b->m.lp, j, cost_ms);
    return 1;
}

/* The patterns of an assignment as columns (a plan's stops are good columns to start with). */
int bp_add_assignment_columns(bp_t *b, const uint32_t *stop_of)
{
    for (size_t p = 0; p < b->ns; ++p) {
        uint32_t n = 0;
        double wl = 0.0, wr = 0.0;
        for (size_t f = 0; f < b->nf; ++f) {
            if (stop_of[f] == p) {
                double c = bp_pair_ms(b, (uint32_t)f, (uint32_t)p);
                if (c < 0) {
                    return -1;
                }
                *(b->inst->fruits[f].side == HV_SIDE_LEFT ? &wl : &wr) += c;
                b->m.sel[n++] = (uint32_t)f;
            }
        }
        if (n > 0 && bp_pattern_add(b, (uint32_t)p, b->m.sel, n, b->tau_ms + fmax(wl, wr)) < 0) {
            return -1;
        }
    }
    return 0;
}

/* Each fruit alone at its cheapest stop as a starting column: the first duals then stay
 * near pick costs instead of the artificials' big cost (SOLVER.md's history). */
int bp_add_start_columns(bp_t *b)
{
    const hv_instance_t *in = b->inst;
    for (size_t f = 0; f < b->nf; ++f) {
        size_t bk = SIZE_MAX;
        for (size_t k = in->fruit_begin[f]; k < in->fruit_begin[f + 1]; ++k) {
            if (!b->fix.pair_dead[k] &&
                (bk == SIZE_MAX || in->pairs[k].cost_s < in->pairs[bk].cost_s)) {
                bk = k;
            }
        }
        if (bk != SIZE_MAX) {
            b->m.sel[0] = (uint32_t)f;
            if (bp_pattern_add(b, in->pairs[bk].stop, b->m.sel, 1,
                               b->tau_ms + 1000.0 * in->pairs[bk].cost_s) < 0) {
                return -1;
            }
        }
    }
    return 0;
}
