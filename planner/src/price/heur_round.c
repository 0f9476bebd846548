/* Branch-and-price (bp.h). Primal heuristic "rounding": the master point rounded to a plan
 * and improved by local search, at every node while the plan is far from the root's bound
 * and every ROUND_EVERY nodes after. */
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
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

/* The master point x rounded into a (fresh) assignment: each fruit at the stop holding most
 * of its mass, or left out (HV_NO_STOP) when it has none there or, where it may be left
 * out (hv_price_bound), its artificial holds more. */
static hv_status_t bp_round_point(const bp_t *b, const double *x, hv_assignment_t *a)
{
    double *mass = malloc((b->nf + 1) * sizeof *mass);
    if (mass == NULL || hv_assignment_alloc(a, b->nf) != HV_OK) {
        free(mass);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < b->nf; ++f) {
        mass[f] = bp_skippable(b, f) && b->m.row_of_fruit[f] ? x[b->m.row_of_fruit[f]] : 0.0;
    }
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        double v = x[b->m.pat[k].col];
        for (uint32_t q = 0; v > LAMBDA_EPS && q < b->m.pat[k].n; ++q) {
            uint32_t f = b->m.pf[b->m.pat[k].first + q];
            if (v > mass[f]) {
                mass[f] = v;
                a->fruit_stop[f] = b->m.pat[k].stop;
            }
        }
    }
    free(mass);
    return HV_OK;
}

/* Round a fractional master point to a plan (round_point), improve it by local search and
 * keep it when it beats the incumbent. */
static hv_status_t bp_round_and_improve(bp_t *b, const double *x)
{
    double t0 = hv_milp_now_s();
    hv_assignment_t a;
    if (bp_round_point(b, x, &a) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    int complete = 1;
    for (size_t f = 0; f < b->nf; ++f) {
        if (b->m.row_of_fruit[f] != 0 && a.fruit_stop[f] == HV_NO_STOP) {
            complete = 0; /* covered by an artificial only */
        }
    }
    hv_status_t st = complete ? bp_improve_plan(b, &a, 20) : HV_OK;
    hv_assignment_free(&a);
    b->stats.t_heur += hv_milp_now_s() - t0;
    return st;
}

/* hv_price_bound's rounding, at every node (round_point), valued as the master values it
 * (the local search knows no fruit left out). */
static hv_status_t bp_round_skip(bp_t *b, const double *x)
{
    hv_assignment_t a;
    double *arm = calloc(2 * b->ns + 1, sizeof *arm);
    unsigned char *used = calloc(b->ns + 1, 1);
    if (arm == NULL || used == NULL || bp_round_point(b, x, &a) != HV_OK) {
        free(arm);
        free(used);
        return HV_ERR_PLAN_NOMEM;
    }
    double t = b->travel_ms;
    int complete = 1;
    for (size_t f = 0; f < b->nf && complete; ++f) {
        if (a.fruit_stop[f] == HV_NO_STOP) {
            complete = !b->m.row_of_fruit[f] || bp_skippable(b, f);
            t += complete && b->m.row_of_fruit[f] ? b->skip_ms[f] : 0.0;
        }
    }
    bp_stop_arms(b, a.fruit_stop, arm, used);
    for (size_t p = 0; p < b->ns; ++p) {
        t += bp_stop_cost_ms(b, arm, used, p);
    }
    hv_status_t st = HV_OK;
    if (complete && t < b->inc.ub_ms - 1e-6) {
        bp_set_incumbent(b, &a, t / 1000.0);
        b->stats.heur_wins++;
        if (bp_add_assignment_columns(b, b->inc.best) < 0) {
            st = HV_ERR_PLAN_NOMEM;
        }
    }
    hv_assignment_free(&a);
    free(arm);
    free(used);
    return st;
}

/* BP_NODE_LP: the rounding pays near the root, and at every node while the plan is far
 * above the root's bound: alpha 2.5 seed 4 found its optimal plan only so (SOLVER.md's history);
 * else every `frequency` nodes. hv_price_bound's plans may leave fruits out: its own
 * rounding, at every node. */
static hv_status_t round_exec(bp_t *b, const bp_plugin_t *self, bp_call_t *call)
{
    if (b->skip_ms != NULL) {
        return bp_round_skip(b, call->x);
    }
    /* a local search costs 5-10 nodes on the product's model (341 stops, 30-70 in a plan),
     * where the plan stays more than PRIMAL_ROOT_GAP above the root's bound at most nodes:
     * unchecked, the rounding took 60-70 % of the search (one thread, alpha 1) */
    uint32_t depth = b->tree.nodes[call->node].depth;
    int budget = depth <= 2 || b->stats.t_heur <= ROUND_TIME_SHARE * (hv_milp_now_s() - b->t_start);
    if ((call->far || depth <= 2 || b->tree.n_nodes % (size_t)self->frequency == 0) && budget &&
        !bp_must_stop(b)) {
        return bp_round_and_improve(b, call->x);
    }
    return HV_OK;
}

const bp_plugin_t bp_heur_round = {"rounding", BP_NODE_LP, 200, ROUND_EVERY, round_exec};
