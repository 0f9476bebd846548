/* The stop-and-harvest MILP on GLPK (milp.h): incumbent, model, branch-and-cut, result. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_clock.h"
#include "hv/milp.h"
#include "hv/milp_cuts.h"
#include "hv/milp_local_search.h"
#include "hv/milp_model.h"
#include "hv/milp_price.h"
#include "hv/milp_status.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"
#include "milp_tunables.h"

/* What the GLPK callback needs. */
typedef struct cb_ctx {
    const hv_instance_t *inst;
    const hv_milp_options_t *opt;
    const hv_milp_model_t *model;
    const double *x_inc; /* incumbent point (1-based), NULL if none */
    int inc_offered;
    int inc_taken;
    double bound; /* best lower bound seen in the tree (s) */
    double t_start, t_last_print;
    double abs_prune_s;     /* > 0: objective granularity (s) */
    long nodes;             /* nodes created so far */
    hv_cut_sep_t *cuts;     /* stop-pattern cut separation, NULL when off */
    double root_after_cuts; /* root LP bound after the cut rounds (s) */
    int cut_rounds;
} cb_ctx_t;

static void track_bound(glp_tree *tree, cb_ctx_t *c)
{
    int best = glp_ios_best_node(tree);
    if (best != 0) {
        double b = glp_ios_node_bound(tree, best);
        if (b > c->bound) {
            c->bound = b;
        }
    }
}

static int link_cuts_add_violated(const hv_instance_t *inst, const hv_milp_model_t *m,
                                  glp_tree *tree);

static void callback(glp_tree *tree, void *info)
{
    cb_ctx_t *c = info;
    int a_cnt, n_cnt, t_cnt;
    glp_ios_tree_size(tree, &a_cnt, &n_cnt, &t_cnt);
    c->nodes = t_cnt;
    int reason = glp_ios_reason(tree);
    if (c->opt->stop != NULL && c->opt->stop(c->opt->stop_ctx)) {
        glp_ios_terminate(tree); /* glp_intopt returns GLP_ESTOP: as at the time limit */
        return;
    }
    if ((reason == GLP_IHEUR || reason == GLP_IBRANCH) && glp_ios_curr_node(tree) != 0 &&
        glp_ios_node_level(tree, glp_ios_curr_node(tree)) == 0) {
        c->root_after_cuts = glp_get_obj_val(glp_ios_get_prob(tree)); /* cuts are done */
    }
    switch (reason) {
    case GLP_IHEUR:
        if (c->x_inc != NULL && !c->inc_offered) {
            c->inc_offered = 1;
            c->inc_taken = glp_ios_heur_sol(tree, c->x_inc) == 0;
        }
        break;
    case GLP_ICUTGEN:
        if (c->opt->link_disaggregated == 2 &&
            link_cuts_add_violated(c->inst, c->model, tree) > 0) {
            break; /* the linking first: pattern cuts on the re-solved LP */
        }
        if (c->cuts != NULL && c->cut_rounds < HV_CUT_MAX_ROUNDS &&
            glp_ios_node_level(tree, glp_ios_curr_node(tree)) <= c->opt->pattern_cuts) {
            /* each round re-solves a bigger LP: a few rounds give most of the bound */
            c->cut_rounds++;
            hv_cut_separate(c->cuts, tree);
        }
        break;
    case GLP_ISELECT:
        track_bound(tree, c);
        if (c->opt->verbose >= 1) {
            double t = hv_milp_now_s();
            if (t - c->t_last_print >= 1.0) {
                c->t_last_print = t;
                fprintf(stderr, "milp: %.1f s, %d active nodes, %d total, bound %.3f s, gap %.4f\n",
                        t - c->t_start, a_cnt, t_cnt, c->bound, glp_ios_mip_gap(tree));
            }
        }
        break;
    default: break;
    }
}

/* 1 when every pick cost, tau and T_travel are whole milliseconds. */
static int costs_in_whole_ms(const hv_instance_t *inst)
{
    if (fabs(inst->stop_penalty_s * 1000.0 - round(inst->stop_penalty_s * 1000.0)) > 1e-6) {
        return 0;
    }
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        double ms = inst->pairs[k].cost_s * 1000.0;
        if (fabs(ms - round(ms)) > 1e-6) {
            return 0;
        }
    }
    return 1;
}

/* Copy an assignment that evaluates on inst; T into *t. */
static hv_status_t check_assignment(const hv_instance_t *inst, const hv_assignment_t *a, double *t)
{
    if (a == NULL || a->fruit_stop == NULL || a->n_fruits != inst->n_fruits) {
        return HV_ERR_MILP_INCUMBENT;
    }
    return hv_assignment_makespan(inst, a, t) == HV_OK ? HV_OK : HV_ERR_MILP_INCUMBENT;
}

static void set_trivial(const hv_instance_t *inst, hv_assignment_t *out, hv_milp_result_t *res)
{
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        out->fruit_stop[f] = HV_NO_STOP;
    }
    res->status = HV_SOLVE_OPTIMAL;
    res->objective_s = res->bound_s = res->root_bound_s = inst->travel_time_s;
    res->gap = 0.0;
}

/* Lazy linking (link_disaggregated == 2): rows a_k - b_p <= 0 for the pairs where the LP
 * point of `lp` has a_k > b_p. Added to the model itself; returns how many. */
static int link_rows_add_violated(const hv_instance_t *inst, const hv_milp_model_t *m, glp_prob *lp)
{
    int added = 0;
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        int jb = m->col_b[inst->pairs[k].stop];
        if (glp_get_col_prim(lp, (int)k + 1) > glp_get_col_prim(lp, jb) + 1e-7) {
            int i = glp_add_rows(lp, 1);
            int ind[3] = {0, (int)k + 1, jb};
            double val[3] = {0.0, 1.0, -1.0};
            glp_set_mat_row(lp, i, 2, ind, val);
            glp_set_row_bnds(lp, i, GLP_UP, 0.0, 0.0);
            ++added;
        }
    }
    return added;
}

/* The same inside the tree, as globally valid cuts at the current node. */
static int link_cuts_add_violated(const hv_instance_t *inst, const hv_milp_model_t *m,
                                  glp_tree *tree)
{
    glp_prob *lp = glp_ios_get_prob(tree);
    int added = 0;
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        int jb = m->col_b[inst->pairs[k].stop];
        if (glp_get_col_prim(lp, (int)k + 1) > glp_get_col_prim(lp, jb) + 1e-7) {
            int ind[3] = {0, (int)k + 1, jb};
            double val[3] = {0.0, 1.0, -1.0};
            glp_ios_add_row(tree, NULL, GLP_RF_CUT, 0, 2, ind, val, GLP_UP, 0.0);
            ++added;
        }
    }
    return added;
}

/* A longer local search from `out` (polish_work * 100 / n^2 kicks); keeps it if better. */
static void polish(const hv_instance_t *inst, const hv_milp_options_t *opt, hv_assignment_t *out,
                   double *best_t)
{
    hv_ls_options_t lo;
    hv_ls_options_default(&lo);
    /* a descent costs ~n^2 (exchanges), so the kick count scales with 1/n^2 */
    size_t n = inst->n_fruits ? inst->n_fruits : 1;
    size_t kicks = (size_t)opt->polish_work * 100u / (n * n);
    lo.kicks = (unsigned)(kicks < 50 ? 50 : (kicks > 3000 ? 3000 : kicks));
    lo.seed = 0x5bd1e9955bd1e995ull;
    hv_assignment_t pa;
    double t;
    if (hv_assignment_alloc(&pa, inst->n_fruits) != HV_OK) {
        return;
    }
    memcpy(pa.fruit_stop, out->fruit_stop, inst->n_fruits * sizeof *pa.fruit_stop);
    if (hv_local_search(inst, &lo, &pa, &t) == HV_OK && t < *best_t - 1e-9) {
        *best_t = t;
        memcpy(out->fruit_stop, pa.fruit_stop, inst->n_fruits * sizeof *pa.fruit_stop);
    }
    hv_assignment_free(&pa);
    if (opt->verbose >= 1) {
        fprintf(stderr, "milp: polished incumbent T = %.3f s\n", *best_t);
    }
}

/* GLPK's MIP solution as an assignment; into `out` when better than *best_t. */
static hv_status_t take_glpk_plan(const hv_instance_t *inst, const hv_milp_model_t *m,
                                  hv_assignment_t *out, double *best_t)
{
    hv_assignment_t cand;
    if (hv_assignment_alloc(&cand, inst->n_fruits) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        for (size_t k = inst->fruit_begin[f]; k < inst->fruit_begin[f + 1]; ++k) {
            if (glp_mip_col_val(m->lp, (int)k + 1) > 0.5) {
                cand.fruit_stop[f] = inst->pairs[k].stop;
            }
        }
    }
    double t;
    if (hv_assignment_makespan(inst, &cand, &t) == HV_OK && t < *best_t) {
        *best_t = t;
        memcpy(out->fruit_stop, cand.fruit_stop, inst->n_fruits * sizeof *cand.fruit_stop);
    }
    hv_assignment_free(&cand);
    return HV_OK;
}

static void set_iocp(glp_iocp *ip, const hv_milp_options_t *opt, cb_ctx_t *c,
                     const hv_instance_t *inst, double best_t)
{
    glp_init_iocp(ip);
    ip->msg_lev = opt->verbose >= 2 ? GLP_MSG_ON : GLP_MSG_OFF;
    ip->presolve = GLP_OFF;
    ip->cb_func = callback;
    ip->cb_info = c;
    ip->br_tech = opt->pcost_branching ? GLP_BR_PCH : GLP_BR_DTH;
    ip->bt_tech = opt->backtracking == 1   ? GLP_BT_DFS
                  : opt->backtracking == 2 ? GLP_BT_BPH
                                           : GLP_BT_BLB;
    ip->gmi_cuts = (opt->glpk_cuts & HV_MILP_CUT_GMI) ? GLP_ON : GLP_OFF;
    ip->mir_cuts = (opt->glpk_cuts & HV_MILP_CUT_MIR) ? GLP_ON : GLP_OFF;
    ip->cov_cuts = (opt->glpk_cuts & HV_MILP_CUT_COVER) ? GLP_ON : GLP_OFF;
    ip->clq_cuts = (opt->glpk_cuts & HV_MILP_CUT_CLIQUE) ? GLP_ON : GLP_OFF;
    ip->mip_gap = opt->rel_gap;
    if (opt->ms_granularity && costs_in_whole_ms(inst) && isfinite(best_t)) {
        /* T is a whole number of ms: a node whose bound is within 1 ms of the incumbent
         * cannot hold a better plan. GLPK only has a relative gap, so set it to 0.999 ms at
         * the incumbent's value (as the incumbent improves this only gets safer). */
        double g = 0.000999 / best_t;
        if (g > ip->mip_gap) {
            ip->mip_gap = g;
            c->abs_prune_s = 0.001;
        }
    }
}

hv_status_t hv_milp_export_lp(const hv_instance_t *inst, const hv_milp_options_t *opt,
                              const char *path)
{
    if (inst == NULL || opt == NULL || path == NULL) {
        return HV_ERR_ARG;
    }
    hv_milp_model_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.link_disaggregated = opt->link_disaggregated == 1;
    hv_milp_model_t m;
    hv_status_t st = hv_milp_model_build(inst, &mo, 1, &m);
    if (st != HV_OK) {
        return st;
    }
    int term_prev = glp_term_out(opt->verbose >= 2 ? GLP_ON : GLP_OFF);
    if (glp_write_lp(m.lp, NULL, path) != 0) {
        st = HV_ERR_MILP_EXPORT;
    }
    glp_term_out(term_prev);
    hv_milp_model_free(&m);
    return st;
}

/* One monolithic solve of `inst` (no decomposition). `inc` may be NULL. */
static hv_status_t solve_one(const hv_instance_t *inst, const hv_milp_options_t *opt,
                             const hv_assignment_t *inc, double inc_t, double t_deadline,
                             hv_assignment_t *out, hv_milp_result_t *res)
{
    double t0 = hv_milp_now_s();
    if (inst->n_pairs == 0) {
        set_trivial(inst, out, res);
        return HV_OK;
    }
    int price = opt->algorithm == HV_MILP_ALG_PRICE;
    if (price && opt->export_lp_path == NULL) {
        res->incumbent_taken = inc != NULL;
        return hv_price_solve(inst, opt, hv_milp_default_subsolver(), inc, inc_t, t_deadline, out,
                              res);
    }
    if (opt->export_lp_path != NULL) {
        hv_status_t se = hv_milp_export_lp(inst, opt, opt->export_lp_path);
        if (se != HV_OK) {
            return se;
        }
    }
    if (price) { /* the paper's model was wanted for the file only */
        res->incumbent_taken = inc != NULL;
        return hv_price_solve(inst, opt, hv_milp_default_subsolver(), inc, inc_t, t_deadline, out,
                              res);
    }
    hv_milp_model_opts_t mo;
    memset(&mo, 0, sizeof mo);
    mo.link_disaggregated = opt->link_disaggregated == 1;
    hv_milp_model_t m;
    hv_status_t st = hv_milp_model_build(inst, &mo, 0, &m);
    if (st != HV_OK) {
        return st;
    }
    double *x = malloc(((size_t)m.n_cols + 1) * sizeof *x);
    if (x == NULL) {
        hv_milp_model_free(&m);
        return HV_ERR_PLAN_NOMEM;
    }
    cb_ctx_t c;
    memset(&c, 0, sizeof c);
    c.inst = inst;
    c.opt = opt;
    c.model = &m;
    c.bound = -INFINITY;
    c.t_start = c.t_last_print = t0;

    /* Root LP: GLPK's branch-and-cut without its presolver needs an optimal basis, and
     * without the presolver the callback sees our own columns (the incumbent maps 1:1). */
    glp_smcp sp;
    glp_init_smcp(&sp);
    sp.msg_lev = opt->verbose >= 2 ? GLP_MSG_ON : GLP_MSG_OFF;
    sp.presolve = GLP_OFF;
    sp.tm_lim = hv_milp_limit_ms(t_deadline - hv_milp_now_s());
    glp_scale_prob(m.lp, GLP_SF_AUTO); /* costs of 1..60 s against 0/1 columns */
    sp.meth = GLP_DUALP;
    int ret = glp_simplex(m.lp, &sp);
    int lp_stat = glp_get_status(m.lp);
    while (opt->link_disaggregated == 2 && ret == 0 && lp_stat == GLP_OPT) {
        /* lazy linking: add a_k <= b_p where the LP breaks it, re-solve from the basis */
        int added = link_rows_add_violated(inst, &m, m.lp);
        if (added == 0) {
            break;
        }
        sp.tm_lim = hv_milp_limit_ms(t_deadline - hv_milp_now_s());
        ret = glp_simplex(m.lp, &sp);
        lp_stat = glp_get_status(m.lp);
    }
    double best_t = inc != NULL ? inc_t : INFINITY;
    int have = inc != NULL;
    if (have) {
        memcpy(out->fruit_stop, inc->fruit_stop, inst->n_fruits * sizeof *out->fruit_stop);
    }
    res->root_bound_s = NAN;
    if (ret == 0 && lp_stat == GLP_NOFEAS) {
        res->status = HV_SOLVE_INFEASIBLE;
        free(x);
        hv_milp_model_free(&m);
        return HV_OK;
    }
    int mip_ret = -1, mip_stat = GLP_UNDEF;
    hv_cut_sep_t sep;
    int sep_on = 0;
    if (ret == 0 && lp_stat == GLP_OPT && opt->pattern_cuts >= 0) {
        if (hv_cut_sep_init(&sep, inst, &m) != HV_OK) {
            free(x);
            hv_milp_model_free(&m);
            return HV_ERR_PLAN_NOMEM;
        }
        sep_on = 1;
        c.cuts = &sep;
    }
    if (ret == 0 && lp_stat == GLP_OPT) {
        res->root_bound_s = glp_get_obj_val(m.lp);
        c.bound = res->root_bound_s;
        /* Phase 1 bounded to a share of the limit when the root gap is wide; if it does not
         * prove optimality, the local search polishes the best plan (the tree rarely
         * improves it there, SOLVER.md's history) and phase 2 restarts the tree from it. */
        int two_phase =
            have && opt->polish_work > 0 && (best_t - res->root_bound_s) / best_t > 2e-3;
        for (int phase = 0; phase < 2; ++phase) {
            if (have && hv_milp_model_point(inst, &m, out->fruit_stop, x) == HV_OK) {
                c.x_inc = x;
                c.inc_offered = 0;
            }
            c.cut_rounds = 0;
            c.nodes = 0;
            glp_iocp ip;
            set_iocp(&ip, opt, &c, inst, best_t);
            if (phase == 1) {
                /* hard instance: GLPK's cuts raise the bound there (SOLVER.md's history), while on
                 * easy ones they only cost time, so they join in phase 2 only */
                int cuts = opt->glpk_cuts | opt->glpk_cuts_phase2;
                ip.gmi_cuts = (cuts & HV_MILP_CUT_GMI) ? GLP_ON : GLP_OFF;
                ip.mir_cuts = (cuts & HV_MILP_CUT_MIR) ? GLP_ON : GLP_OFF;
                ip.cov_cuts = (cuts & HV_MILP_CUT_COVER) ? GLP_ON : GLP_OFF;
                ip.clq_cuts = (cuts & HV_MILP_CUT_CLIQUE) ? GLP_ON : GLP_OFF;
            }
            double left_s = t_deadline - hv_milp_now_s();
            if (two_phase && phase == 0) {
                left_s = fmin(left_s, fmax(1.0, 0.2 * opt->time_limit_s));
            }
            ip.tm_lim = hv_milp_limit_ms(left_s);
            mip_ret = glp_intopt(m.lp, &ip);
            mip_stat = glp_mip_status(m.lp);
            res->incumbent_taken |= c.inc_taken;
            res->nodes += c.nodes;
            if (c.root_after_cuts > res->root_bound_s) {
                res->root_bound_s = c.root_after_cuts;
            }
            if ((mip_stat == GLP_OPT || mip_stat == GLP_FEAS) &&
                take_glpk_plan(inst, &m, out, &best_t) != HV_OK) {
                st = HV_ERR_PLAN_NOMEM;
                break;
            }
            have |= isfinite(best_t);
            int proven = (mip_ret == 0 && mip_stat == GLP_OPT) || mip_ret == GLP_EMIPGAP;
            if (proven || !two_phase || phase == 1 || t_deadline - hv_milp_now_s() < 2.0 ||
                mip_ret == GLP_ESTOP || (mip_ret == 0 && mip_stat == GLP_NOFEAS)) {
                break;
            }
            polish(inst, opt, out, &best_t);
        }
    }
    if (st != HV_OK) {
        if (sep_on) {
            hv_cut_sep_free(&sep);
        }
        free(x);
        hv_milp_model_free(&m);
        return st;
    }
    /* tree exhausted (or stopped at the gap): the bound is the incumbent within the gap */
    int proven = (mip_ret == 0 && mip_stat == GLP_OPT) || mip_ret == GLP_EMIPGAP;
    if (mip_ret == 0 && mip_stat == GLP_NOFEAS) {
        res->status = HV_SOLVE_INFEASIBLE;
    } else if (!have) {
        res->status =
            (mip_ret == GLP_ETMLIM || mip_ret == GLP_ESTOP || ret == GLP_ETMLIM || mip_ret == -1)
                ? HV_SOLVE_NO_SOLUTION
                : HV_SOLVE_ERROR;
    } else {
        /* each a valid lower bound; T_travel is one whatever the LP managed */
        double bound = fmax(fmax(c.bound, c.root_after_cuts), inst->travel_time_s);
        if (proven) {
            double gap_abs = fmax(opt->rel_gap * best_t, c.abs_prune_s);
            bound = fmax(bound, best_t - gap_abs);
        }
        bound = fmin(bound, best_t);
        res->objective_s = best_t;
        res->bound_s = bound;
        res->gap = isfinite(bound) ? (best_t - bound) / fmax(best_t, DBL_EPSILON) : INFINITY;
        res->status = proven || res->gap <= opt->rel_gap ? HV_SOLVE_OPTIMAL : HV_SOLVE_FEASIBLE;
        if (proven && c.abs_prune_s > 0) {
            /* every plan is a whole number of ms: nothing lies strictly between */
            res->bound_s = best_t;
            res->gap = 0.0;
        }
    }
    if (sep_on) {
        res->cuts = sep.cuts_added;
        hv_cut_sep_free(&sep);
    }
    free(x);
    hv_milp_model_free(&m);
    return HV_OK;
}

/* Row segments that share no stop: fruits whose reachable stop ranges overlap (directly or
 * through other fruits) form one segment; segments are independent sub-problems. Writes the
 * segment of every fruit (SIZE_MAX for unreachable fruit) and the stop range of each
 * segment; returns the number of segments. */
static size_t row_segments(const hv_instance_t *inst, size_t *seg_of, size_t *lo, size_t *hi)
{
    /* sweep the stops: a stop starts a new segment when no earlier fruit reaches past it */
    size_t ns = inst->n_stops, n_seg = 0;
    long *reach_end = malloc((ns + 1) * sizeof *reach_end); /* last stop of fruits starting here */
    if (reach_end == NULL) {
        return 0;
    }
    for (size_t p = 0; p < ns; ++p) {
        reach_end[p] = -1;
    }
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        size_t b = inst->fruit_begin[f], e = inst->fruit_begin[f + 1];
        if (b == e) {
            continue;
        }
        uint32_t first = inst->pairs[b].stop, last = inst->pairs[e - 1].stop;
        if ((long)last > reach_end[first]) {
            reach_end[first] = (long)last;
        }
    }
    long open_until = -1;
    size_t *seg_at = malloc((ns + 1) * sizeof *seg_at);
    if (seg_at == NULL) {
        free(reach_end);
        return 0;
    }
    for (size_t p = 0; p < ns; ++p) {
        seg_at[p] = SIZE_MAX;
        if (reach_end[p] < 0 && (long)p > open_until) {
            continue;
        }
        if ((long)p > open_until) {
            lo[n_seg] = p;
            n_seg++;
        }
        if (reach_end[p] > open_until) {
            open_until = reach_end[p];
        }
        seg_at[p] = n_seg - 1;
        hi[n_seg - 1] = p + 1;
    }
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        size_t b = inst->fruit_begin[f];
        seg_of[f] = b == inst->fruit_begin[f + 1] ? SIZE_MAX : seg_at[inst->pairs[b].stop];
    }
    free(seg_at);
    free(reach_end);
    return n_seg;
}

/* Solve each segment on its own and add up (T_travel once). */
static hv_status_t solve_segments(const hv_instance_t *inst, const hv_milp_options_t *opt,
                                  const hv_assignment_t *inc, double t_deadline, size_t n_seg,
                                  const size_t *seg_of, const size_t *lo, const size_t *hi,
                                  hv_assignment_t *out, hv_milp_result_t *res)
{
    size_t nf = inst->n_fruits;
    unsigned char *keep = malloc(nf + 1);
    uint32_t *sub_fruit = malloc((nf + 1) * sizeof *sub_fruit);
    if (keep == NULL || sub_fruit == NULL) {
        free(keep);
        free(sub_fruit);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < nf; ++f) {
        out->fruit_stop[f] = HV_NO_STOP;
    }
    hv_status_t st = HV_OK;
    double obj = inst->travel_time_s, bound = inst->travel_time_s, root = inst->travel_time_s;
    int all_opt = 1, any_missing = 0, any_infeasible = 0;
    res->incumbent_taken = 0;
    for (size_t s = 0; s < n_seg && st == HV_OK; ++s) {
        for (size_t f = 0; f < nf; ++f) {
            keep[f] = seg_of[f] == s;
        }
        hv_instance_t sub;
        st = hv_instance_subset(inst, lo[s], hi[s], keep, 1, &sub, sub_fruit);
        if (st != HV_OK) {
            break;
        }
        hv_assignment_t si = {0, NULL}, so = {0, NULL};
        st = hv_assignment_alloc(&so, sub.n_fruits);
        if (st == HV_OK && inc != NULL) {
            st = hv_assignment_alloc(&si, sub.n_fruits);
            for (size_t g = 0; st == HV_OK && g < sub.n_fruits; ++g) {
                uint32_t p = inc->fruit_stop[sub_fruit[g]];
                si.fruit_stop[g] = p == HV_NO_STOP ? HV_NO_STOP : (uint32_t)(p - lo[s]);
            }
        }
        hv_milp_options_t o = *opt;
        o.decompose = 0;
        o.export_lp_path = NULL;
        o.time_limit_s = fmax(0.01, t_deadline - hv_milp_now_s());
        hv_milp_result_t r;
        if (st == HV_OK) {
            st = hv_milp_solve(&sub, &o, inc != NULL ? &si : NULL, &so, &r);
        }
        if (st == HV_OK) {
            res->nodes += r.nodes;
            res->worker_nodes += r.worker_nodes;
            res->interval_branches += r.interval_branches;
            res->tailed_nodes += r.tailed_nodes;
            res->incumbent_taken |= r.incumbent_taken;
            if (r.status == HV_SOLVE_OPTIMAL || r.status == HV_SOLVE_FEASIBLE) {
                obj += r.objective_s - sub.travel_time_s;
                bound += r.bound_s - sub.travel_time_s;
                root += r.root_bound_s - sub.travel_time_s;
                all_opt &= r.status == HV_SOLVE_OPTIMAL;
                for (size_t g = 0; g < sub.n_fruits; ++g) {
                    out->fruit_stop[sub_fruit[g]] = (uint32_t)(so.fruit_stop[g] + lo[s]);
                }
            } else {
                any_infeasible |= r.status == HV_SOLVE_INFEASIBLE;
                any_missing = 1;
            }
        }
        hv_assignment_free(&si);
        hv_assignment_free(&so);
        hv_instance_free(&sub);
    }
    free(keep);
    free(sub_fruit);
    if (st != HV_OK) {
        return st;
    }
    res->root_bound_s = root;
    if (any_infeasible) {
        res->status = HV_SOLVE_INFEASIBLE;
    } else if (any_missing) {
        res->status = HV_SOLVE_NO_SOLUTION;
    } else {
        res->objective_s = obj;
        res->bound_s = fmin(bound, obj);
        res->gap = (obj - res->bound_s) / fmax(obj, DBL_EPSILON);
        res->status = all_opt ? HV_SOLVE_OPTIMAL : HV_SOLVE_FEASIBLE;
    }
    return HV_OK;
}

/* A bound that needs no solve, for a solve stopped before it had one (the time limit or
 * a stop request during the first pricing): T_travel, one stop, and each arm's cheapest
 * picks, since every stop lasts at least as long as each arm's picks there. */
static double trivial_bound_s(const hv_instance_t *inst)
{
    double side[2] = {0.0, 0.0};
    int any = 0;
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        double least = INFINITY;
        for (size_t k = inst->fruit_begin[f]; k < inst->fruit_begin[f + 1]; ++k) {
            least = fmin(least, inst->pairs[k].cost_s);
        }
        if (isfinite(least)) {
            side[inst->fruits[f].side == HV_SIDE_LEFT ? 0 : 1] += least;
            any = 1;
        }
    }
    return inst->travel_time_s + (any ? inst->stop_penalty_s + fmax(side[0], side[1]) : 0.0);
}

hv_status_t hv_milp_solve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                          const hv_assignment_t *incumbent, hv_assignment_t *out,
                          hv_milp_result_t *res)
{
    double t0 = hv_milp_now_s();
    if (inst == NULL || opt == NULL || out == NULL || res == NULL || out->fruit_stop == NULL ||
        out->n_fruits != inst->n_fruits || !(opt->time_limit_s > 0) || !(opt->rel_gap >= 0) ||
        !isfinite(opt->rel_gap)) {
        return HV_ERR_ARG;
    }
    memset(res, 0, sizeof *res);
    res->status = HV_SOLVE_ERROR;
    res->objective_s = res->bound_s = res->gap = res->incumbent_s = INFINITY;
    res->root_bound_s = NAN;
    res->components = 1;
    double t_deadline = t0 + opt->time_limit_s;

    /* the starting incumbent: the caller's (checked), else the heuristic's */
    hv_assignment_t inc = {0, NULL};
    const hv_assignment_t *incp = NULL;
    hv_status_t st = HV_OK;
    if (incumbent != NULL) {
        st = check_assignment(inst, incumbent, &res->incumbent_s);
        if (st != HV_OK) {
            return st;
        }
        incp = incumbent;
    } else if (opt->heuristic_incumbent && inst->n_pairs > 0) {
        st = hv_assignment_alloc(&inc, inst->n_fruits);
        if (st == HV_OK) {
            st = hv_heuristic_solve(inst, &inc);
        }
        if (st == HV_OK) {
            st = check_assignment(inst, &inc, &res->incumbent_s);
        }
        if (st != HV_OK) {
            hv_assignment_free(&inc);
            return st;
        }
        incp = &inc;
    }
    if (opt->verbose >= 1 && incp != NULL) {
        fprintf(stderr, "milp: incumbent T = %.3f s after %.2f s\n", res->incumbent_s,
                hv_milp_now_s() - t0);
    }

    size_t nf = inst->n_fruits, ns = inst->n_stops, n_seg = 1;
    size_t *seg_of = NULL, *lo = NULL, *hi = NULL;
    if (opt->decompose && opt->export_lp_path == NULL && inst->n_pairs > 0) {
        seg_of = malloc((nf + 1) * sizeof *seg_of);
        lo = malloc((ns + 1) * sizeof *lo);
        hi = malloc((ns + 1) * sizeof *hi);
        if (seg_of == NULL || lo == NULL || hi == NULL) {
            st = HV_ERR_PLAN_NOMEM;
        } else {
            n_seg = row_segments(inst, seg_of, lo, hi);
            st = n_seg == 0 ? (hv_status_t)HV_ERR_PLAN_NOMEM : HV_OK;
        }
    }
    /* GLPK prints some notes (cut set-up, file writing) whatever msg_lev says: its terminal
     * output is switched off for the solve and restored after */
    int term_prev = glp_term_out(opt->verbose >= 2 ? GLP_ON : GLP_OFF);
    if (st == HV_OK && n_seg > 1) {
        res->components = (int)n_seg;
        st = solve_segments(inst, opt, incp, t_deadline, n_seg, seg_of, lo, hi, out, res);
    } else if (st == HV_OK) {
        st = solve_one(inst, opt, incp, res->incumbent_s, t_deadline, out, res);
    }
    glp_term_out(term_prev);
    free(seg_of);
    free(lo);
    free(hi);
    hv_assignment_free(&inc);
    if (st == HV_OK && res->status == HV_SOLVE_FEASIBLE) {
        double tb = fmin(trivial_bound_s(inst), res->objective_s);
        if (!(res->bound_s >= tb)) { /* also a -inf or NaN bound: a gap is always stated */
            res->bound_s = tb;
            res->gap = (res->objective_s - tb) / fmax(res->objective_s, DBL_EPSILON);
        }
    }
    res->runtime_s = hv_milp_now_s() - t0;
    if (opt->verbose >= 1 && st == HV_OK) {
        fprintf(stderr, "milp: T = %.3f s, bound %.3f s, gap %.2e, %.2f s\n", res->objective_s,
                res->bound_s, res->gap, res->runtime_s);
    }
    return st;
}

/* The sub-solver handed down to the branch-and-price's plugins (milp_subsolve.h). */
static hv_status_t subsolver_solve(const hv_milp_subsolver_t *self, const hv_instance_t *inst,
                                   const hv_milp_options_t *opt, const hv_assignment_t *inc,
                                   hv_assignment_t *out, hv_milp_result_t *res)
{
    (void)self;
    return hv_milp_solve(inst, opt, inc, out, res);
}

static hv_status_t subsolver_bound(const hv_milp_subsolver_t *self, const hv_instance_t *inst,
                                   const hv_milp_options_t *opt, const double *skip_ms,
                                   double cutoff_ms, double t_deadline_s, uint32_t *plan,
                                   hv_price_bound_result_t *res)
{
    return hv_price_bound(inst, opt, self, skip_ms, cutoff_ms, t_deadline_s, plan, res);
}

static const hv_milp_subsolver_t subsolver = {subsolver_solve, subsolver_bound};

const hv_milp_subsolver_t *hv_milp_default_subsolver(void)
{
    return &subsolver;
}
