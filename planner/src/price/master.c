/* Branch-and-price (bp.h). The master LP: the context's set-up and release, a node's
 * restrictions (intervals, count rows, fixed patterns), saved bases, duals and the simplex
 * calls. */
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

void bp_free(bp_t *b)
{
    if (b->m.lp != NULL) {
        glp_delete_prob(b->m.lp);
    }
    free(b->m.stop_begin);
    free(b->m.stop_pair);
    free(b->m.row_of_fruit);
    free(b->m.row_of_stop);
    free(b->m.fixed_pat);
    free(b->m.pat);
    free(b->m.pf);
    free(b->m.pat_open);
    free(b->m.pat_dead);
    free(b->fix.pair_dead);
    free(b->fix.root_pi);
    free(b->m.hslot);
    free(b->tree.nodes);
    for (size_t i = 0; i < b->tree.n_bases; ++i) {
        free(b->tree.bases[i].stat);
        free(b->tree.bases[i].pi);
    }
    free(b->tree.bases);
    free(b->tree.heap);
    free(b->tree.lo);
    for (int d = 0; d < 2; ++d) {
        free(b->tree.pc.sum[d]);
        free(b->tree.pc.n[d]);
        free(b->tree.ivpc.sum[d]);
        free(b->tree.ivpc.n[d]);
    }
    free(b->tree.hi);
    hv_pricer_free(&b->m.pricer);
    hv_src_free(&b->cuts.src);
    free(b->cuts.src_row);
    free(b->cuts.src_hit);
    free(b->cuts.src_bit);
    free(b->m.itl);
    free(b->m.itr);
    free(b->m.sel);
    free(b->m.pi_lp);
    free(b->m.mu_lp);
    free(b->m.sg_lp);
    free(b->m.pi_c);
    free(b->m.sg_c);
    free(b->m.pi_sep);
    free(b->m.cover);
    free(b->m.sg_sep);
    free(b->m.sigma_lp);
    free(b->tree.stop_mass);
    free(b->tree.stop_empty);
    free(b->m.cand);
    free(b->m.warm_pair);
    free(b->m.warm_n);
    free(b->m.pair_at);
    free(b->m.cf);
    free(b->m.ind);
    free(b->m.val);
    free(b->m.crow);
    free(b->m.sigma_stop);
    free(b->inc.best);
    free(b->m.stop_v);
    free(b->region.region_pi);
    free(b->region.region_v);
    hv_share_node_free(&b->tree.msg);
    free(b->tree.col_pat);
}

hv_status_t bp_init(bp_t *b, const hv_instance_t *inst, const hv_milp_options_t *opt)
{
    memset(b, 0, sizeof *b);
    b->inst = inst;
    b->opt = opt;
    b->nf = inst->n_fruits;
    b->ns = inst->n_stops;
    b->tau_ms = 1000.0 * inst->stop_penalty_s;
    b->travel_ms = 1000.0 * inst->travel_time_s;
    b->inc.ub_ms = INFINITY;
    hv_pricer_init(&b->m.pricer);
    size_t nf = b->nf, ns = b->ns;
    b->m.stop_begin = calloc(ns + 1, sizeof *b->m.stop_begin);
    b->m.stop_pair = malloc((inst->n_pairs + 1) * sizeof *b->m.stop_pair);
    b->m.row_of_fruit = calloc(nf + 1, sizeof *b->m.row_of_fruit);
    b->m.row_of_stop = calloc(ns + 1, sizeof *b->m.row_of_stop);
    b->m.fixed_pat = malloc((ns + 1) * sizeof *b->m.fixed_pat);
    b->tree.lo = malloc((nf + 1) * sizeof *b->tree.lo);
    b->tree.ivpc_w = opt->interval_branching > 0 ? (size_t)opt->interval_branching : 0;
    for (int d = 0; d < 2; ++d) {
        b->tree.pc.sum[d] = calloc(nf + 1, sizeof *b->tree.pc.sum[d]);
        b->tree.pc.n[d] = calloc(nf + 1, sizeof *b->tree.pc.n[d]);
        b->tree.ivpc.sum[d] = calloc(ns * b->tree.ivpc_w + 1, sizeof *b->tree.ivpc.sum[d]);
        b->tree.ivpc.n[d] = calloc(ns * b->tree.ivpc_w + 1, sizeof *b->tree.ivpc.n[d]);
    }
    b->tree.hi = malloc((nf + 1) * sizeof *b->tree.hi);
    b->m.itl = malloc((nf + 1) * sizeof *b->m.itl);
    b->m.itr = malloc((nf + 1) * sizeof *b->m.itr);
    b->m.sel = malloc((nf + 1) * sizeof *b->m.sel);
    b->m.pi_lp = calloc(nf + SR_MAX + 1, sizeof *b->m.pi_lp);
    b->m.pi_c = calloc(nf + SR_MAX + 1, sizeof *b->m.pi_c);
    b->m.pi_sep = calloc(nf + SR_MAX + 1, sizeof *b->m.pi_sep);
    b->m.cover = calloc(nf + 1, sizeof *b->m.cover);
    b->cuts.src_row = calloc(SR_MAX + 1, sizeof *b->cuts.src_row);
    b->cuts.src_hit = calloc(SR_MAX + 1, sizeof *b->cuts.src_hit);
    b->cuts.src_bit = malloc((SR_MAX + 1) * sizeof *b->cuts.src_bit);
    b->m.mu_lp = calloc(ns + 1, sizeof *b->m.mu_lp);
    b->m.sigma_lp = calloc(ns + 1, sizeof *b->m.sigma_lp);
    b->tree.stop_mass = calloc(ns + 1, sizeof *b->tree.stop_mass);
    b->tree.stop_empty = calloc(2 * ns + 1, sizeof *b->tree.stop_empty);
    b->m.cand = calloc(ns + 1, sizeof *b->m.cand);
    b->fix.pair_dead = calloc(inst->n_pairs + 1, 1);
    b->fix.root_pi = calloc(nf + SR_MAX + 1, sizeof *b->fix.root_pi);
    b->fix.root_lag = -INFINITY;
    b->fix.fixed_ub = INFINITY;
    b->tree.cur_basis = -1;
    b->m.warm_pair = malloc((inst->n_pairs + 1) * sizeof *b->m.warm_pair);
    b->m.warm_n = malloc((ns + 1) * sizeof *b->m.warm_n);
    b->m.pair_at = malloc((nf + 1) * sizeof *b->m.pair_at);
    b->m.iv_cap = nf + 3;
    b->m.ind = malloc(b->m.iv_cap * sizeof *b->m.ind);
    b->m.val = malloc(b->m.iv_cap * sizeof *b->m.val);
    b->m.sigma_stop = calloc(ns + 1, sizeof *b->m.sigma_stop);
    b->inc.best = malloc((nf + 1) * sizeof *b->inc.best);
    b->m.stop_v = calloc(ns + 1, sizeof *b->m.stop_v);
    b->region.region_pi = calloc(nf + 1, sizeof *b->region.region_pi);
    b->region.region_v = calloc(ns + 1, sizeof *b->region.region_v);
    b->region.region_lb = b->region.region_lag0 = -INFINITY;
    b->region.region_tried_ub = INFINITY;
    b->region.region_s0 = SIZE_MAX;
    if (b->m.stop_v == NULL || b->region.region_pi == NULL || b->region.region_v == NULL ||
        b->m.stop_begin == NULL || b->m.stop_pair == NULL || b->m.row_of_fruit == NULL ||
        b->m.row_of_stop == NULL || b->m.fixed_pat == NULL || b->tree.lo == NULL ||
        b->tree.hi == NULL || b->m.itl == NULL || b->m.itr == NULL || b->m.sel == NULL ||
        b->m.pi_lp == NULL || b->m.pi_c == NULL || b->m.pi_sep == NULL || b->m.cover == NULL ||
        b->m.mu_lp == NULL || b->m.sigma_lp == NULL || b->tree.stop_mass == NULL ||
        b->tree.stop_empty == NULL || b->m.cand == NULL || b->m.warm_pair == NULL ||
        b->m.warm_n == NULL || b->m.pair_at == NULL || b->fix.pair_dead == NULL ||
        b->fix.root_pi == NULL || b->cuts.src_row == NULL || b->cuts.src_hit == NULL ||
        b->cuts.src_bit == NULL || hv_src_init(&b->cuts.src, nf) != HV_OK ||
        b->tree.pc.sum[0] == NULL || b->tree.pc.sum[1] == NULL || b->tree.pc.n[0] == NULL ||
        b->tree.pc.n[1] == NULL || b->tree.ivpc.sum[0] == NULL || b->tree.ivpc.sum[1] == NULL ||
        b->tree.ivpc.n[0] == NULL || b->tree.ivpc.n[1] == NULL || b->m.ind == NULL ||
        b->m.val == NULL || b->inc.best == NULL || b->m.sigma_stop == NULL ||
        !bp_hash_rebuild(b, 1024)) {
        return HV_ERR_PLAN_NOMEM;
    }
    b->whole_ms = fabs(b->tau_ms - round(b->tau_ms)) < 1e-6 && opt->ms_granularity;
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        b->m.stop_begin[inst->pairs[k].stop + 1]++;
        double ms = 1000.0 * inst->pairs[k].cost_s;
        b->whole_ms &= fabs(ms - round(ms)) < 1e-6;
    }
    for (size_t c = 0; c < SR_MAX; ++c) {
        b->cuts.src_bit[c] = -1;
    }
    for (size_t f = 0; f < nf; ++f) { /* the root's intervals: the centre is priced before it */
        b->tree.lo[f] = 0;
        b->tree.hi[f] = (uint32_t)(ns - 1);
    }
    for (size_t p = 0; p < ns; ++p) {
        b->m.stop_begin[p + 1] += b->m.stop_begin[p];
        b->m.warm_n[p] = SIZE_MAX;
        b->m.fixed_pat[p] = -1;
    }
    size_t *fill = malloc((ns + 1) * sizeof *fill);
    if (fill == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(fill, b->m.stop_begin, (ns + 1) * sizeof *fill);
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        b->m.stop_pair[fill[inst->pairs[k].stop]++] = k;
    }
    free(fill);

    /* master: a row per reachable fruit (>= 1 or = 1: opt->cover_rows), a row per usable
     * stop (<= 1), and an artificial column per fruit row */
    int cover = opt->cover_rows == 1 || (opt->cover_rows == 2 && inst->n_pairs >= CENTRE_MIN_PAIRS);
    b->cuts.sr_max = inst->n_pairs >= CENTRE_MIN_PAIRS ? opt->sr_cuts_large : opt->sr_cuts;
    b->m.lp = glp_create_prob();
    glp_set_obj_dir(b->m.lp, GLP_MIN);
    int rows = 0;
    for (size_t f = 0; f < nf; ++f) {
        if (inst->fruit_begin[f] < inst->fruit_begin[f + 1]) {
            b->m.row_of_fruit[f] = ++rows;
        }
    }
    b->m.n_art = rows;
    for (size_t p = 0; p < ns; ++p) {
        if (b->m.stop_begin[p] < b->m.stop_begin[p + 1]) {
            b->m.row_of_stop[p] = ++rows;
        }
    }
    glp_add_rows(b->m.lp, rows);
    for (int i = 1; i <= b->m.n_art; ++i) {
        glp_set_row_bnds(b->m.lp, i, cover ? GLP_LO : GLP_FX, 1.0, 1.0);
    }
    for (int i = b->m.n_art + 1; i <= rows; ++i) {
        glp_set_row_bnds(b->m.lp, i, GLP_UP, 0.0, 1.0);
    }
    glp_add_cols(b->m.lp, b->m.n_art);
    for (int j = 1; j <= b->m.n_art; ++j) {
        int ind[2] = {0, j};
        double val[2] = {0.0, 1.0};
        glp_set_mat_col(b->m.lp, j, 1, ind, val);
        glp_set_col_bnds(b->m.lp, j, GLP_LO, 0.0, 0.0);
        glp_set_obj_coef(b->m.lp, j, BIG_MS);
    }
    return HV_OK;
}

/* Duals per pi vector: the fruits' and then the subset-row cuts'. */
size_t bp_n_pi(const bp_t *b)
{
    return b->nf + b->cuts.src.n;
}

/* A basis of nr rows and nc columns (statuses `stat`, rows first) with its centre (`duals`:
 * n_pi fruit and cut duals, then n_sg count-row duals; bound lag) joins b->tree.bases, which
 * takes both arrays: returns its index, or -1 (both freed) past the memory cap. */
int32_t bp_basis_keep(bp_t *b, int nr, int nc, unsigned char *stat, double *duals, size_t n_pi,
                      size_t n_sg, double lag)
{
    size_t bytes = (size_t)nr + (size_t)nc + (n_pi + n_sg) * sizeof(double);
    if (b->tree.bases_bytes + bytes > ((size_t)256 << 20) ||
        !hv_grow((void **)&b->tree.bases, &b->tree.bases_cap, b->tree.n_bases + 1,
                 sizeof *b->tree.bases)) {
        free(stat);
        free(duals);
        return -1;
    }
    b->tree.bases[b->tree.n_bases] = (basis_t){nr, nc, stat, duals, duals + n_pi, n_pi, n_sg, lag};
    b->tree.bases_bytes += bytes;
    return (int32_t)b->tree.n_bases++;
}

/* Keep the master's current basis; returns its index, -1 when not kept (memory). */
int32_t bp_basis_save(bp_t *b)
{
    int nr = glp_get_num_rows(b->m.lp), nc = glp_get_num_cols(b->m.lp);
    size_t npi = bp_n_pi(b);
    unsigned char *st = malloc((size_t)nr + (size_t)nc);
    double *duals = malloc((npi + b->m.n_crow + 1) * sizeof *duals);
    if (st == NULL || duals == NULL) {
        free(st);
        free(duals);
        return -1;
    }
    memcpy(duals, b->m.pi_c, npi * sizeof *duals);
    if (b->m.n_crow > 0) {
        memcpy(duals + npi, b->m.sg_c, b->m.n_crow * sizeof *duals);
    }
    for (int i = 1; i <= nr; ++i) {
        st[i - 1] = (unsigned char)glp_get_row_stat(b->m.lp, i);
    }
    for (int j = 1; j <= nc; ++j) {
        st[nr + j - 1] = (unsigned char)glp_get_col_stat(b->m.lp, j);
    }
    return bp_basis_keep(b, nr, nc, st, duals, npi, b->m.n_crow,
                         isfinite(b->m.center_lag) ? b->m.center_lag : -INFINITY);
}

/* Restore a kept basis: rows made since are basic, columns made since non-basic, so it
 * stays a valid basis of the grown master. */
static void bp_basis_restore(bp_t *b, int32_t k)
{
    const basis_t *s = &b->tree.bases[k];
    int nr = glp_get_num_rows(b->m.lp), nc = glp_get_num_cols(b->m.lp);
    for (int i = 1; i <= nr; ++i) {
        glp_set_row_stat(b->m.lp, i, i <= s->n_rows ? s->stat[i - 1] : GLP_BS);
    }
    for (int j = 1; j <= nc; ++j) {
        glp_set_col_stat(b->m.lp, j, j <= s->n_cols ? s->stat[s->n_rows + j - 1] : GLP_NL);
    }
}

/* The count row of the interval [lo, hi], made on first use. NULL when out of memory. */
count_row_t *bp_crow_get(bp_t *b, uint32_t lo, uint32_t hi)
{
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        if (b->m.crow[r].lo == lo && b->m.crow[r].hi == hi) {
            return &b->m.crow[r];
        }
    }
    if (!bp_iv_reserve(b, b->m.n_pat) ||
        !hv_grow((void **)&b->m.crow, &b->m.crow_cap, b->m.n_crow + 1, sizeof *b->m.crow)) {
        return NULL;
    }
    count_row_t *c = &b->m.crow[b->m.n_crow++];
    *c = (count_row_t){lo,        hi,      glp_add_rows(b->m.lp, 1), glp_add_cols(b->m.lp, 1),
                       -INFINITY, INFINITY};
    int len = 0;
    for (size_t j = 0; j < b->m.n_pat; ++j) {
        if (lo <= b->m.pat[j].stop && b->m.pat[j].stop <= hi) {
            b->m.ind[++len] = b->m.pat[j].col;
            b->m.val[len] = 1.0;
        }
    }
    glp_set_mat_row(b->m.lp, c->row, len, b->m.ind, b->m.val);
    glp_set_row_bnds(b->m.lp, c->row, GLP_FR, 0.0, 0.0);
    glp_set_row_stat(b->m.lp, c->row, GLP_BS); /* keeps the current basis valid */
    int ind[2] = {0, c->row};
    double val[2] = {0.0, 1.0};
    glp_set_mat_col(b->m.lp, c->art, 1, ind, val);
    glp_set_col_bnds(b->m.lp, c->art, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(b->m.lp, c->art, BIG_MS);
    return c;
}

/* Fruit f may be left uncovered (hv_price_bound). */
int bp_skippable(const bp_t *b, size_t f)
{
    return b->skip_ms != NULL && isfinite(b->skip_ms[f]);
}

/* ... and the current node allows that (its interval holds the virtual stop ns). */
int bp_skip_open(const bp_t *b, size_t f)
{
    return bp_skippable(b, f) && b->tree.hi[f] == b->ns;
}

/* The node's restrictions: its fruits' stop intervals with the master columns that respect
 * them opened, and its count rows. */
hv_status_t bp_node_apply(bp_t *b, int32_t k, int *infeasible)
{
    *infeasible = 0;
    for (size_t f = 0; f < b->nf; ++f) {
        b->tree.lo[f] = 0;
        b->tree.hi[f] = (uint32_t)(bp_skippable(b, f) ? b->ns : b->ns - 1);
    }
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        b->m.crow[r].min = -INFINITY;
        b->m.crow[r].max = INFINITY;
    }
    for (size_t p = 0; p < b->ns; ++p) {
        b->m.fixed_pat[p] = -1;
    }
    /* deeper restrictions of a fruit lie inside shallower ones: intersect along the path */
    for (int32_t q = k; q >= 0; q = b->tree.nodes[q].parent) {
        const node_t *n = &b->tree.nodes[q];
        if (n->kind == KIND_FRUIT) {
            if (n->lo > b->tree.lo[n->fruit]) {
                b->tree.lo[n->fruit] = n->lo;
            }
            if (n->hi < b->tree.hi[n->fruit]) {
                b->tree.hi[n->fruit] = n->hi;
            }
        } else if (n->kind == KIND_PATTERN) {
            const pattern_t *pt = &b->m.pat[n->rhs];
            b->m.fixed_pat[pt->stop] = n->rhs;
            for (uint32_t q = 0; q < pt->n; ++q) {
                b->tree.lo[b->m.pf[pt->first + q]] = b->tree.hi[b->m.pf[pt->first + q]] = pt->stop;
            }
        } else if (n->kind != KIND_ROOT) {
            count_row_t *c = bp_crow_get(b, n->lo, n->hi);
            if (c == NULL) {
                return HV_ERR_PLAN_NOMEM;
            }
            if (n->kind == KIND_COUNT_LE) {
                c->max = fmin(c->max, (double)n->rhs);
            } else {
                c->min = fmax(c->min, (double)n->rhs);
            }
        }
    }
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        const count_row_t *c = &b->m.crow[r];
        int lo_set = isfinite(c->min), hi_set = isfinite(c->max);
        if (c->min > c->max) {
            *infeasible = 1; /* "at least" above "at most" on one interval */
            continue;
        }
        int type = lo_set && hi_set ? (c->min == c->max ? GLP_FX : GLP_DB)
                   : lo_set         ? GLP_LO
                   : hi_set         ? GLP_UP
                                    : GLP_FR;
        glp_set_row_bnds(b->m.lp, c->row, type, lo_set ? c->min : 0.0, hi_set ? c->max : 0.0);
    }
    for (size_t j = 0; j < b->m.n_pat; ++j) {
        const pattern_t *p = &b->m.pat[j];
        unsigned char ok = 1;
        for (uint32_t q = 0; q < p->n && ok; ++q) {
            uint32_t f = b->m.pf[p->first + q];
            ok = b->tree.lo[f] <= p->stop && p->stop <= b->tree.hi[f];
        }
        int32_t fx = b->m.fixed_pat[p->stop];
        bp_col_open(b, j, fx == (int32_t)j ? 2 : (ok && fx < 0 && !b->m.pat_dead[j]));
    }
    for (size_t f = 0; b->skip_ms != NULL && f < b->nf; ++f) {
        if (bp_skippable(b, f) &&
            b->m.row_of_fruit[f] != 0) { /* the artificial stays: feasibility */
            glp_set_obj_coef(b->m.lp, b->m.row_of_fruit[f],
                             bp_skip_open(b, f) ? b->skip_ms[f] : BIG_MS);
        }
    }
    b->tree.cur_basis = b->tree.nodes[k].basis;
    if (b->tree.cur_basis >= 0) {
        bp_basis_restore(b, b->tree.cur_basis);
    }
    return HV_OK;
}

/* The master's duals: pi per fruit (pi_lp), mu per stop row (mu_lp), and per count row
 * (sg_lp) clamped to the sign valid for the restriction in force (a dual of the wrong sign
 * would make the Lagrangian bound invalid). */
int bp_duals_read(bp_t *b)
{
    if (!hv_grow((void **)&b->m.sg_lp, &b->m.sg_cap, b->m.n_crow + 1, sizeof *b->m.sg_lp)) {
        return 0;
    }
    for (size_t f = 0; f < b->nf; ++f) {
        b->m.pi_lp[f] =
            b->m.row_of_fruit[f] ? glp_get_row_dual(b->m.lp, b->m.row_of_fruit[f]) : 0.0;
    }
    for (size_t c = 0; c < b->cuts.src.n; ++c) { /* "<= 1" rows: a dual above 0 is round-off */
        b->m.pi_lp[b->nf + c] = fmin(0.0, glp_get_row_dual(b->m.lp, b->cuts.src_row[c]));
    }
    for (size_t p = 0; p < b->ns; ++p) {
        b->m.mu_lp[p] = b->m.row_of_stop[p] ? glp_get_row_dual(b->m.lp, b->m.row_of_stop[p]) : 0.0;
    }
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        const count_row_t *c = &b->m.crow[r];
        double d = glp_get_row_dual(b->m.lp, c->row);
        b->m.sg_lp[r] = d < 0.0 && isfinite(c->max) ? d : (d > 0.0 && isfinite(c->min) ? d : 0.0);
    }
    return 1;
}

/* The time to the deadline as GLPK's tm_lim. */
static int bp_ms_left(const bp_t *b)
{
    return hv_milp_limit_ms(b->t_deadline - hv_milp_now_s());
}

/* first: after a node switch only bounds changed, so the last basis stays dual feasible
 * and the dual simplex repairs it; after new columns the primal simplex continues. */
hv_status_t bp_lp_solve(bp_t *b, int first)
{
    glp_smcp sp;
    glp_init_smcp(&sp);
    sp.msg_lev = GLP_MSG_OFF;
    sp.meth = first ? GLP_DUALP : GLP_PRIMAL;
    double t0 = hv_milp_now_s();
    sp.tm_lim = bp_ms_left(b);
    sp.it_lim = STALL_ITERS_PER_ROW * glp_get_num_rows(b->m.lp) + 1000;
    int r = glp_simplex(b->m.lp, &sp);
    if (r == GLP_EITLIM) {
        /* the master is highly degenerate and GLPK's primal simplex can stall on it (seen:
         * 300,000 iterations, 22 s, on one call); the dual simplex from the same basis
         * finishes such a call in milliseconds */
        b->stats.lp_stalls++;
        sp.it_lim = INT_MAX;
        sp.meth = GLP_DUALP;
        sp.tm_lim = bp_ms_left(b); /* what the stalled call left, not what it started with */
        r = glp_simplex(b->m.lp, &sp);
    }
    if (r == GLP_EBADB || r == GLP_ESING || r == GLP_ECOND) {
        b->stats.lp_restarts++;
        glp_adv_basis(b->m.lp, 0); /* an unusable warm start (singular, invalid): start afresh */
        sp.tm_lim = bp_ms_left(b);
        r = glp_simplex(b->m.lp, &sp);
    }
    b->stats.t_lp += hv_milp_now_s() - t0;
    if (r == GLP_ETMLIM) {
        return HV_OK; /* the caller sees the deadline */
    }
    if (r == 0 && glp_get_status(b->m.lp) != GLP_OPT) {
        r = -glp_get_status(b->m.lp); /* artificials make every master feasible */
    }
    if (r != 0) {
        if (b->opt->verbose >= 1) {
            fprintf(stderr, "price: master LP failed: glp_simplex %d, status %d\n", r,
                    glp_get_status(b->m.lp));
        }
        return HV_ERR_MILP_GLPK;
    }
    return HV_OK;
}
