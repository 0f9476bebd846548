/* Branch-and-price (bp.h). The root's first stabilisation centre: subgradient ascent, or
 * the paper's LP duals on large instances. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bp.h"
#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_model.h"
#include "hv/milp_status.h"
#include "hv/plan_status.h"

/* A stabilisation centre for the root from the paper's model: its LP relaxation's duals of
 * the assignment rows are duals for the master too, and the Lagrangian bound at them is at
 * least that LP's bound. Best effort: on any failure the root starts without a centre. */
void bp_compact_centre(bp_t *b, double limit_s)
{
    double t0 = hv_milp_now_s();
    hv_milp_model_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.link_disaggregated = 0; /* the small LP: its duals are a centre, not the bound */
    hv_milp_model_t m;
    if (hv_milp_model_build(b->inst, &mo, 0, &m) != HV_OK) {
        return;
    }
    glp_smcp sp;
    glp_init_smcp(&sp);
    sp.msg_lev = GLP_MSG_OFF;
    sp.meth = GLP_DUALP;
    sp.tm_lim = hv_milp_limit_ms(fmin(limit_s, b->t_deadline - hv_milp_now_s()));
    glp_scale_prob(m.lp, GLP_SF_AUTO);
    if (glp_simplex(m.lp, &sp) == 0 && glp_get_status(m.lp) == GLP_OPT) {
        /* the model's first rows are the assignment rows, in fruit order */
        for (size_t f = 0; f < b->nf; ++f) {
            b->m.pi_c[f] =
                b->m.row_of_fruit[f] ? 1000.0 * glp_get_row_dual(m.lp, b->m.row_of_fruit[f]) : 0.0;
        }
        double lag;
        int added;
        if (bp_price_at(b, b->m.pi_c, b->m.sg_lp, &lag, &added) == HV_OK) {
            b->m.center_lag = lag;
            b->m.root_centre = 1;
        }
    }
    hv_milp_model_free(&m);
    if (b->opt->verbose >= 1) {
        fprintf(stderr, "price: centre from the paper's LP, bound %.3f s in %.2f s\n",
                b->m.center_lag / 1000.0, hv_milp_now_s() - t0);
    }
}

/* The root's first stabilisation centre by subgradient ascent on the Lagrangian of the
 * fruit rows, from zero duals: a step prices every stop (about 2 ms at alpha 4, against
 * about 8 ms for a round of the master LP), so `steps` steps bring the bound near the root
 * LP's before the master's first solve, and the column generation only has to finish
 * from there (SOLVER.md's history). Polyak steps towards the incumbent along the subgradient
 * deflected by ASCENT_DEFLECT of the last direction (it zig-zags less), halved after 4
 * steps without a better bound; the duals stay >= 0, so every step's value is a valid
 * bound. The best pattern of every stop in the second half of the steps joins the master. */
hv_status_t bp_ascent_centre(bp_t *b, int steps)
{
    size_t nf = b->nf;
    double *pi = calloc(nf + 1, sizeof *pi), *g = malloc((nf + 1) * sizeof *g),
           *d = calloc(nf + 1, sizeof *d), *pi_best = calloc(nf + 1, sizeof *pi_best);
    hv_status_t st =
        pi != NULL && g != NULL && d != NULL && pi_best != NULL ? HV_OK : HV_ERR_PLAN_NOMEM;
    double best = -INFINITY, theta = 1.0, t0 = hv_milp_now_s();
    int since = 0, it = 0;
    long added = 0;
    for (; st == HV_OK && it < steps && !bp_must_stop(b); ++it) {
        double lag = b->travel_ms;
        for (size_t f = 0; f < nf; ++f) {
            lag += pi[f];
            g[f] = b->m.row_of_fruit[f] ? 1.0 : 0.0; /* 1 - the times f is covered */
        }
        for (size_t p = 0; p < b->ns && st == HV_OK; ++p) {
            if (b->m.row_of_stop[p] == 0) {
                continue;
            }
            size_t nl, nr, n_sel;
            double v, time;
            bp_stop_items(b, p, pi, 1, &nl, &nr);
            st = hv_pricer_best(&b->m.pricer, b->m.itl, nl, b->m.itr, nr, b->tau_ms, NULL, 0.0, &v,
                                b->m.sel, &n_sel, &time);
            if (st != HV_OK || time < 0.0) {
                continue; /* time < 0: no pattern below 0, the stop stays closed */
            }
            lag += v;
            for (size_t q = 0; q < n_sel; ++q) {
                g[b->m.sel[q]] -= 1.0;
            }
            int r = 2 * it >= steps ? bp_pattern_add(b, (uint32_t)p, b->m.sel, (uint32_t)n_sel,
                                                     b->tau_ms + time)
                                    : 0;
            st = r < 0 ? HV_ERR_PLAN_NOMEM : HV_OK;
            added += r;
        }
        if (st != HV_OK) {
            break;
        }
        if (lag > best) {
            best = lag;
            memcpy(pi_best, pi, nf * sizeof *pi);
            since = 0;
        } else if (++since >= 4) {
            theta *= 0.5;
            since = 0;
        }
        double g2 = 0.0, norm = 0.0;
        for (size_t f = 0; f < nf; ++f) {
            d[f] = g[f] + ASCENT_DEFLECT * d[f];
            g2 += g[f] * g[f];
            norm += d[f] * d[f];
        }
        if (g2 == 0.0 || !isfinite(b->inc.ub_ms)) {
            break; /* every fruit covered once (these duals are optimal), or no target */
        }
        double step = theta * (b->inc.ub_ms - lag) / norm;
        for (size_t f = 0; f < nf; ++f) {
            pi[f] = fmax(0.0, pi[f] + step * d[f]);
        }
    }
    if (st == HV_ERR_MILP_DEADLINE) {
        st = HV_OK; /* the search sees the deadline */
    }
    if (st == HV_OK && isfinite(best)) {
        memcpy(b->m.pi_c, pi_best, nf * sizeof *pi_best);
        b->m.center_lag = best;
        b->m.root_centre = 1;
    }
    if (b->opt->verbose >= 1) {
        fprintf(stderr, "price: centre by %d ascent steps, bound %.3f s in %.2f s, %ld columns\n",
                it, best / 1000.0, hv_milp_now_s() - t0, added);
    }
    free(pi);
    free(g);
    free(d);
    free(pi_best);
    return st;
}
