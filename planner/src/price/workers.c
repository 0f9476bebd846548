/* Branch-and-price (bp.h). The second tree worker (milp_share.h): the context's copy, nodes
 * passed with their warm starts, balancing, start and join. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bp.h"
#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_status.h"
#include "hv/plan_status.h"

/* This search's index among the tree workers (milp_share.h): 0 the main one, 1 the second. */
static size_t bp_worker_id(const bp_t *b)
{
    return b->tree.is_worker ? 1u : 0u;
}

/* A node's warm start in transit (hv_share_node_t.warm): the basis its parent left it and
 * that parent's stabilisation centre, with the columns named by content, because the two
 * workers' masters number them differently. Rows other than count rows are numbered alike
 * in both (made before the second worker copied the master); count rows go by their
 * interval. Layout, each item copied with memcpy: warm_head_t; n_rows warm_item_t (rows
 * that are neither basic nor count rows: index, status); n_crow warm_crow_t; n_art
 * warm_item_t (fruit artificials not at 0: column, status); n_basic times a warm_pat_t
 * followed by its fruits (uint32_t); n_pi doubles (the centre's fruit and cut duals). */
typedef struct warm_head {
    uint32_t n_rows, n_crow, n_art, n_basic, n_pi;
    double lag;
} warm_head_t;

typedef struct warm_item {
    int32_t index, stat;
} warm_item_t;

typedef struct warm_crow {
    uint32_t lo, hi;
    int32_t stat, art_stat;
    double sg;
} warm_crow_t;

typedef struct warm_pat {
    uint32_t stop, n;
} warm_pat_t;

static int bp_warm_put(hv_share_node_t *m, const void *p, size_t len)
{
    if (!hv_grow((void **)&m->warm, &m->warm_cap, m->warm_len + len, 1)) {
        return 0;
    }
    memcpy(m->warm + m->warm_len, p, len);
    m->warm_len += len;
    return 1;
}

/* Basis bi (b->tree.bases) as a warm start into m->warm (none when bi < 0). Returns 1, or 0
 * when out of memory. */
static int bp_warm_pack(bp_t *b, int32_t bi, hv_share_node_t *m)
{
    m->warm_len = 0;
    if (bi < 0) {
        return 1;
    }
    const basis_t *s = &b->tree.bases[bi];
    size_t nr = (size_t)s->n_rows, nc = (size_t)s->n_cols;
    if (!hv_grow((void **)&b->tree.col_pat, &b->tree.col_pat_cap, nr + nc + 1,
                 sizeof *b->tree.col_pat)) {
        return 0;
    }
    uint32_t *pat_of = b->tree.col_pat, *crow_of = b->tree.col_pat + nc + 1; /* by column / row */
    for (size_t j = 0; j <= nc; ++j) {
        pat_of[j] = UINT32_MAX;
    }
    for (size_t i = 0; i < nr; ++i) {
        crow_of[i] = UINT32_MAX;
    }
    for (size_t k = 0; k < b->m.n_pat; ++k) {
        if ((size_t)b->m.pat[k].col <= nc) {
            pat_of[b->m.pat[k].col] = (uint32_t)k;
        }
    }
    for (size_t r = 0; r < b->m.n_crow; ++r) {
        if ((size_t)b->m.crow[r].row <= nr) {
            crow_of[b->m.crow[r].row - 1] = (uint32_t)r;
        }
    }
    warm_head_t h = {0, 0, 0, 0, (uint32_t)s->n_pi, s->lag};
    int ok = bp_warm_put(m, &h, sizeof h);
    for (size_t i = 0; ok && i < nr; ++i) {
        if (crow_of[i] == UINT32_MAX && s->stat[i] != GLP_BS) {
            warm_item_t it = {(int32_t)i + 1, s->stat[i]};
            ok = bp_warm_put(m, &it, sizeof it);
            h.n_rows++;
        }
    }
    for (size_t i = 0; ok && i < nr; ++i) {
        if (crow_of[i] != UINT32_MAX) {
            const count_row_t *c = &b->m.crow[crow_of[i]];
            warm_crow_t it = {c->lo, c->hi, s->stat[i],
                              (size_t)c->art <= nc ? s->stat[nr + (size_t)c->art - 1] : GLP_NL,
                              crow_of[i] < s->n_sg ? s->sg[crow_of[i]] : 0.0};
            ok = bp_warm_put(m, &it, sizeof it);
            h.n_crow++;
        }
    }
    for (size_t j = 1; ok && j <= (size_t)b->m.n_art && j <= nc; ++j) {
        if (s->stat[nr + j - 1] != GLP_NL) {
            warm_item_t it = {(int32_t)j, s->stat[nr + j - 1]};
            ok = bp_warm_put(m, &it, sizeof it);
            h.n_art++;
        }
    }
    for (size_t j = 1; ok && j <= nc; ++j) {
        if (pat_of[j] != UINT32_MAX && s->stat[nr + j - 1] == GLP_BS) {
            const pattern_t *pt = &b->m.pat[pat_of[j]];
            warm_pat_t it = {pt->stop, pt->n};
            ok = bp_warm_put(m, &it, sizeof it) &&
                 bp_warm_put(m, b->m.pf + pt->first, pt->n * sizeof *b->m.pf);
            h.n_basic++;
        }
    }
    ok = ok && bp_warm_put(m, s->pi, s->n_pi * sizeof *s->pi);
    if (ok) {
        memcpy(m->warm, &h, sizeof h);
    }
    return ok;
}

/* Reads len bytes at *at of warm start m into p: 1, or 0 past its end. */
static int bp_warm_get(const hv_share_node_t *m, size_t *at, void *p, size_t len)
{
    if (m->warm_len - *at < len) {
        return 0;
    }
    memcpy(p, m->warm + *at, len);
    *at += len;
    return 1;
}

/* The basic patterns of warm start m (from byte *at) as patterns of this worker, made here
 * when missing, their indices into pat[0 .. n). Returns 1, 0 when m is malformed or names a
 * pair unknown here, -1 when out of memory. */
static int bp_warm_patterns(bp_t *b, const hv_share_node_t *m, size_t *at, int32_t *pat, uint32_t n)
{
    for (uint32_t q = 0; q < n; ++q) {
        warm_pat_t wp;
        if (!bp_warm_get(m, at, &wp, sizeof wp) || wp.n > b->nf || wp.stop >= b->ns ||
            !bp_warm_get(m, at, b->m.sel, wp.n * sizeof *b->m.sel)) {
            return 0;
        }
        double w[2];
        for (uint32_t i = 0; i < wp.n; ++i) {
            if (b->m.sel[i] >= b->nf) {
                return 0;
            }
        }
        if (!bp_pattern_times(b, wp.stop, b->m.sel, wp.n, w)) {
            return 0;
        }
        if (bp_pattern_add(b, wp.stop, b->m.sel, wp.n, b->tau_ms + fmax(w[0], w[1])) < 0) {
            return -1;
        }
        pat[q] = bp_pattern_find(b, wp.stop, b->m.sel, wp.n); /* pattern_add sorted b->m.sel */
    }
    return 1;
}

/* The statuses of warm start m (header h; its count rows and basic patterns pat[] exist
 * here) over this worker's master of nr rows and nc columns, rows first, into st, and its
 * count rows' duals into sg (by count row here). Returns 1 when they make a basis here. */
static int bp_warm_statuses(bp_t *b, const hv_share_node_t *m, const warm_head_t *h,
                            const int32_t *pat, int nr, int nc, unsigned char *st, double *sg)
{
    memset(st, GLP_BS, (size_t)nr); /* rows not named: basic; columns: at 0 */
    memset(st + nr, GLP_NL, (size_t)nc);
    size_t at = sizeof *h;
    warm_item_t it;
    for (uint32_t q = 0; q < h->n_rows; ++q) {
        bp_warm_get(m, &at, &it, sizeof it);
        if (it.index < 1 || it.index > nr) {
            return 0;
        }
        st[it.index - 1] = (unsigned char)it.stat;
    }
    for (uint32_t q = 0; q < h->n_crow; ++q) {
        warm_crow_t wc;
        bp_warm_get(m, &at, &wc, sizeof wc);
        const count_row_t *c = bp_crow_get(b, wc.lo, wc.hi); /* made by warm_unpack: found */
        st[c->row - 1] = (unsigned char)wc.stat;
        st[nr + c->art - 1] = (unsigned char)wc.art_stat;
        sg[c - b->m.crow] = wc.sg;
    }
    for (uint32_t q = 0; q < h->n_art; ++q) {
        bp_warm_get(m, &at, &it, sizeof it);
        if (it.index < 1 || it.index > b->m.n_art) {
            return 0;
        }
        st[nr + it.index - 1] = (unsigned char)it.stat;
    }
    for (uint32_t q = 0; q < h->n_basic; ++q) {
        st[nr + b->m.pat[pat[q]].col - 1] = GLP_BS;
    }
    int n_basic = 0;
    for (int i = 0; i < nr + nc; ++i) {
        n_basic += st[i] == GLP_BS;
    }
    return n_basic == nr;
}

/* The warm start of m as a basis of this worker's master in b->tree.bases (the count rows and
 * patterns it names are made here when missing): its index in *bi, -1 when m has none, is
 * malformed, or does not make a basis here (the node then starts from the current one).
 * Returns HV_OK or HV_ERR_PLAN_NOMEM. */
static hv_status_t bp_warm_unpack(bp_t *b, const hv_share_node_t *m, int32_t *bi)
{
    *bi = -1;
    warm_head_t h;
    size_t at = 0;
    if (!bp_warm_get(m, &at, &h, sizeof h)) {
        return HV_OK;
    }
    size_t pat_at =
        at + (h.n_rows + h.n_art) * sizeof(warm_item_t) + h.n_crow * sizeof(warm_crow_t);
    size_t pi_len = h.n_pi * sizeof(double);
    if (pat_at + pi_len > m->warm_len || h.n_basic > m->warm_len) {
        return HV_OK;
    }
    at += h.n_rows * sizeof(warm_item_t);
    for (uint32_t q = 0; q < h.n_crow; ++q) {
        warm_crow_t wc;
        bp_warm_get(m, &at, &wc, sizeof wc);
        if (bp_crow_get(b, wc.lo, wc.hi) == NULL) {
            return HV_ERR_PLAN_NOMEM;
        }
    }
    int32_t *pat = malloc(((size_t)h.n_basic + 1) * sizeof *pat);
    double *duals = NULL;
    unsigned char *st = NULL;
    int ok = pat != NULL ? bp_warm_patterns(b, m, &(size_t){pat_at}, pat, h.n_basic) : -1;
    int nr = glp_get_num_rows(b->m.lp), nc = glp_get_num_cols(b->m.lp);
    size_t npi = bp_n_pi(b);
    if (ok == 1) {
        st = malloc((size_t)nr + (size_t)nc);
        duals = calloc(npi + b->m.n_crow + 1, sizeof *duals);
        ok = st != NULL && duals != NULL ? 1 : -1;
    }
    if (ok == 1 && bp_warm_statuses(b, m, &h, pat, nr, nc, st, duals + npi)) {
        int centre = h.n_pi == npi; /* the same cuts: always, as the root made them all */
        if (centre) {
            memcpy(duals, m->warm + m->warm_len - pi_len, pi_len);
        }
        *bi = bp_basis_keep(b, nr, nc, st, duals, npi, b->m.n_crow, centre ? h.lag : -INFINITY);
    } else {
        free(st);
        free(duals);
    }
    free(pat);
    return ok < 0 ? HV_ERR_PLAN_NOMEM : HV_OK;
}

/* When the other worker waits for a node or asked for one: this worker's best open one
 * goes to it, as its path of restrictions from the root (node 0 of both workers, which
 * restricts nothing) and its warm start. */
hv_status_t bp_give_if_hungry(bp_t *b)
{
    while (b->tree.share != NULL && b->tree.heap_len > 0 &&
           hv_share_hungry(b->tree.share, bp_worker_id(b))) {
        int32_t k = bp_heap_pop(b);
        if (bp_prunable(b, b->tree.nodes[k].lb_ms)) {
            continue;
        }
        hv_share_node_t *m = &b->tree.msg;
        size_t n = 0;
        for (int32_t q = k; b->tree.nodes[q].parent >= 0; q = b->tree.nodes[q].parent) {
            n++;
        }
        if (!hv_grow((void **)&m->path, &m->cap, n + 1, sizeof *m->path) ||
            !bp_warm_pack(b, b->opt->warm_transfer ? b->tree.nodes[k].basis : -1, m)) {
            return HV_ERR_PLAN_NOMEM;
        }
        m->n = n;
        m->lb_ms = b->tree.nodes[k].lb_ms;
        for (int32_t q = k; b->tree.nodes[q].parent >= 0; q = b->tree.nodes[q].parent) {
            const node_t *d = &b->tree.nodes[q];
            m->path[--n] = (hv_share_step_t){(int)d->kind, d->fruit, d->lo, d->hi, d->rhs};
        }
        b->tree.given++;
        return hv_share_give(b->tree.share, m);
    }
    return HV_OK;
}

/* The node the other worker gave (in b->tree.msg) made a node here, into *k, with its warm
 * start when that makes a basis here (no pseudocost learning: its parent's bound is not
 * known here). Returns 1, or -1 when out of memory. */
static int bp_import_shared(bp_t *b, int32_t *k)
{
    const hv_share_node_t *m = &b->tree.msg;
    int32_t q = 0;
    for (size_t i = 0; i < m->n && q >= 0; ++i) {
        const hv_share_step_t *st = &m->path[i];
        q = bp_node_new(b, q, (node_kind_t)st->kind, st->fruit, st->lo, st->hi, st->rhs, m->lb_ms);
    }
    int32_t bi = -1;
    if (q < 0 || bp_warm_unpack(b, m, &bi) != HV_OK) {
        return -1;
    }
    b->tree.nodes[q].basis = bi;
    b->tree.taken++;
    b->tree.taken_warm += bi >= 0;
    *k = q;
    return 1;
}

/* This worker holds open nodes whose best bound is well above the other worker's: it asks
 * for the other's best (which comes at the other's next node) and queues what came of an
 * earlier ask, so that both search near the least bound. Returns 0, or -1 when out of
 * memory. */
int bp_balance_shared(bp_t *b)
{
    double lb = b->tree.heap_len > 0 ? b->tree.nodes[b->tree.heap[0]].lb_ms : INFINITY;
    double margin = fmax(1.0, BALANCE_SHARE * (b->inc.ub_ms - lb));
    if (!hv_share_balance(b->tree.share, bp_worker_id(b), lb, margin)) {
        return 0;
    }
    int32_t k;
    int r = hv_share_poll(b->tree.share, bp_worker_id(b), &b->tree.msg);
    if (r == 0) {
        return 0;
    }
    if (r < 0 || bp_import_shared(b, &k) < 0 || !bp_heap_push(b, k)) {
        return -1;
    }
    return 0;
}

/* This worker has no open node: one from the other worker, made a node here (*k). Returns
 * 1 with a node, 0 when the search is over or time is up, -1 when out of memory. */
int bp_next_shared(bp_t *b, int32_t *k)
{
    for (;;) {
        if (bp_must_stop(b)) {
            return 0;
        }
        int r = hv_share_wait(b->tree.share, bp_worker_id(b), &b->tree.msg);
        if (r == 0 || r == -2) {
            return r == 0 ? 0 : -1;
        }
        if (r == 1) {
            return bp_import_shared(b, k);
        }
    }
}

/* w (from bp_init) becomes a copy of b's state after the root: its master (same rows and
 * columns in the same order), pattern pool, cuts, count rows, fixed pairs and incumbent
 * (the pseudocosts come from the shared pool). Returns HV_OK or an error. */
static hv_status_t bp_clone(bp_t *w, const bp_t *b)
{
    size_t nf = b->nf, np = b->inst->n_pairs;
    glp_erase_prob(w->m.lp);
    glp_copy_prob(w->m.lp, b->m.lp, GLP_OFF);
    glp_set_obj_dir(w->m.lp, GLP_MIN);
    if (!hv_grow((void **)&w->m.pat, &w->m.pat_cap, b->m.n_pat + 1, sizeof *w->m.pat) ||
        !hv_grow((void **)&w->m.pf, &w->m.pf_cap, b->m.pf_len + 1, sizeof *w->m.pf) ||
        !hv_grow((void **)&w->m.pat_open, &w->m.open_cap, b->m.n_pat + 1, 1) ||
        !hv_grow((void **)&w->m.pat_dead, &w->m.dead_cap, b->m.n_pat + 1, 1) ||
        !hv_grow((void **)&w->m.crow, &w->m.crow_cap, b->m.n_crow + 1, sizeof *w->m.crow) ||
        !bp_iv_reserve(w, b->m.iv_cap)) {
        return HV_ERR_PLAN_NOMEM;
    }
    w->m.n_pat = b->m.n_pat;
    w->m.pf_len = b->m.pf_len;
    memcpy(w->m.pat, b->m.pat, b->m.n_pat * sizeof *w->m.pat);
    memcpy(w->m.pf, b->m.pf, b->m.pf_len * sizeof *w->m.pf);
    memcpy(w->m.pat_open, b->m.pat_open, b->m.n_pat);
    memcpy(w->m.pat_dead, b->m.pat_dead, b->m.n_pat);
    w->m.n_crow = b->m.n_crow;
    if (b->m.n_crow > 0) { /* b->m.crow is NULL until the first count row */
        memcpy(w->m.crow, b->m.crow, b->m.n_crow * sizeof *w->m.crow);
    }
    if (!bp_hash_rebuild(w, b->m.hcap)) {
        return HV_ERR_PLAN_NOMEM;
    }
    hv_status_t st = hv_src_copy(&w->cuts.src, &b->cuts.src);
    if (st != HV_OK) {
        return st;
    }
    memcpy(w->cuts.src_row, b->cuts.src_row, SR_MAX * sizeof *w->cuts.src_row);
    w->cuts.sr_rounds = b->cuts.sr_rounds;
    w->cuts.sr_lb0 = b->cuts.sr_lb0;
    memcpy(w->fix.pair_dead, b->fix.pair_dead, np);
    memcpy(w->fix.root_pi, b->fix.root_pi, bp_n_pi(b) * sizeof *w->fix.root_pi);
    w->fix.root_lag = b->fix.root_lag;
    w->fix.fixed_ub = b->fix.fixed_ub;
    memcpy(w->inc.best, b->inc.best, nf * sizeof *w->inc.best);
    hv_share_pc_copy(&w->tree.ivpc, &b->tree.ivpc,
                     b->ns * b->tree.ivpc_w); /* from here each its own */
    w->inc.ub_ms = b->inc.ub_ms;
    memcpy(w->m.warm_pair, b->m.warm_pair, np * sizeof *w->m.warm_pair);
    memcpy(w->m.warm_n, b->m.warm_n, b->ns * sizeof *w->m.warm_n);
    w->t_deadline = w->m.pricer.t_deadline_s = b->t_deadline;
    w->t_start = w->t_print = b->t_start;
    w->tree.is_worker = 1;
    w->sub = b->sub;
    memcpy(w->plugins, b->plugins, sizeof w->plugins);
    w->n_plugins = b->n_plugins;
    return HV_OK;
}

/* The second tree worker's thread: it makes its own master and pool as a copy of the main
 * search's (which waits meanwhile), searches, and leaves its results in `worker_t`. All
 * its GLPK objects live and die in this thread (GLPK's memory is per thread). */
struct worker {
    const bp_t *main;
    hv_share_t *share;
    pthread_t thread;
    pthread_mutex_t mu; /* guards copied */
    pthread_cond_t cv;
    int copied;
    hv_status_t st_copy; /* the copy's status */
    /* written by the worker before it ends, read after the join */
    hv_status_t st;
    long nodes, iv_branches, tailed, given, taken_warm;
    rins_stats_t rins;
    int inexact;
    double open_lb; /* of its nodes still open (INFINITY none), n_open of them */
    size_t n_open;
};

static void *bp_worker_main(void *arg)
{
    worker_t *wk = arg;
    bp_t w;
    hv_status_t st = bp_init(&w, wk->main->inst, wk->main->opt);
    if (st == HV_OK) {
        st = bp_clone(&w, wk->main);
    }
    if (st == HV_OK &&
        bp_node_new(&w, -1, KIND_ROOT, 0, 0, 0, 0, wk->main->tree.nodes[0].lb_ms) != 0) {
        st = HV_ERR_PLAN_NOMEM;
    }
    w.tree.share = wk->share;
    pthread_mutex_lock(&wk->mu);
    wk->st_copy = st;
    wk->copied = 1;
    pthread_cond_signal(&wk->cv);
    pthread_mutex_unlock(&wk->mu);
    if (st == HV_OK) {
        double root_lb; /* the main search's */
        st = bp_tree_search(&w, &root_lb, &w.tree.nodes_done);
        if (st != HV_OK) {
            hv_share_fail(wk->share);
        }
        double ub;
        if (hv_share_take(wk->share, w.inc.ub_ms, w.inc.best, &ub)) {
            w.inc.ub_ms = ub; /* prune what it leaves open by the best plan known */
        }
        wk->open_lb = bp_open_bound(&w, &wk->n_open);
        wk->st = st;
        wk->nodes = w.tree.nodes_done;
        wk->iv_branches = w.stats.iv_branches;
        wk->tailed = w.stats.tailed;
        wk->rins = w.stats.rins;
        wk->given = w.tree.given;
        wk->taken_warm = w.tree.taken_warm;
        wk->inexact = w.tree.inexact;
    }
    bp_free(&w);
    glp_free_env(); /* this thread's GLPK environment */
    return NULL;
}

static void bp_worker_free(worker_t *wk)
{
    pthread_cond_destroy(&wk->cv);
    pthread_mutex_destroy(&wk->mu);
    hv_share_destroy(wk->share);
    free(wk);
}

/* The second tree worker starts from a copy of the main search after its root. When its
 * thread cannot start the main search goes on alone. */
hv_status_t bp_worker_start(bp_t *b)
{
    worker_t *wk = calloc(1, sizeof *wk);
    if (wk == NULL || hv_share_create(2, b->nf, &wk->share) != HV_OK) {
        free(wk);
        return HV_ERR_PLAN_NOMEM;
    }
    wk->main = b;
    pthread_mutex_init(&wk->mu, NULL);
    pthread_cond_init(&wk->cv, NULL);
    hv_share_offer(wk->share, b->inc.best, b->inc.ub_ms);
    hv_share_pc_set(wk->share, &b->tree.pc);
    if (pthread_create(&wk->thread, NULL, bp_worker_main, wk) != 0) {
        if (b->opt->verbose >= 1) {
            fprintf(stderr, "price: the second tree worker did not start: one worker\n");
        }
        bp_worker_free(wk);
        return HV_OK;
    }
    pthread_mutex_lock(&wk->mu);
    while (!wk->copied) {
        pthread_cond_wait(&wk->cv, &wk->mu);
    }
    pthread_mutex_unlock(&wk->mu);
    hv_status_t st = wk->st_copy;
    if (st != HV_OK) {
        pthread_join(wk->thread, NULL);
        bp_worker_free(wk);
        return st;
    }
    b->tree.share = wk->share;
    b->tree.worker = wk;
    return HV_OK;
}

/* Stop (after an error: `failed`) and join the second worker. Its nodes, incumbent and
 * open bound come back: *open_lb the least bound of the nodes it or the queue still hold
 * (INFINITY none), *n_open their number. Returns the worker's status. */
hv_status_t bp_worker_join(bp_t *b, int failed, double *open_lb, size_t *n_open)
{
    worker_t *wk = b->tree.worker;
    if (failed) {
        hv_share_fail(wk->share);
    }
    pthread_join(wk->thread, NULL);
    double ub;
    if (hv_share_take(wk->share, b->inc.ub_ms, b->inc.best, &ub)) {
        b->inc.ub_ms = ub;
    }
    *open_lb = fmin(hv_share_open_lb(wk->share, n_open), wk->open_lb);
    *n_open += wk->n_open;
    if (bp_prunable(b, *open_lb)) {
        *n_open = 0; /* every node left open is pruned by the final incumbent */
    }
    b->tree.inexact |= wk->inexact;
    b->tree.nodes_done = wk->nodes;
    b->stats.iv_branches += wk->iv_branches;
    b->stats.tailed += wk->tailed;
    b->stats.rins.calls += wk->rins.calls;
    b->stats.rins.better += wk->rins.better;
    b->stats.rins.freed += wk->rins.freed;
    b->stats.rins.t_s += wk->rins.t_s;
    /* both workers take from one queue, so either may take back a node it gave: what
     * passed is what was given, by either, and of it what was taken warm, by either */
    b->tree.given += wk->given;
    b->tree.taken_warm += wk->taken_warm;
    hv_status_t st = wk->st;
    b->tree.share = NULL;
    b->tree.worker = NULL;
    bp_worker_free(wk);
    return st;
}
