/* Branch-and-price (bp.h). Branching rule "fruit": split one fruit's stop interval, chosen
 * by pseudocosts (weighted by where its arm binds) or by balance; it also records the
 * pseudocosts a solved node taught. */
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

static int bp_by_fruit_stop(const void *a, const void *c)
{
    const mass_t *u = a, *v = c;
    if (u->fruit != v->fruit) {
        return u->fruit < v->fruit ? -1 : 1;
    }
    return u->stop < v->stop ? -1 : (u->stop > v->stop);
}

/* The average pseudocost of fruit f's split in direction d (0 "<= stop", 1 "> stop"): its
 * own when it was branched on in that direction, else the average over all fruits, else 1. */
static double bp_pseudocost(const bp_t *b, uint32_t f, int d)
{
    return bp_pc_mean(&b->tree.pc, f, d, 1.0);
}

/* The fruit whose stop is split most evenly by the master point, at the stop that halves
 * its mass (with opt->pseudocost: the fruit and stop of the largest product of the two
 * children's estimated bound rises, mass times pseudocost). score 0 when no fruit is
 * split. */
static hv_status_t bp_choose_split(bp_t *b, const double *x, split_t *best)
{
    size_t n = 0, cap = 0;
    mass_t *m = NULL;
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        double v = x[b->m.pat[k].col];
        if (v <= LAMBDA_EPS) {
            continue;
        }
        if (!hv_grow((void **)&m, &cap, n + b->m.pat[k].n, sizeof *m)) {
            free(m);
            return HV_ERR_PLAN_NOMEM;
        }
        for (uint32_t q = 0; q < b->m.pat[k].n; ++q) {
            uint32_t f = b->m.pf[b->m.pat[k].first + q];
            int binds = (b->m.pat[k].binds >> b->inst->fruits[f].side) & 1;
            m[n++] = (mass_t){f, b->m.pat[k].stop, v, binds ? v : 0.0};
        }
    }
    for (size_t f = 0; b->skip_ms != NULL && f < b->nf; ++f) {
        double v = b->m.row_of_fruit[f] ? x[b->m.row_of_fruit[f]] : 0.0;
        if (bp_skip_open(b, f) && v > LAMBDA_EPS) { /* uncovered: mass at the virtual stop */
            if (!hv_grow((void **)&m, &cap, n + 1, sizeof *m)) {
                free(m);
                return HV_ERR_PLAN_NOMEM;
            }
            m[n++] = (mass_t){(uint32_t)f, (uint32_t)b->ns, v, 0.0};
        }
    }
    qsort(m, n, sizeof *m, bp_by_fruit_stop);
    if (b->tree.share != NULL && b->opt->pseudocost) {
        hv_share_pc_get(b->tree.share, &b->tree.pc); /* what both workers learnt */
    }
    best->score = 0.0;
    for (size_t i = 0; i < n;) {
        size_t e = i;
        double tot = 0.0, tot_binds = 0.0;
        while (e < n && m[e].fruit == m[i].fruit) {
            tot_binds += m[e].x_binds;
            tot += m[e++].x;
        }
        /* opt->binding_splits: a fruit whose arm has slack wherever the point puts it can
         * usually move at no cost (alpha 4: the left fruits at stops where the right arm
         * binds), so a split of it rarely raises the bound (SOLVER.md's history) */
        double w_binds = b->opt->binding_splits ? fmax(tot_binds / tot, BIND_MIN_WEIGHT) : 1.0;
        double cum = 0.0;
        double pc_lo = b->opt->pseudocost ? bp_pseudocost(b, m[i].fruit, 0) : 0.0;
        double pc_hi = b->opt->pseudocost ? bp_pseudocost(b, m[i].fruit, 1) : 0.0;
        for (size_t k = i + 1; k < e && k < n; ++k) {
            cum += m[k - 1].x;
            if (m[k].stop == m[k - 1].stop) {
                continue;
            }
            double s = fmin(cum, tot - cum) / tot;
            /* prefer balanced splits, then splits between distant stops */
            double score = s + 1e-4 * (double)(m[e - 1].stop - m[i].stop);
            if (b->opt->pseudocost && s > LAMBDA_EPS) {
                score = w_binds * fmax((tot - cum) * pc_lo, 1e-6) * fmax(cum * pc_hi, 1e-6);
            }
            if (s > LAMBDA_EPS && score > best->score) {
                *best = (split_t){KIND_FRUIT, m[i].fruit, m[k - 1].stop,   0,         0,
                                  0,          score,      cum < 0.5 * tot, tot - cum, cum};
            }
        }
        i = e;
    }
    free(m);
    return HV_OK;
}

/* BP_BRANCH, after the count: a fruit's split replaces the count's when it has any score. */
static hv_status_t fruit_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    split_t fs = {KIND_FRUIT, 0, 0, 0, 0, 0, 0.0, 0, 0.0, 0.0};
    hv_status_t st = bp_choose_split(b, call->x, &fs);
    if (fs.score > 0.0) {
        *call->split = fs;
    }
    return st;
}

const bp_plugin_t bp_branch_fruit = {"fruit", BP_BRANCH, 100, 0, fruit_exec};
