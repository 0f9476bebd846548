/* Branch-and-price (bp.h). Bound plugin "region": regional bounds (milp_region.h) that
 * prove the incumbent optimal over a stretch of stops, through the context's sub-solver;
 * the captured root duals they use. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bp.h"
#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_region.h"
#include "hv/milp_status.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* At the root's converged master, before any cut: its best duals, their stop terms and
 * bound, which the regional bound uses (the cuts' duals would need their penalties in the
 * stretch's sub-problem, which it leaves out: measured, a rise of 0 where these give one). */
static hv_status_t bp_region_capture(bp_t *b)
{
    if (b->opt->region_stops <= 0) { /* also in hv_price_bound's own solves (subsolve options) */
        return HV_OK;
    }
    double lag;
    int added;
    hv_status_t st = bp_price_at(b, b->m.pi_c, b->m.sg_c, &lag, &added);
    if (st == HV_OK) {
        memcpy(b->region.region_pi, b->m.pi_c, b->nf * sizeof *b->region.region_pi);
        memcpy(b->region.region_v, b->m.stop_v, b->ns * sizeof *b->region.region_v);
        b->region.region_lag0 = lag;
    }
    return st;
}

/* The incumbent's gap over the captured bound, per stop: its pattern's cost less its fruits'
 * duals less the stop's term (0 where the plan does not stop: its term then). They sum to
 * incumbent - bound, so where they lie is where a stretch's rise can close the gap. */
static hv_status_t bp_region_gaps(bp_t *b, double *g)
{
    double *arm = calloc(2 * b->ns + 1, sizeof *arm); /* per stop: the left, right arm's time */
    unsigned char *used = calloc(b->ns + 1, 1);
    if (arm == NULL || used == NULL) {
        free(arm);
        free(used);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t p = 0; p < b->ns; ++p) {
        g[p] = -b->region.region_v[p];
    }
    for (size_t f = 0; f < b->nf; ++f) {
        if (b->inc.best[f] != HV_NO_STOP) {
            g[b->inc.best[f]] -= b->region.region_pi[f];
        }
    }
    bp_stop_arms(b, b->inc.best, arm, used);
    for (size_t p = 0; p < b->ns; ++p) {
        g[p] += bp_stop_cost_ms(b, arm, used, p);
        g[p] = fmax(0.0, g[p]); /* round-off, or a pair the pricing left out as fixed */
    }
    free(arm);
    free(used);
    return HV_OK;
}

/* A plan from the stretch [s0, s1]'s best solution `plan` (HV_NO_STOP outside it and for the
 * fruits it leaves out) and the incumbent's stops outside the stretch; a fruit neither
 * places joins the used stop where it adds least to the stop's time (the cheapest stop when
 * none reaches it), and a short local search polishes the result. At the optimum the
 * stretch's best solution is often the optimal plan's part there. */
static hv_status_t bp_region_plan(bp_t *b, const uint32_t *plan, size_t s0, size_t s1)
{
    const hv_instance_t *in = b->inst;
    hv_assignment_t a;
    double *arm = calloc(2 * b->ns + 1, sizeof *arm);
    unsigned char *used = calloc(b->ns + 1, 1);
    if (arm == NULL || used == NULL || hv_assignment_alloc(&a, b->nf) != HV_OK) {
        free(arm);
        free(used);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < b->nf; ++f) {
        a.fruit_stop[f] =
            plan[f] != HV_NO_STOP ? plan[f]
            : (b->inc.best[f] != HV_NO_STOP && (b->inc.best[f] < s0 || b->inc.best[f] > s1))
                ? b->inc.best[f]
                : HV_NO_STOP;
    }
    bp_stop_arms(b, a.fruit_stop, arm, used);
    for (size_t f = 0; f < b->nf; ++f) {
        if (a.fruit_stop[f] != HV_NO_STOP || in->fruit_begin[f] == in->fruit_begin[f + 1]) {
            continue;
        }
        size_t side = in->fruits[f].side == HV_SIDE_LEFT ? 0 : 1, best = SIZE_MAX;
        double best_add = INFINITY;
        for (size_t k = in->fruit_begin[f]; k < in->fruit_begin[f + 1]; ++k) {
            uint32_t p = in->pairs[k].stop;
            double t = arm[2 * p + side] + 1000.0 * in->pairs[k].cost_s;
            double add = used[p] ? fmax(0.0, t - fmax(arm[2 * p], arm[2 * p + 1])) : b->tau_ms + t;
            if (add < best_add) {
                best_add = add;
                best = k;
            }
        }
        uint32_t p = in->pairs[best].stop;
        a.fruit_stop[f] = p;
        arm[2 * p + side] += 1000.0 * in->pairs[best].cost_s;
        used[p] = 1;
    }
    free(arm);
    free(used);
    hv_status_t st = bp_improve_plan(b, &a, REGION_KICKS);
    hv_assignment_free(&a);
    return st;
}

/* [*s0, *s1] grown by REGION_GROW stops on either side, within the row. */
static void bp_region_grow(const bp_t *b, size_t *s0, size_t *s1)
{
    *s0 = *s0 > REGION_GROW ? *s0 - REGION_GROW : 0;
    *s1 = *s1 + REGION_GROW < b->ns ? *s1 + REGION_GROW : b->ns - 1;
}

/* What the regional bound must prove for the incumbent to be optimal, above region_lag0. */
static double bp_region_need(const bp_t *b)
{
    double target =
        b->whole_ms ? b->inc.ub_ms - 1.0 + 1e-6 : b->inc.ub_ms * (1.0 - b->opt->rel_gap);
    return target - b->region.region_lag0 + REGION_EPS_MS;
}

/* The stretch to try first: the shortest run of stops holding `need` of the incumbent's gap
 * (region_gaps), widened to every stop a fruit of those stops reaches, so that all of them
 * must be covered inside it (else the stretch's optimum leaves them out at no cost). 0 when
 * the gap lies nowhere shorter than the row. */
static int bp_region_stretch(bp_t *b, double need, size_t *s0, size_t *s1)
{
    double *g = malloc((b->ns + 1) * sizeof *g);
    if (g == NULL || bp_region_gaps(b, g) != HV_OK) {
        free(g);
        return 0; /* no memory: no regional bound, the tree goes on */
    }
    size_t best_lo = 0, best_len = SIZE_MAX, lo = 0;
    double sum = 0.0;
    for (size_t hi = 0; hi < b->ns; ++hi) { /* the shortest [lo, hi] with sum >= need */
        sum += g[hi];
        while (lo < hi && sum - g[lo] >= need) {
            sum -= g[lo++];
        }
        if (sum >= need && hi - lo + 1 < best_len) {
            best_lo = lo;
            best_len = hi - lo + 1;
        }
    }
    free(g);
    *s0 = SIZE_MAX;
    *s1 = 0;
    for (size_t p = best_lo; best_len != SIZE_MAX && p < best_lo + best_len; ++p) {
        for (size_t q = b->m.stop_begin[p]; q < b->m.stop_begin[p + 1]; ++q) {
            uint32_t f = b->inst->pairs[b->m.stop_pair[q]].fruit;
            const hv_pair_t *first = &b->inst->pairs[b->inst->fruit_begin[f]];
            const hv_pair_t *last = &b->inst->pairs[b->inst->fruit_begin[f + 1] - 1];
            *s0 = first->stop < *s0 ? first->stop : *s0;
            *s1 = last->stop > *s1 ? last->stop : *s1;
        }
    }
    return *s0 <= *s1;
}

/* Try to prove the incumbent optimal by regional bounds: over region_stretch's stretch (or,
 * when that lies inside the last stretch whose exact rise is known, over that one grown),
 * and while a stretch's exact rise falls short but rose, over that stretch grown by
 * REGION_GROW stops on either side, up to opt->region_stops stops. Each sub-solve
 * (hv_region_rise) may take REGION_SHARE of the time left; one that runs out of it ends the
 * tries for the solve. The best solution of each stretch is made a plan (region_plan).
 * Once per incumbent. */
static hv_status_t bp_region_try(bp_t *b)
{
    b->region.region_tried_ub = b->inc.ub_ms;
    size_t s0, s1;
    if (!bp_region_stretch(b, bp_region_need(b), &s0, &s1)) {
        return HV_OK;
    }
    if (b->region.region_s0 <= s0 &&
        s1 <= b->region.region_s1) { /* inside one whose exact rise is known */
        s0 = b->region.region_s0;
        s1 = b->region.region_s1;
        bp_region_grow(b, &s0, &s1);
    }
    uint32_t *plan = malloc((b->nf + 1) * sizeof *plan);
    if (plan == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    hv_status_t st = HV_OK;
    double last_rise = -INFINITY;
    while (st == HV_OK && s1 - s0 + 1 <= (size_t)b->opt->region_stops &&
           !(s0 == b->region.region_s0 && s1 == b->region.region_s1) &&
           !bp_prunable(b, b->region.region_lb)) {
        double t0 = hv_milp_now_s(), need = bp_region_need(b);
        hv_region_result_t rr;
        st = hv_region_rise(b->inst, (uint32_t)s0, (uint32_t)s1, b->region.region_pi,
                            b->region.region_v, need, b->opt, b->sub,
                            t0 + REGION_SHARE * (b->t_deadline - t0), plan, &rr);
        if (st != HV_OK) {
            break;
        }
        b->region.region_tries++;
        b->region.region_nodes += rr.nodes;
        b->region.region_lb = fmax(b->region.region_lb, b->region.region_lag0 + rr.rise_ms);
        b->region.region_proofs += rr.rise_ms >= need - 1e-6;
        if (b->tree.share != NULL) {
            hv_share_floor(b->tree.share, b->region.region_lb);
        }
        if (b->opt->verbose >= 1) {
            fprintf(stderr,
                    "price: regional bound over stops %zu-%zu: %.3f of the %.3f ms "
                    "needed above %.3f s (%.3f at its root), %ld nodes in %.2f s%s\n",
                    s0, s1, rr.rise_ms, need, b->region.region_lag0 / 1000.0, rr.root_rise_ms,
                    rr.nodes, hv_milp_now_s() - t0, rr.finished ? "" : ", stopped");
        }
        if (rr.has_plan && (st = bp_region_plan(b, plan, s0, s1)) != HV_OK) {
            break;
        }
        b->region.t_region += hv_milp_now_s() - t0;
        if (!rr.finished) {
            b->region.region_stalled = 1; /* too hard for the time left */
            break;
        }
        b->region.region_s0 = s0; /* its exact rise is in region_lb: not again */
        b->region.region_s1 = s1;
        if (rr.rise_ms <= last_rise + REGION_EPS_MS) {
            break; /* growing did not raise it: the incumbent is likely not optimal */
        }
        last_rise = rr.rise_ms;
        bp_region_grow(b, &s0, &s1);
    }
    free(plan);
    return st;
}

/* A regional bound is to be tried now: the main search, a captured root, a plan new since
 * the last try, REGION_AFTER_NODES nodes done, no sub-solve out of time, the gap open. */
static int bp_region_due(const bp_t *b, long nodes_done)
{
    return !b->tree.is_worker && isfinite(b->region.region_lag0) && !b->region.region_stalled &&
           b->inc.ub_ms < b->region.region_tried_ub - 0.5 && nodes_done >= REGION_AFTER_NODES &&
           !bp_prunable(b, b->region.region_lb);
}

/* BP_ROOT_LP, before the cuts: the root's duals captured once, before any cut. */
static hv_status_t region_capture_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    (void)call;
    if (b->cuts.sr_rounds == 0 && !isfinite(b->region.region_lag0)) {
        return bp_region_capture(b);
    }
    return HV_OK;
}

/* BP_BEFORE_NODE: a try when one is due. */
static hv_status_t region_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    (void)self;
    return bp_region_due(b, call->nodes_done) ? bp_region_try(b) : HV_OK;
}

const bp_plugin_t bp_region_capture_plugin = {"region-capture", BP_ROOT_LP, 200, 0,
                                              region_capture_exec};
const bp_plugin_t bp_region = {"region", BP_BEFORE_NODE, 100, 0, region_exec};
