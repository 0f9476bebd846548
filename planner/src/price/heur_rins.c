/* Branch-and-price (bp.h). Primal heuristic "rins": relaxation-induced neighbourhoods of
 * the plan (milp_rins.h), solved through the context's sub-solver. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bp.h"
#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_rins.h"
#include "hv/milp_status.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* Pattern k's value at the master point x of columns 1..ncol (0 for the patterns added
 * since, which it does not hold). */
static double bp_point_value(const bp_t *b, const double *x, int ncol, size_t k)
{
    return b->m.pat[k].col <= ncol ? x[b->m.pat[k].col] : 0.0;
}

/* The fruits on which the master point x (columns 1..ncol: the patterns added since are
 * not in it) and the incumbent disagree (x holds less than all of the fruit at its
 * incumbent stop), in order of their incumbent stop, into ord[]; returns their number. */
static size_t bp_rins_disagree(const bp_t *b, const double *x, int ncol, double *agree,
                               uint32_t *ord)
{
    memset(agree, 0, b->nf * sizeof *agree);
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        double v = bp_point_value(b, x, ncol, k);
        for (uint32_t q = 0; v > LAMBDA_EPS && q < b->m.pat[k].n; ++q) {
            uint32_t f = b->m.pf[b->m.pat[k].first + q];
            agree[f] += b->inc.best[f] == b->m.pat[k].stop ? v : 0.0;
        }
    }
    size_t n = 0;
    for (size_t f = 0; f < b->nf; ++f) {
        if (b->inc.best[f] != HV_NO_STOP && agree[f] < 1.0 - LAMBDA_EPS) {
            ord[n++] = (uint32_t)f;
        }
    }
    for (size_t i = 1; i < n; ++i) { /* insertion sort: nearly ordered by fruit already */
        uint32_t f = ord[i];
        size_t j = i;
        for (; j > 0 && b->inc.best[ord[j - 1]] > b->inc.best[f]; --j) {
            ord[j] = ord[j - 1];
        }
        ord[j] = f;
    }
    return n;
}

/* Relaxation-induced neighbourhoods of the incumbent at master point x (columns 1..ncol;
 * milp_rins.h): the fruits on which they disagree are re-planned exactly, RINS_MAX_FREE
 * at a time along the row, each over the stops where x holds it and its incumbent stop,
 * the rest kept. After a better plan the disagreement is taken again from the same place. */
static hv_status_t bp_rins_at(bp_t *b, const double *x, int ncol)
{
    double t0 = hv_milp_now_s();
    size_t nf = b->nf;
    double *agree = malloc((nf + 1) * sizeof *agree);
    uint32_t *ord = malloc((nf + 1) * sizeof *ord);
    unsigned char *freed = calloc(nf + 1, 1);
    unsigned char *open = calloc(b->inst->n_pairs + 1, 1);
    hv_assignment_t a;
    if (agree == NULL || ord == NULL || freed == NULL || open == NULL ||
        hv_assignment_alloc(&a, nf) != HV_OK) {
        free(agree);
        free(ord);
        free(freed);
        free(open);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        if (bp_point_value(b, x, ncol, k) <= LAMBDA_EPS) {
            continue; /* x does not hold it: its pairs stay closed */
        }
        for (uint32_t q = 0; q < b->m.pat[k].n; ++q) {
            size_t pk =
                hv_instance_pair_index(b->inst, b->m.pf[b->m.pat[k].first + q], b->m.pat[k].stop);
            if (pk != SIZE_MAX) {
                open[pk] = 1;
            }
        }
    }
    hv_status_t st = HV_OK;
    size_t at = 0; /* the first disagreeing fruit (in row order) of the next neighbourhood */
    size_t n = bp_rins_disagree(b, x, ncol, agree, ord);
    for (;;) {
        double left = fmin(b->t_deadline, t0 + RINS_CALL_S) - hv_milp_now_s();
        if (at >= n || left <= 0.0 || bp_must_stop(b)) {
            break;
        }
        size_t end = at + RINS_MAX_FREE < n ? at + RINS_MAX_FREE : n;
        for (size_t i = at; i < end; ++i) {
            freed[ord[i]] = 1;
        }
        memcpy(a.fruit_stop, b->inc.best, nf * sizeof *b->inc.best);
        double t = b->inc.ub_ms / 1000.0;
        int better = 0;
        st = hv_rins_improve(b->inst, b->opt, b->sub, freed, open, fmin(RINS_LIMIT_S, left), &a, &t,
                             &better, NULL);
        for (size_t i = at; i < end; ++i) {
            freed[ord[i]] = 0;
        }
        b->stats.rins.calls++;
        b->stats.rins.freed += (long)(end - at);
        if (st == HV_OK && better) {
            b->stats.rins.better++;
            if (b->opt->verbose >= 1) {
                fprintf(stderr, "price: %.2f s: a neighbourhood of %zu fruits: %.3f -> %.3f s\n",
                        hv_milp_now_s() - b->t_start, end - at, b->inc.ub_ms / 1000.0, t);
            }
            st = bp_offer_plan(b, &a, t);
        }
        if (st != HV_OK) {
            break;
        }
        if (better) {
            n = bp_rins_disagree(b, x, ncol, agree, ord); /* against the new incumbent */
        } else {
            at = end >= n ? n : at + RINS_MAX_FREE / 2; /* the next overlapping run */
        }
    }
    hv_assignment_free(&a);
    free(agree);
    free(ord);
    free(freed);
    free(open);
    b->stats.rins.t_s += hv_milp_now_s() - t0;
    return st;
}

/* BP_NODE_LP, after the rounding: every opt->rins_every nodes once the plan is near the
 * root's bound, and at the root while it is far: there alpha 4 seed 4 found its optimum
 * 2-3 s sooner (SOLVER.md's history). */
static hv_status_t rins_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    int root_far = call->far && b->tree.nodes[call->node].parent < 0 && !b->tree.is_worker;
    if (b->opt->rins_every > 0 &&
        (root_far || (!call->far && ++b->stats.rins_wait >= b->opt->rins_every)) &&
        !bp_must_stop(b)) {
        b->stats.rins_wait = 0;
        return bp_rins_at(b, call->x, call->ncol);
    }
    return HV_OK;
}

const bp_plugin_t bp_heur_rins = {"rins", BP_NODE_LP, 100, -1, rins_exec};
