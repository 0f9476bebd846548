/* Branch-and-price (bp.h). Separator "subset-row": subset-row cuts on fruit triples at the
 * root (milp_srcuts.h), dropped when not worth their cost or slack. */
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

/* One round of subset-row cuts (milp_srcuts.h) on the master's point: the violated ones
 * become "<= 1" rows over the patterns holding two or more of their fruits; their duals
 * start at 0, where every bound so far stays valid. */
static hv_status_t bp_separate_cuts(bp_t *b, size_t *added)
{
    *added = 0;
    b->cuts.sr_rounds++;
    size_t first = b->cuts.src.n, room = SR_MAX - first;
    hv_src_col_t *cols = malloc((b->m.n_pat + 1) * sizeof *cols);
    if (cols == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    size_t n = 0;
    for (size_t j = 0; j < b->m.n_pat; ++j) {
        double x = glp_get_col_prim(b->m.lp, b->m.pat[j].col);
        if (x > LAMBDA_EPS) {
            cols[n++] = (hv_src_col_t){b->m.pf + b->m.pat[j].first, b->m.pat[j].n, x};
        }
    }
    hv_status_t st = room == 0 ? HV_OK
                               : hv_src_separate(&b->cuts.src, b->inst, cols, n,
                                                 room < SR_PER_ROUND ? room : SR_PER_ROUND,
                                                 SR_PER_FRUIT, SR_MIN_VIOL, added);
    free(cols);
    if (st != HV_OK || *added == 0) {
        return st;
    }
    /* the new rows' columns, cut by cut: count, then fill (CSR over the new cuts) */
    size_t *beg = calloc(*added + 2, sizeof *beg), len = 0;
    int *col = NULL;
    for (int pass = 0; pass < 2 && beg != NULL; ++pass) {
        for (size_t j = 0; j < b->m.n_pat; ++j) {
            size_t nh = hv_src_hits(&b->cuts.src, b->m.pf + b->m.pat[j].first, b->m.pat[j].n,
                                    b->cuts.src_hit);
            for (size_t h = 0; h < nh; ++h) {
                if (b->cuts.src_hit[h] >= first) {
                    size_t c = b->cuts.src_hit[h] - first;
                    if (pass == 0) {
                        beg[c + 2]++;
                    } else {
                        col[beg[c + 1]++] = b->m.pat[j].col;
                    }
                }
            }
        }
        if (pass == 0) {
            for (size_t c = 0; c < *added; ++c) {
                beg[c + 2] += beg[c + 1];
            }
            len = beg[*added + 1];
            col = malloc((len + 1) * sizeof *col);
            if (col == NULL) {
                break;
            }
        }
    }
    if (beg == NULL || col == NULL || !bp_iv_reserve(b, len + 1)) {
        free(beg);
        free(col);
        return HV_ERR_PLAN_NOMEM;
    }
    int r0 = glp_add_rows(b->m.lp, (int)*added);
    for (size_t c = 0; c < *added; ++c) { /* beg[c] .. beg[c + 1]: cut first + c's columns */
        int row = r0 + (int)c, m = 0;
        for (size_t q = beg[c]; q < beg[c + 1]; ++q) {
            b->m.ind[++m] = col[q];
            b->m.val[m] = 1.0;
        }
        glp_set_mat_row(b->m.lp, row, m, b->m.ind, b->m.val);
        glp_set_row_bnds(b->m.lp, row, GLP_UP, 0.0, 1.0);
        glp_set_row_stat(b->m.lp, row, GLP_BS); /* keeps the current basis valid */
        b->cuts.src_row[first + c] = row;
        b->m.pi_lp[b->nf + first + c] = b->m.pi_c[b->nf + first + c] = 0.0;
        b->m.pi_sep[b->nf + first + c] = b->fix.root_pi[b->nf + first + c] = 0.0;
    }
    free(beg);
    free(col);
    return HV_OK;
}

/* Deletes every cut row (at the root, before any count row or kept basis). The master is
 * re-solved without them; a basis left without a basic variable is rebuilt by lp_solve. */
static hv_status_t bp_drop_cuts(bp_t *b)
{
    if (!bp_iv_reserve(b, b->cuts.src.n + 1)) {
        return HV_ERR_PLAN_NOMEM;
    }
    int *num = b->m.ind;
    for (size_t c = 0; c < b->cuts.src.n; ++c) {
        num[c + 1] = b->cuts.src_row[c];
    }
    glp_del_rows(b->m.lp, (int)b->cuts.src.n, num);
    b->cuts.sr_dropped += (long)b->cuts.src.n;
    hv_src_clear(&b->cuts.src);
    b->cuts.sr_rounds = b->cuts.sr_max;
    b->m.center_lag = -INFINITY; /* the centre's bound counted the cuts' duals */
    return HV_OK;
}

/* Deletes the cut rows that are slack at the solved root (basic, a zero dual in the
 * master and in the centre): they cut nothing there, while every cut row makes each
 * master solve dearer in the tree (SOLVER.md's history). The centre and its bound stay as they are,
 * the basis stays valid (only basic rows go). *n_dropped: how many went. */
static hv_status_t bp_purge_slack_cuts(bp_t *b, size_t *n_dropped)
{
    size_t n = b->cuts.src.n, nf = b->nf, m = 0, d = 0;
    unsigned char *keep = malloc(n + 1);
    if (keep == NULL || !bp_iv_reserve(b, n + 1)) {
        free(keep);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t c = 0; c < n; ++c) {
        keep[c] = glp_get_row_stat(b->m.lp, b->cuts.src_row[c]) != GLP_BS ||
                  b->m.pi_lp[nf + c] < -RC_EPS_MS || b->m.pi_c[nf + c] < -RC_EPS_MS;
        if (!keep[c]) {
            b->m.ind[++d] = b->cuts.src_row[c];
        }
    }
    *n_dropped = d;
    if (d == 0) {
        free(keep);
        return HV_OK;
    }
    glp_del_rows(b->m.lp, (int)d, b->m.ind);
    for (size_t c = 0; c < n; ++c) {
        if (keep[c]) {
            int below = 0; /* GLPK renumbers the rows after a deleted one */
            for (size_t q = 1; q <= d; ++q) {
                below += b->m.ind[q] < b->cuts.src_row[c];
            }
            b->cuts.src_row[m] = b->cuts.src_row[c] - below;
            b->m.pi_c[nf + m] = b->m.pi_c[nf + c]; /* the master's duals are read afresh */
            ++m;
        }
    }
    hv_status_t st = hv_src_keep(&b->cuts.src, keep);
    free(keep);
    b->cuts.sr_dropped += (long)d;
    return st;
}

/* BP_ROOT_LP (the root's master converged): a round of cuts while rounds are left (the
 * master solves again), then, once no round adds any, the cuts dropped when they raised
 * the root's bound by less than sr_keep_gain, or their slack ones purged (sr_purge). */
static hv_status_t sep_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    hv_status_t st;
    if (b->cuts.sr_rounds < b->cuts.sr_max) {
        size_t n_cuts;
        if (b->cuts.sr_rounds == 0) {
            b->cuts.sr_lb0 = b->tree.nodes[call->node].lb_ms;
        }
        if ((st = bp_separate_cuts(b, &n_cuts)) != HV_OK) {
            return st;
        }
        if (n_cuts > 0) {
            b->m.lp_dual_next = 1; /* the point violates the new rows: repair by the dual */
            /* the centre stays valid (its cut duals 0) while the new duals of the cuts
             * can be extreme: priced unsmoothed they blew the pricing up (alpha 4 seed
             * 5: 200,000 frontier points a round, SOLVER.md's history) */
            b->m.smooth = SMOOTHING;
            call->added = 1;
            return HV_OK;
        }
    }
    if (b->cuts.src.n > 0 &&
        b->tree.nodes[call->node].lb_ms - b->cuts.sr_lb0 < b->opt->sr_keep_gain * b->cuts.sr_lb0) {
        if ((st = bp_drop_cuts(b)) != HV_OK) { /* not worth their cost in the tree */
            return st;
        }
        call->added = 1;
        return HV_OK; /* the root keeps its bound; the master converges without them */
    }
    if (b->cuts.src.n > 0 && b->opt->sr_purge) {
        size_t n_dropped;
        if ((st = bp_purge_slack_cuts(b, &n_dropped)) != HV_OK) {
            return st;
        }
        if (n_dropped > 0) {
            call->added = 1;
            return HV_OK; /* the same point and duals: one master solve restores them */
        }
    }
    return HV_OK;
}

const bp_plugin_t bp_sep_subset_row = {"subset-row", BP_ROOT_LP, 100, 0, sep_exec};
