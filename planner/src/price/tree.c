/* Branch-and-price (bp.h). The tree search: best bound first with dives, the node queue,
 * pruning, and the plugin driver. */
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

/* The time limit is reached or the caller asked to stop. */
int bp_must_stop(const bp_t *b)
{
    return hv_milp_now_s() >= b->t_deadline ||
           (b->opt->stop != NULL && b->opt->stop(b->opt->stop_ctx)) ||
           (b->tree.share != NULL && hv_share_failed(b->tree.share)); /* the other worker's error */
}

int bp_prunable(const bp_t *b, double lb_ms)
{
    if (!isfinite(b->inc.ub_ms)) {
        return 0;
    }
    lb_ms = fmax(lb_ms, b->region.region_lb);
    if (b->whole_ms && lb_ms > b->inc.ub_ms - 1.0 + 1e-6) {
        return 1;
    }
    return lb_ms >= b->inc.ub_ms - b->opt->rel_gap * b->inc.ub_ms - 1e-9;
}

int bp_node_new(bp_t *b, int32_t parent, node_kind_t kind, uint32_t fruit, uint32_t lo, uint32_t hi,
                int32_t rhs, double lb)
{
    if (!hv_grow((void **)&b->tree.nodes, &b->tree.nodes_cap, b->tree.n_nodes + 1,
                 sizeof *b->tree.nodes)) {
        return -1;
    }
    uint32_t depth = parent < 0 ? 0 : b->tree.nodes[parent].depth + 1;
    b->tree.nodes[b->tree.n_nodes] = (node_t){parent, kind, fruit, lo, hi, rhs, depth, lb, -1, 0.0};
    return (int)b->tree.n_nodes++;
}

/* Heap order: lower bound first, then deeper first (reaches plans sooner). */
static int bp_heap_less(const bp_t *b, int32_t x, int32_t y)
{
    const node_t *u = &b->tree.nodes[x], *v = &b->tree.nodes[y];
    return u->lb_ms < v->lb_ms || (u->lb_ms == v->lb_ms && u->depth > v->depth);
}

int bp_heap_push(bp_t *b, int32_t k)
{
    if (!hv_grow((void **)&b->tree.heap, &b->tree.heap_cap, b->tree.heap_len + 1,
                 sizeof *b->tree.heap)) {
        return 0;
    }
    size_t i = b->tree.heap_len++;
    while (i > 0 && bp_heap_less(b, k, b->tree.heap[(i - 1) / 2])) {
        b->tree.heap[i] = b->tree.heap[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    b->tree.heap[i] = k;
    return 1;
}

int32_t bp_heap_pop(bp_t *b)
{
    int32_t top = b->tree.heap[0], last = b->tree.heap[--b->tree.heap_len];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= b->tree.heap_len) {
            break;
        }
        if (c + 1 < b->tree.heap_len && bp_heap_less(b, b->tree.heap[c + 1], b->tree.heap[c])) {
            ++c;
        }
        if (!bp_heap_less(b, b->tree.heap[c], last)) {
            break;
        }
        b->tree.heap[i] = b->tree.heap[c];
        i = c;
    }
    if (b->tree.heap_len > 0) {
        b->tree.heap[i] = last;
    }
    return top;
}

/* The regional bound the other tree worker proved, if higher. */
void bp_region_floor(bp_t *b)
{
    if (b->tree.share != NULL) {
        b->region.region_lb = fmax(b->region.region_lb, hv_share_floor_get(b->tree.share));
    }
}

/* Node k ended in NODE_BRANCH at `sp`: its two children are made and queued, except the one
 * a dive goes on with (*dive, when `diving`; else *dive = -1). */
static hv_status_t bp_branch(bp_t *b, int32_t k, const split_t *sp, int diving, int32_t *dive)
{
    uint32_t f = sp->fruit;
    double lb = b->tree.nodes[k].lb_ms;
    int32_t c1, c2;
    if (sp->kind == KIND_FRUIT) {
        c1 = bp_node_new(b, k, KIND_FRUIT, f, b->tree.lo[f], sp->stop, 0, lb);
        c2 = bp_node_new(b, k, KIND_FRUIT, f, sp->stop + 1, b->tree.hi[f], 1, lb); /* rhs: up */
        if (c1 >= 0 && c2 >= 0) {
            b->tree.nodes[c1].frac = sp->mass_hi;
            b->tree.nodes[c2].frac = sp->mass_lo;
        }
    } else {
        c1 = bp_node_new(b, k, KIND_COUNT_LE, 0, sp->lo, sp->hi, sp->rhs, lb);
        c2 = bp_node_new(b, k, KIND_COUNT_GE, 0, sp->lo, sp->hi, sp->rhs + 1, lb);
        if (c1 >= 0 && c2 >= 0) {
            b->tree.nodes[c1].frac = sp->mass_lo; /* the count's distance each child forbids */
            b->tree.nodes[c2].frac = sp->mass_hi;
        }
        b->stats.iv_branches += sp->lo > 0 || sp->hi + 1 < b->ns;
    }
    if (c1 < 0 || c2 < 0) {
        return HV_ERR_PLAN_NOMEM;
    }
    b->tree.nodes[c1].basis = b->tree.nodes[c2].basis = bp_basis_save(b);
    *dive = diving ? (sp->up ? c2 : c1) : -1;
    if ((*dive != c1 && !bp_heap_push(b, c1)) || (*dive != c2 && !bp_heap_push(b, c2))) {
        return HV_ERR_PLAN_NOMEM;
    }
    return HV_OK;
}

/* The least bound of the nodes still queued at the end that the incumbent does not prune
 * (INFINITY none), their number in *n: the others (the limit came before they were popped)
 * cannot hold a better plan, as during the search. */
double bp_open_bound(const bp_t *b, size_t *n)
{
    double lb = INFINITY;
    *n = 0;
    for (size_t i = 0; i < b->tree.heap_len; ++i) {
        if (!bp_prunable(b, b->tree.nodes[b->tree.heap[i]].lb_ms)) {
            lb = fmin(lb, b->tree.nodes[b->tree.heap[i]].lb_ms);
            ++*n;
        }
    }
    return lb;
}

hv_status_t bp_search(bp_t *b, double *root_lb, long *nodes_done)
{
    /* a centre set before the root is a proven bound already */
    int32_t root =
        bp_node_new(b, -1, KIND_ROOT, 0, 0, 0, 0, b->m.root_centre ? b->m.center_lag : -INFINITY);
    if (root != 0 || !bp_heap_push(b, root)) { /* node 0: the root of shared paths too */
        return HV_ERR_PLAN_NOMEM;
    }
    *root_lb = -INFINITY;
    *nodes_done = 0;
    bp_call_t c = {.node = root};
    hv_status_t st = bp_plugins_run(b, BP_AT_START, &c);
    if (st != HV_OK) {
        return st;
    }
    return bp_tree_search(b, root_lb, nodes_done);
}

/* Best bound first, interrupted by dives: from the root and then every DIVE_EVERY nodes,
 * follow the child holding more of the master's mass until the dive is pruned or ends in
 * a plan. Dives find plans (the bound rarely closes before the incumbent is optimal); best
 * bound first proves them. With a second worker, a worker out of nodes takes one of the
 * other's; the second worker does not dive, and the root (node 0) is the main search's. */
hv_status_t bp_tree_search(bp_t *b, double *root_lb, long *nodes_done)
{
    const int32_t root = b->tree.is_worker ? -1 : 0;
    int32_t dive = -1;
    int diving = !b->tree.is_worker;
    long since_dive = 0;
    for (;;) {
        int32_t k = dive;
        if (b->tree.share != NULL && b->opt->balance_workers && bp_balance_shared(b) < 0) {
            return HV_ERR_PLAN_NOMEM;
        }
        bp_call_t bc = {.node = -1, .nodes_done = *nodes_done};
        hv_status_t stb = bp_plugins_run(b, BP_BEFORE_NODE, &bc);
        if (stb != HV_OK) {
            return stb;
        }
        if (k >= 0) {
            dive = -1;
        } else if (b->tree.heap_len > 0) {
            k = bp_heap_pop(b);
        } else if (b->tree.share == NULL) {
            break;
        } else {
            int r = bp_next_shared(b, &k);
            if (r <= 0) {
                return r == 0 ? HV_OK : HV_ERR_PLAN_NOMEM;
            }
        }
        if (bp_prunable(b, b->tree.nodes[k].lb_ms)) {
            if (k == root) {
                *root_lb = b->tree.nodes[k].lb_ms; /* closed by the ascent's bound, unsolved */
            }
            diving = 0;
            continue;
        }
        node_end_t end;
        split_t sp = {KIND_FRUIT, 0, 0, 0, 0, 0, 0.0, 0, 0.0, 0.0};
        hv_status_t st = bp_node_process(b, k, &end, &sp);
        if (st != HV_OK) {
            return st;
        }
        ++*nodes_done;
        if (k == root) {
            *root_lb = b->tree.nodes[k].lb_ms;
        }
        if (end == NODE_TIMEOUT) {
            return bp_heap_push(b, k) ? HV_OK : HV_ERR_PLAN_NOMEM; /* still open */
        }
        bp_pseudocost_record(b, k);
        if (end != NODE_BRANCH) {
            diving = 0;
            continue;
        }
        if (!diving && !b->tree.is_worker && ++since_dive >= DIVE_EVERY) {
            diving = 1;
            since_dive = 0;
        }
        if ((st = bp_branch(b, k, &sp, diving, &dive)) != HV_OK) {
            return st;
        }
        if (k == root) {
            bp_call_t ac = {.node = root, .lb_ms = b->tree.nodes[k].lb_ms};
            if ((st = bp_plugins_run(b, BP_AFTER_ROOT, &ac)) != HV_OK) {
                return st;
            }
        }
        /* The second core searches the tree too once the incumbent is near the bound: the
         * helper then stops (it rarely improves such a plan, and more nodes prove it). */
        if (b->opt->tree_threads > 1 && !b->tree.is_worker && b->tree.worker == NULL &&
            b->tree.heap_len > 0 &&
            b->inc.ub_ms - b->tree.nodes[b->tree.heap[0]].lb_ms <= WORKER_GAP * b->inc.ub_ms) {
            if ((b->inc.helper != NULL && (st = bp_helper_finish(b, 1)) != HV_OK) ||
                (st = bp_worker_start(b)) != HV_OK) {
                return st;
            }
        }
        if ((st = bp_give_if_hungry(b)) != HV_OK) {
            return st;
        }
    }
    return HV_OK;
}

/* Entry i's average pseudocost in direction d: its own when it has records, else the
 * average over all entries, else `none`. */
double bp_pc_mean(const hv_share_pc_t *pc, size_t i, int d, double none)
{
    if (pc->n[d][i] > 0) {
        return pc->sum[d][i] / (double)pc->n[d][i];
    }
    return pc->all_n[d] > 0 ? pc->all[d] / (double)pc->all_n[d] : none;
}

static void bp_pc_add(hv_share_pc_t *pc, size_t i, int d, double g)
{
    pc->sum[d][i] += g;
    pc->n[d][i]++;
    pc->all[d] += g;
    pc->all_n[d]++;
}

/* Child k of a fruit or interval-count split is solved: its bound rise over its parent's,
 * per unit of mass (or count) its restriction forbade, goes to the pseudocosts (capped at
 * the incumbent, where a child is pruned however far its bound would have risen). The
 * whole row's count children forbid nothing recorded (frac 0). */
void bp_pseudocost_record(bp_t *b, int32_t k)
{
    const node_t *c = &b->tree.nodes[k];
    if (c->frac <= LAMBDA_EPS || c->parent < 0) {
        return;
    }
    double plb = b->tree.nodes[c->parent].lb_ms, lb = fmin(c->lb_ms, b->inc.ub_ms);
    if (!isfinite(plb) || !isfinite(lb)) {
        return;
    }
    double g = fmax(0.0, lb - plb) / c->frac;
    if (c->kind == KIND_COUNT_LE || c->kind == KIND_COUNT_GE) {
        if (c->hi - c->lo < b->tree.ivpc_w) {
            bp_pc_add(&b->tree.ivpc, (size_t)c->lo * b->tree.ivpc_w + (c->hi - c->lo),
                      c->kind == KIND_COUNT_GE, g);
        }
    } else if (c->kind == KIND_FRUIT) {
        int d = c->rhs == 1; /* the "> stop" child */
        if (b->tree.share != NULL) {
            hv_share_pc_add(b->tree.share, c->fruit, d, g); /* both workers learn from it */
        } else {
            bp_pc_add(&b->tree.pc, c->fruit, d, g);
        }
    }
}

/* ---- the plugin driver ------------------------------------------------------------------ */

static int plugin_before(const bp_plugin_t *x, const bp_plugin_t *y)
{
    return x->timing < y->timing || (x->timing == y->timing && x->priority > y->priority);
}

void bp_plugins_include(bp_t *b, const bp_plugin_t *const *plugins, size_t n)
{
    for (size_t i = 0; i < n && b->n_plugins < BP_MAX_PLUGINS; ++i) {
        size_t j = b->n_plugins++; /* insertion: equal keys keep the order given */
        while (j > 0 && plugin_before(plugins[i], b->plugins[j - 1])) {
            b->plugins[j] = b->plugins[j - 1];
            --j;
        }
        b->plugins[j] = plugins[i];
    }
}

hv_status_t bp_plugins_run(bp_t *b, bp_timing_t timing, bp_call_t *call)
{
    for (size_t i = 0; i < b->n_plugins && !call->done; ++i) {
        const bp_plugin_t *p = b->plugins[i];
        if (p->timing == timing) {
            hv_status_t st = p->exec(b, p, call);
            if (st != HV_OK) {
                return st;
            }
        }
    }
    return HV_OK;
}
