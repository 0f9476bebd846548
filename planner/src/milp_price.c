/* Branch-and-price for the stop-and-harvest MILP (milp_price.h): the master LP on GLPK's
 * simplex, exact per-stop pricing (milp_pricing.h), branching on a fruit's stop interval,
 * best-bound node order, Lagrangian bounds. Internally times are in ms. */
#include <float.h>
#include <limits.h>
#include <glpk.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_clock.h"
#include "hv/milp_price.h"
#include "hv/milp_pricing.h"
#include "hv/grow_array.h"
#include "hv/milp_local_search.h"
#include "hv/milp_model.h"
#include "hv/milp_status.h"
#include "hv/milp_helper.h"
#include "hv/milp_region.h"
#include "hv/milp_rins.h"
#include "hv/milp_share.h"
#include "hv/milp_srcuts.h"
#include "hv/milp_subsolve.h"
#include "hv/milp_window.h"
#include "hv/plan_eval.h"
#include "hv/plan_status.h"

#define BIG_MS 1e6         /* cost of an artificial column: keeps every node's master feasible */
#define RC_EPS_MS 1e-6     /* a column enters when its reduced cost is below -RC_EPS_MS */
#define LAMBDA_EPS 1e-6    /* a master value this close to 0 or 1 counts as integral */
#define SMOOTHING 0.8      /* Wentges dual smoothing weight of the centre (SOLVER.md) */
#define SMOOTH_STEP 0.1    /* auto_smoothing: the weight's step per round */
#define SMOOTH_MAX 0.99    /* ... and its largest value */
#define ASCENT_DEFLECT 0.5 /* the root's ascent: share of the last direction kept (SOLVER.md) */
#define CAND_WINDOW 5      /* a stop's column enters when its reduced cost is the least
                              within +-CAND_WINDOW stops */
#define CENTRE_MIN_PAIRS 9000 /* from this many pairs, without ascent_steps, the root starts
                                 from the paper's LP duals (SOLVER.md), cover_rows 2
                                 makes the fruit rows ">= 1", the root separates
                                 sr_cuts_large rounds of cuts, and column_dive 1 does
                                 not dive */
#define PRIMAL_ROOT_GAP 2e-3 /* polish, column dive, row windows and rounding at every node
                                when the root leaves more than 0.2 % (SOLVER.md) */
#define POLISH_MAX_KICKS 1000 /* ~0.15 s at 60 fruits */
#define POLISH_CHUNK 50       /* kicks between two readings of the clock */
#define WORKER_GAP 2e-3 /* the incumbent's gap from which the second core searches the tree */
#define DIVE_EVERY 64     /* nodes between dives (search()) */
#define BALANCE_SHARE 0.2 /* balance_workers: a worker asks for the other's best node once
                             its own best bound is this share of its gap above the other's */
#define ROUND_EVERY 8     /* nodes between roundings of the master point, once the plan is
                             within PRIMAL_ROOT_GAP of the root's bound */
#define WINDOW_SHARE 0.25 /* of the time left after the root, at most, for row windows */
#define WINDOW_LIMIT_S 0.5 /* per window */
#define RINS_LIMIT_S 0.3   /* per relaxation-induced neighbourhood (sub-solve) */
#define RINS_MAX_FREE 60   /* ... fruits freed in one, at most */
#define RINS_CALL_S 1.0    /* ... time for the neighbourhoods at one master point */
#define SR_MAX 512          /* subset-row cuts at most (milp_srcuts.h), all made at the root */
#define SR_PER_ROUND 64     /* cuts added per separation round */
#define SR_PER_FRUIT 4      /* new cuts per fruit per round: spreads them over the row */
#define REGION_AFTER_NODES 16 /* tree nodes before the first regional bound (SOLVER.md) */
#define REGION_SHARE 0.5      /* ... of the time left, at most, for each */
#define REGION_EPS_MS 1e-3    /* ... proved above what the incumbent needs */
#define REGION_KICKS 20       /* local-search kicks on the plan a stretch's solution gives */
#define REGION_GROW 12        /* stops a stretch grows by on either side when short */
#define SR_MIN_VIOL 0.05    /* a cut enters when the master point violates it by this */
#define COUNT_MIN_SCORE 0.05 /* a count this far from an integer is branched on first */
#define IV_MIN_FRAC 0.1     /* interval branching: the least fractional count considered */
#define IV_GAP_WEIGHT 0.01  /* ... the weight of the empty stops around the interval */
#define IV_EDGE_GAP 1000u   /* ... the empty run counted beyond an end of the row */
#define IV_PC_FLOOR_MS 1e-3 /* ... the least estimated rise of a child (iv_pseudocost) */
#define TAIL_ROUNDS 10      /* tailing off: rounds without a fall of the master value */
#define TAIL_FALL_MS 1e-3   /* ... that counts as one */
#define BIND_MIN_WEIGHT 1e-3 /* binding_splits: the weight of a fruit whose arm never binds */
#define STALL_ITERS_PER_ROW 10 /* primal simplex iterations per master row before a call
                                  counts as stalled (a normal round takes ~40 in all) */

typedef struct pattern {
    uint32_t stop;
    uint32_t first, n; /* fruits bp->pf[first .. first + n), ascending */
    double cost_ms;
    int col; /* master column */
    unsigned char binds; /* the arms whose time is the pattern's max: bit hv_side_t */
} pattern_t;

/* A branch-and-bound node: the parent's restrictions plus one more. */
typedef enum node_kind {
    KIND_ROOT,
    KIND_FRUIT,    /* fruit `fruit` at a stop in [lo, hi]; rhs 1 for the "> stop" child */
    KIND_COUNT_LE, /* at most `rhs` stops used in [lo, hi] */
    KIND_COUNT_GE, /* at least `rhs` stops used in [lo, hi] */
    KIND_PATTERN   /* pattern `rhs` (at stop lo = hi) used: only in column-fixing dives */
} node_kind_t;

typedef struct node {
    int32_t parent;
    node_kind_t kind;
    uint32_t fruit, lo, hi;
    int32_t rhs;
    uint32_t depth;
    double lb_ms;
    int32_t basis; /* the parent's final master basis (index into bp_t.bases), -1 none */
    double frac;   /* KIND_FRUIT: the parent's master mass of `fruit` this child forbids */
} node_t;

/* What a parent leaves its children: its master basis (the status of rows 1..n_rows then
 * columns 1..n_cols) and its stabilisation centre (the duals of its best Lagrangian bound,
 * lag; at those duals a child's bound is at least lag, its patterns being fewer). */
typedef struct basis {
    int n_rows, n_cols;
    unsigned char *stat;
    double *pi, *sg; /* fruit then subset-row cut duals (n_pi), count-row duals (n_sg) */
    size_t n_pi, n_sg;
    double lag;
} basis_t;

/* A master row counting the patterns at stops [lo, hi], one per interval ever branched on
 * (rows never move, so a stored basis stays meaningful); free unless the current node's
 * path restricts that count to [min, max]. */
typedef struct count_row {
    uint32_t lo, hi;
    int row;
    int art; /* artificial column: keeps an "at least" row feasible at every node */
    double min, max; /* -INFINITY / INFINITY: no restriction on that side */
} count_row_t;

/* A stop's best pattern in the current pricing round. */
typedef struct cand {
    double rc, cost;
    uint32_t first, n; /* fruits cf[first .. first + n) */
} cand_t;

typedef struct worker worker_t;

/* What the relaxation-induced neighbourhoods did: sub-solves, better plans, fruits freed,
 * time (s). */
typedef struct rins_stats {
    long calls, better, freed;
    double t_s;
} rins_stats_t;

typedef struct bp {
    const hv_instance_t *inst;
    const hv_milp_options_t *opt;
    size_t nf, ns;
    double tau_ms, travel_ms;
    int whole_ms; /* every cost is whole ms: a better plan is better by >= 1 ms */

    size_t *stop_begin; /* CSR: pairs of stop p are stop_pair[stop_begin[p] .. ) (pair index) */
    size_t *stop_pair;
    int *row_of_fruit;  /* master row of fruit f, 0 when unreachable */
    int *row_of_stop;   /* master row of stop p, 0 when no fruit reaches it */
    int32_t *fixed_pat; /* per stop: the pattern the current node fixes there, -1 none */
    int n_art;
    count_row_t *crow;
    size_t n_crow, crow_cap;
    double *sigma_stop; /* per stop: the sum of the active count rows' duals */

    glp_prob *lp;
    pattern_t *pat;
    size_t n_pat, pat_cap;
    uint32_t *pf;
    size_t pf_len, pf_cap;
    unsigned char *pat_open;   /* the column is open in the master (2: fixed at 1) */
    size_t open_cap, dead_cap;
    unsigned char *pat_dead;  /* uses a pair removed by reduced-cost fixing */
    unsigned char *pair_dead; /* per pair: cannot be in a plan better than the incumbent */
    double *root_pi;          /* the root's best duals and their Lagrangian bound */
    double root_lag, fixed_ub;
    long pairs_fixed;
    int32_t *hslot; /* open-addressing hash of patterns, -1 = empty */
    size_t hcap;

    node_t *nodes;
    size_t n_nodes, nodes_cap;
    basis_t *bases;
    size_t n_bases, bases_cap, bases_bytes;
    int32_t cur_basis; /* what the current node's parent left it, -1 none */
    int32_t *heap;
    size_t heap_len, heap_cap;
    uint32_t *lo, *hi; /* the current node's stop interval per fruit */

    hv_pricer_t pricer;
    hv_src_t src;       /* subset-row cuts: their duals follow the fruits' in every pi */
    int *src_row;       /* per cut: its master row */
    uint32_t *src_hit;  /* scratch: the cuts a pattern meets (SR_MAX) */
    int32_t *src_bit;   /* per cut: its bit in the stop being priced, -1 none */
    double pen[64];     /* the penalties of those bits */
    int sr_rounds;      /* separation rounds done at the root */
    int sr_max;         /* ... and to do: opt->sr_cuts, or sr_cuts_large from CENTRE_MIN_PAIRS */
    double sr_lb0;      /* the root's bound before the first cut */
    int lp_dual_next;   /* rows were added: the next master solve is a dual one */
    long src_overflow;  /* stops priced with more than 64 cuts (the rest left out) */
    long src_bits, src_stops; /* cut bits given to priced stops, and those stops */
    long sr_dropped;          /* cuts deleted after the root as not worth their cost */
    hv_price_item_t *itl, *itr;
    uint32_t *sel;
    double *pi_lp, *mu_lp, *sg_lp; /* the master's duals: fruit (+ cut), stop, count rows */
    double *pi_c, *sg_c;          /* the duals of the best bound at this node (centre) */
    double *pi_sep, *sg_sep;      /* the duals priced at */
    double *cover;                /* per fruit: the patterns of the last pricing holding it */
    double smooth;                /* this node's smoothing weight (auto_smoothing) */
    size_t sg_cap, sgc_cap, sgs_cap;
    double *sigma_lp;
    double *stop_mass;    /* scratch of choose_count: prefix sums of the mass per stop */
    uint32_t *stop_empty; /* ... and the runs of stops without mass (2 ns) */
    double center_lag;
    int root_centre; /* center_lag / pi_c were set before the root: keep them */
    cand_t *cand; /* per stop */
    uint32_t *cf;
    size_t cf_len, cf_cap;
    size_t *warm_pair; /* per stop (slots at stop_begin[p]): its last best pattern's pairs */
    size_t *warm_n;    /* their number, SIZE_MAX when none yet */
    size_t *pair_at;   /* per fruit: its pair at the stop being priced */
    int *ind;
    double *val;
    size_t iv_cap; /* entries of ind and val */

    uint32_t *best; /* incumbent assignment */
    double ub_ms;
    double t_deadline;
    double t_start, t_print;
    long cg_iters;
    double t_heur; /* time spent in the rounding heuristic (s) */
    double t_fix;  /* time spent in reduced-cost fixing (s) */
    double t_dive; /* time spent in column-fixing dives (s) */
    long dives;
    double t_window; /* time spent re-planning row windows (s) */
    long windows, windows_better;
    rins_stats_t rins; /* the relaxation-induced neighbourhoods (both workers' at the end) */
    int rins_wait; /* nodes solved since the last neighbourhoods */
    hv_helper_t *helper; /* re-plans windows on the second core, NULL when not running */
    long helper_plans;   /* incumbents taken from it */
    int plan_cols_due;   /* the incumbent came from it during the root: its columns wait */
    double t_lp, t_price; /* time in the master LP and in pricing (s) */
    long lp_restarts;     /* master bases rebuilt after a singular warm start */
    long lp_stalls;       /* primal simplex calls stopped as stalled, finished by the dual */
    long heur_runs, heur_wins;
    int inexact; /* a numerically doubtful node was closed: do not claim optimality */
    /* hv_price_bound: per fruit the cost of leaving it uncovered (INFINITY: it must be
     * covered), NULL in a plain solve. A fruit that may be left out has the virtual stop
     * ns at the top of its interval, there its artificial column costs skip_ms, and a
     * branch on its stop can forbid that as it forbids real stops. */
    const double *skip_ms;
    double *stop_v; /* per stop: its term of the Lagrangian bound at the duals last priced */
    /* the regional bound (milp_region.h, opt->region_stops): the root's duals before any cut
     * (fruits), their stop terms and Lagrangian bound; the bound it proved, valid at every
     * node; the incumbent it last tried to prove; its sub-solves' tries, nodes and time */
    double *region_pi, *region_v, region_lag0;
    double region_lb, region_tried_ub;
    long region_tries, region_proofs, region_nodes;
    size_t region_s0, region_s1; /* the stretch whose sub-solve last finished */
    int region_stalled;          /* a sub-solve ran out of its time: no more tries */
    double t_region;
    /* pseudocosts of fruit splits, [0] the child "<= stop", [1] "> stop": per fruit the sum
     * of (child bound - parent bound) / frac and the count, and over all fruits; with two
     * workers read from and added to the pool they share (milp_share.h) */
    hv_share_pc_t pc;
    /* pseudocosts of count splits, as pc but per interval [lo, hi] of up to ivpc_w stops
     * (index lo * ivpc_w + hi - lo) and per unit of the count's distance a child forbade,
     * [0] the child "<= rhs", [1] ">= rhs + 1"; each worker keeps its own */
    hv_share_pc_t ivpc;
    size_t ivpc_w;
    /* two tree workers (milp_share.h): the main search holds the second in `worker` */
    hv_share_t *share;   /* NULL while one worker searches */
    struct worker *worker; /* the second worker, NULL none */
    int is_worker;         /* this is the second worker: no progress lines */
    long nodes_done;       /* the second worker's nodes */
    long iv_branches;      /* branches on an interval's stop count (interval_branching) */
    long tailed;           /* nodes branched on before their column generation converged */
    long given, taken;     /* nodes passed to and taken from the other worker */
    long taken_warm;       /* of `taken`, those whose warm start made a basis here */
    hv_share_node_t msg;   /* scratch: a node passed between the workers */
    uint32_t *col_pat;     /* scratch (warm_pack): the pattern of each column, the count
                              row of each row */
    size_t col_pat_cap;
} bp_t;

/* The time limit is reached or the caller asked to stop. */
static int must_stop(const bp_t *b)
{
    return hv_milp_now_s() >= b->t_deadline ||
           (b->opt->stop != NULL && b->opt->stop(b->opt->stop_ctx)) ||
           (b->share != NULL && hv_share_failed(b->share)); /* the other worker's error */
}

static int prunable(const bp_t *b, double lb_ms)
{
    if (!isfinite(b->ub_ms)) {
        return 0;
    }
    lb_ms = fmax(lb_ms, b->region_lb);
    if (b->whole_ms && lb_ms > b->ub_ms - 1.0 + 1e-6) {
        return 1;
    }
    return lb_ms >= b->ub_ms - b->opt->rel_gap * b->ub_ms - 1e-9;
}

/* ---- the pattern pool ------------------------------------------------------------------- */

static uint64_t pattern_hash(uint32_t stop, const uint32_t *f, uint32_t n)
{
    uint64_t h = 1469598103934665603ull ^ stop;
    for (uint32_t k = 0; k < n; ++k) {
        h = (h ^ f[k]) * 1099511628211ull;
        h ^= h >> 29;
    }
    return h;
}

static int pattern_equal(const bp_t *b, int32_t k, uint32_t stop, const uint32_t *f, uint32_t n)
{
    const pattern_t *p = &b->pat[k];
    return p->stop == stop && p->n == n && memcmp(b->pf + p->first, f, n * sizeof *f) == 0;
}

static int hash_insert(bp_t *b, int32_t k);

static int iv_reserve(bp_t *b, size_t n)
{
    size_t ci = b->iv_cap, cv = b->iv_cap;
    if (!hv_grow((void **)&b->ind, &ci, n + 1, sizeof *b->ind) ||
        !hv_grow((void **)&b->val, &cv, n + 1, sizeof *b->val)) {
        return 0;
    }
    b->iv_cap = ci < cv ? ci : cv;
    return 1;
}

static int hash_rebuild(bp_t *b, size_t cap)
{
    free(b->hslot);
    b->hslot = malloc(cap * sizeof *b->hslot);
    if (b->hslot == NULL) {
        return 0;
    }
    b->hcap = cap;
    for (size_t s = 0; s < cap; ++s) {
        b->hslot[s] = -1;
    }
    for (size_t k = 0; k < b->n_pat; ++k) {
        hash_insert(b, (int32_t)k);
    }
    return 1;
}

static int hash_insert(bp_t *b, int32_t k)
{
    const pattern_t *p = &b->pat[k];
    size_t s = (size_t)(pattern_hash(p->stop, b->pf + p->first, p->n) & (b->hcap - 1));
    while (b->hslot[s] >= 0) {
        s = (s + 1) & (b->hcap - 1);
    }
    b->hslot[s] = k;
    return 1;
}

/* The index of the pattern (stop, f[0..n)) in the pool, -1 when new. */
static int32_t pattern_find(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n)
{
    size_t s = (size_t)(pattern_hash(stop, f, n) & (b->hcap - 1));
    for (; b->hslot[s] >= 0; s = (s + 1) & (b->hcap - 1)) {
        if (pattern_equal(b, b->hslot[s], stop, f, n)) {
            return b->hslot[s];
        }
    }
    return -1;
}

/* open: 0 closed (fixed at 0), 1 open, 2 fixed at 1 */
static void col_open(bp_t *b, size_t j, unsigned char open)
{
    if (open != b->pat_open[j]) {
        b->pat_open[j] = open;
        double v = open == 2 ? 1.0 : 0.0;
        glp_set_col_bnds(b->lp, b->pat[j].col, open == 1 ? GLP_LO : GLP_FX, v, v);
    }
}

static int cmp_u32(const void *a, const void *c)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)c;
    return x < y ? -1 : x > y;
}

/* Cost of the pair (fruit f, stop p) in ms, or -1 when not reachable. */
static double pair_ms(const bp_t *b, uint32_t f, uint32_t p)
{
    size_t k = hv_instance_pair_index(b->inst, f, p);
    return k == SIZE_MAX ? -1.0 : 1000.0 * b->inst->pairs[k].cost_s;
}

/* The arms' times (ms) per stop of the assignment stop_of (HV_NO_STOP: none), added into
 * arm[2 p] (left) and arm[2 p + 1] (right), and the stops it uses marked in used[]. */
static void stop_arms(const bp_t *b, const uint32_t *stop_of, double *arm, unsigned char *used)
{
    for (size_t f = 0; f < b->nf; ++f) {
        uint32_t p = stop_of[f];
        if (p != HV_NO_STOP) {
            arm[2 * p + (b->inst->fruits[f].side == HV_SIDE_LEFT ? 0 : 1)] +=
                pair_ms(b, (uint32_t)f, p);
            used[p] = 1;
        }
    }
}

/* Stop p's cost (ms) from stop_arms' arrays: tau + its slower arm's time, 0 when unused. */
static double stop_cost_ms(const bp_t *b, const double *arm, const unsigned char *used,
                           size_t p)
{
    return used[p] ? b->tau_ms + fmax(arm[2 * p], arm[2 * p + 1]) : 0.0;
}

/* The arms' pick times (ms, indexed by hv_side_t) of the pattern of fruits f[0 .. n) at
 * `stop` into w. Returns 0 when one of the fruits is not reachable from there. */
static int pattern_times(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n,
                         double w[2])
{
    w[0] = w[1] = 0.0;
    for (uint32_t q = 0; q < n; ++q) {
        double c = pair_ms(b, f[q], stop);
        if (c < 0.0) {
            return 0;
        }
        w[b->inst->fruits[f[q]].side] += c;
    }
    return 1;
}

/* Which arms bind in the pattern of fruits f[0 .. n) at `stop`: bit s set when side s's
 * time is the larger (both when equal). */
static unsigned char pattern_binds(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n)
{
    double w[2];
    pattern_times(b, stop, f, n, w);
    return (unsigned char)((w[HV_SIDE_LEFT] >= w[HV_SIDE_RIGHT] ? 1u << HV_SIDE_LEFT : 0u) |
                           (w[HV_SIDE_RIGHT] >= w[HV_SIDE_LEFT] ? 1u << HV_SIDE_RIGHT : 0u));
}

/* Add the pattern (stop, fruits f[0..n), sorted here) as a master column unless known.
 * Returns 1 added, 0 known, -1 out of memory. */
static int pattern_add(bp_t *b, uint32_t stop, uint32_t *f, uint32_t n, double cost_ms)
{
    qsort(f, n, sizeof *f, cmp_u32);
    int32_t known = pattern_find(b, stop, f, n);
    if (known >= 0) {
        return 0;
    }
    if (!hv_grow((void **)&b->pat, &b->pat_cap, b->n_pat + 1, sizeof *b->pat) ||
        !hv_grow((void **)&b->pf, &b->pf_cap, b->pf_len + n, sizeof *b->pf)) {
        return -1;
    }
    if (!hv_grow((void **)&b->pat_open, &b->open_cap, b->n_pat + 1, 1) ||
        !hv_grow((void **)&b->pat_dead, &b->dead_cap, b->n_pat + 1, 1)) {
        return -1;
    }
    b->pat_dead[b->n_pat] = 0;
    b->pat[b->n_pat] = (pattern_t){stop, (uint32_t)b->pf_len, n, cost_ms, 0,
                                   pattern_binds(b, stop, f, n)};
    memcpy(b->pf + b->pf_len, f, n * sizeof *f);
    b->pf_len += n;
    b->pat_open[b->n_pat] = 1;
    int32_t k = (int32_t)b->n_pat++;
    if (2 * b->n_pat > b->hcap) {
        if (!hash_rebuild(b, 2 * b->hcap)) {
            return -1;
        }
    } else {
        hash_insert(b, k);
    }
    if (!iv_reserve(b, n + 2 + b->n_crow + b->src.n)) {
        return -1;
    }
    int j = glp_add_cols(b->lp, 1);
    b->pat[k].col = j;
    int len = 0;
    for (uint32_t q = 0; q < n; ++q) {
        b->ind[++len] = b->row_of_fruit[f[q]];
        b->val[len] = 1.0;
    }
    b->ind[++len] = b->row_of_stop[stop];
    b->val[len] = 1.0;
    for (size_t r = 0; r < b->n_crow; ++r) {
        if (b->crow[r].lo <= stop && stop <= b->crow[r].hi) {
            b->ind[++len] = b->crow[r].row;
            b->val[len] = 1.0;
        }
    }
    size_t nh = hv_src_hits(&b->src, f, n, b->src_hit);
    for (size_t h = 0; h < nh; ++h) {
        b->ind[++len] = b->src_row[b->src_hit[h]];
        b->val[len] = 1.0;
    }
    glp_set_mat_col(b->lp, j, len, b->ind, b->val);
    glp_set_col_bnds(b->lp, j, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(b->lp, j, cost_ms);
    return 1;
}

/* The patterns of an assignment as columns (a plan's stops are good columns to start with). */
static int add_assignment_columns(bp_t *b, const uint32_t *stop_of)
{
    for (size_t p = 0; p < b->ns; ++p) {
        uint32_t n = 0;
        double wl = 0.0, wr = 0.0;
        for (size_t f = 0; f < b->nf; ++f) {
            if (stop_of[f] == p) {
                double c = pair_ms(b, (uint32_t)f, (uint32_t)p);
                if (c < 0) {
                    return -1;
                }
                *(b->inst->fruits[f].side == HV_SIDE_LEFT ? &wl : &wr) += c;
                b->sel[n++] = (uint32_t)f;
            }
        }
        if (n > 0 && pattern_add(b, (uint32_t)p, b->sel, n, b->tau_ms + fmax(wl, wr)) < 0) {
            return -1;
        }
    }
    return 0;
}

/* Each fruit alone at its cheapest stop as a starting column: the first duals then stay
 * near pick costs instead of the artificials' big cost (SOLVER.md). */
static int add_start_columns(bp_t *b)
{
    const hv_instance_t *in = b->inst;
    for (size_t f = 0; f < b->nf; ++f) {
        size_t bk = SIZE_MAX;
        for (size_t k = in->fruit_begin[f]; k < in->fruit_begin[f + 1]; ++k) {
            if (bk == SIZE_MAX || in->pairs[k].cost_s < in->pairs[bk].cost_s) {
                bk = k;
            }
        }
        if (bk != SIZE_MAX) {
            b->sel[0] = (uint32_t)f;
            if (pattern_add(b, in->pairs[bk].stop, b->sel, 1,
                            b->tau_ms + 1000.0 * in->pairs[bk].cost_s) < 0) {
                return -1;
            }
        }
    }
    return 0;
}

/* ---- set-up ----------------------------------------------------------------------------- */

static void bp_free(bp_t *b)
{
    if (b->lp != NULL) {
        glp_delete_prob(b->lp);
    }
    free(b->stop_begin);
    free(b->stop_pair);
    free(b->row_of_fruit);
    free(b->row_of_stop);
    free(b->fixed_pat);
    free(b->pat);
    free(b->pf);
    free(b->pat_open);
    free(b->pat_dead);
    free(b->pair_dead);
    free(b->root_pi);
    free(b->hslot);
    free(b->nodes);
    for (size_t i = 0; i < b->n_bases; ++i) {
        free(b->bases[i].stat);
        free(b->bases[i].pi);
    }
    free(b->bases);
    free(b->heap);
    free(b->lo);
    for (int d = 0; d < 2; ++d) {
        free(b->pc.sum[d]);
        free(b->pc.n[d]);
        free(b->ivpc.sum[d]);
        free(b->ivpc.n[d]);
    }
    free(b->hi);
    hv_pricer_free(&b->pricer);
    hv_src_free(&b->src);
    free(b->src_row);
    free(b->src_hit);
    free(b->src_bit);
    free(b->itl);
    free(b->itr);
    free(b->sel);
    free(b->pi_lp);
    free(b->mu_lp);
    free(b->sg_lp);
    free(b->pi_c);
    free(b->sg_c);
    free(b->pi_sep);
    free(b->cover);
    free(b->sg_sep);
    free(b->sigma_lp);
    free(b->stop_mass);
    free(b->stop_empty);
    free(b->cand);
    free(b->warm_pair);
    free(b->warm_n);
    free(b->pair_at);
    free(b->cf);
    free(b->ind);
    free(b->val);
    free(b->crow);
    free(b->sigma_stop);
    free(b->best);
    free(b->stop_v);
    free(b->region_pi);
    free(b->region_v);
    hv_share_node_free(&b->msg);
    free(b->col_pat);
}

static hv_status_t bp_init(bp_t *b, const hv_instance_t *inst, const hv_milp_options_t *opt)
{
    memset(b, 0, sizeof *b);
    b->inst = inst;
    b->opt = opt;
    b->nf = inst->n_fruits;
    b->ns = inst->n_stops;
    b->tau_ms = 1000.0 * inst->stop_penalty_s;
    b->travel_ms = 1000.0 * inst->travel_time_s;
    b->ub_ms = INFINITY;
    hv_pricer_init(&b->pricer);
    size_t nf = b->nf, ns = b->ns;
    b->stop_begin = calloc(ns + 1, sizeof *b->stop_begin);
    b->stop_pair = malloc((inst->n_pairs + 1) * sizeof *b->stop_pair);
    b->row_of_fruit = calloc(nf + 1, sizeof *b->row_of_fruit);
    b->row_of_stop = calloc(ns + 1, sizeof *b->row_of_stop);
    b->fixed_pat = malloc((ns + 1) * sizeof *b->fixed_pat);
    b->lo = malloc((nf + 1) * sizeof *b->lo);
    b->ivpc_w = opt->interval_branching > 0 ? (size_t)opt->interval_branching : 0;
    for (int d = 0; d < 2; ++d) {
        b->pc.sum[d] = calloc(nf + 1, sizeof *b->pc.sum[d]);
        b->pc.n[d] = calloc(nf + 1, sizeof *b->pc.n[d]);
        b->ivpc.sum[d] = calloc(ns * b->ivpc_w + 1, sizeof *b->ivpc.sum[d]);
        b->ivpc.n[d] = calloc(ns * b->ivpc_w + 1, sizeof *b->ivpc.n[d]);
    }
    b->hi = malloc((nf + 1) * sizeof *b->hi);
    b->itl = malloc((nf + 1) * sizeof *b->itl);
    b->itr = malloc((nf + 1) * sizeof *b->itr);
    b->sel = malloc((nf + 1) * sizeof *b->sel);
    b->pi_lp = calloc(nf + SR_MAX + 1, sizeof *b->pi_lp);
    b->pi_c = calloc(nf + SR_MAX + 1, sizeof *b->pi_c);
    b->pi_sep = calloc(nf + SR_MAX + 1, sizeof *b->pi_sep);
    b->cover = calloc(nf + 1, sizeof *b->cover);
    b->src_row = calloc(SR_MAX + 1, sizeof *b->src_row);
    b->src_hit = calloc(SR_MAX + 1, sizeof *b->src_hit);
    b->src_bit = malloc((SR_MAX + 1) * sizeof *b->src_bit);
    b->mu_lp = calloc(ns + 1, sizeof *b->mu_lp);
    b->sigma_lp = calloc(ns + 1, sizeof *b->sigma_lp);
    b->stop_mass = calloc(ns + 1, sizeof *b->stop_mass);
    b->stop_empty = calloc(2 * ns + 1, sizeof *b->stop_empty);
    b->cand = calloc(ns + 1, sizeof *b->cand);
    b->pair_dead = calloc(inst->n_pairs + 1, 1);
    b->root_pi = calloc(nf + SR_MAX + 1, sizeof *b->root_pi);
    b->root_lag = -INFINITY;
    b->fixed_ub = INFINITY;
    b->cur_basis = -1;
    b->warm_pair = malloc((inst->n_pairs + 1) * sizeof *b->warm_pair);
    b->warm_n = malloc((ns + 1) * sizeof *b->warm_n);
    b->pair_at = malloc((nf + 1) * sizeof *b->pair_at);
    b->iv_cap = nf + 3;
    b->ind = malloc(b->iv_cap * sizeof *b->ind);
    b->val = malloc(b->iv_cap * sizeof *b->val);
    b->sigma_stop = calloc(ns + 1, sizeof *b->sigma_stop);
    b->best = malloc((nf + 1) * sizeof *b->best);
    b->stop_v = calloc(ns + 1, sizeof *b->stop_v);
    b->region_pi = calloc(nf + 1, sizeof *b->region_pi);
    b->region_v = calloc(ns + 1, sizeof *b->region_v);
    b->region_lb = b->region_lag0 = -INFINITY;
    b->region_tried_ub = INFINITY;
    b->region_s0 = SIZE_MAX;
    if (b->stop_v == NULL || b->region_pi == NULL || b->region_v == NULL ||
        b->stop_begin == NULL || b->stop_pair == NULL || b->row_of_fruit == NULL ||
        b->row_of_stop == NULL || b->fixed_pat == NULL || b->lo == NULL || b->hi == NULL ||
        b->itl == NULL || b->itr == NULL || b->sel == NULL || b->pi_lp == NULL || b->pi_c == NULL ||
        b->pi_sep == NULL || b->cover == NULL || b->mu_lp == NULL || b->sigma_lp == NULL ||
        b->stop_mass == NULL || b->stop_empty == NULL || b->cand == NULL ||
        b->warm_pair == NULL || b->warm_n == NULL || b->pair_at == NULL ||
        b->pair_dead == NULL || b->root_pi == NULL || b->src_row == NULL ||
        b->src_hit == NULL || b->src_bit == NULL || hv_src_init(&b->src, nf) != HV_OK ||
        b->pc.sum[0] == NULL || b->pc.sum[1] == NULL || b->pc.n[0] == NULL || b->pc.n[1] == NULL ||
        b->ivpc.sum[0] == NULL || b->ivpc.sum[1] == NULL || b->ivpc.n[0] == NULL ||
        b->ivpc.n[1] == NULL ||
        b->ind == NULL || b->val == NULL || b->best == NULL || b->sigma_stop == NULL ||
        !hash_rebuild(b, 1024)) {
        return HV_ERR_PLAN_NOMEM;
    }
    b->src.cross_sides = opt->sr_cross;
    b->whole_ms = fabs(b->tau_ms - round(b->tau_ms)) < 1e-6 && opt->ms_granularity;
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        b->stop_begin[inst->pairs[k].stop + 1]++;
        double ms = 1000.0 * inst->pairs[k].cost_s;
        b->whole_ms &= fabs(ms - round(ms)) < 1e-6;
    }
    for (size_t c = 0; c < SR_MAX; ++c) {
        b->src_bit[c] = -1;
    }
    for (size_t f = 0; f < nf; ++f) { /* the root's intervals: the centre is priced before it */
        b->lo[f] = 0;
        b->hi[f] = (uint32_t)(ns - 1);
    }
    for (size_t p = 0; p < ns; ++p) {
        b->stop_begin[p + 1] += b->stop_begin[p];
        b->warm_n[p] = SIZE_MAX;
        b->fixed_pat[p] = -1;
    }
    size_t *fill = malloc((ns + 1) * sizeof *fill);
    if (fill == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(fill, b->stop_begin, (ns + 1) * sizeof *fill);
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        b->stop_pair[fill[inst->pairs[k].stop]++] = k;
    }
    free(fill);

    /* master: a row per reachable fruit (>= 1 or = 1: opt->cover_rows), a row per usable
     * stop (<= 1), and an artificial column per fruit row */
    int cover = opt->cover_rows == 1 ||
                (opt->cover_rows == 2 && inst->n_pairs >= CENTRE_MIN_PAIRS);
    b->sr_max = inst->n_pairs >= CENTRE_MIN_PAIRS ? opt->sr_cuts_large : opt->sr_cuts;
    b->lp = glp_create_prob();
    glp_set_obj_dir(b->lp, GLP_MIN);
    int rows = 0;
    for (size_t f = 0; f < nf; ++f) {
        if (inst->fruit_begin[f] < inst->fruit_begin[f + 1]) {
            b->row_of_fruit[f] = ++rows;
        }
    }
    b->n_art = rows;
    for (size_t p = 0; p < ns; ++p) {
        if (b->stop_begin[p] < b->stop_begin[p + 1]) {
            b->row_of_stop[p] = ++rows;
        }
    }
    glp_add_rows(b->lp, rows);
    for (int i = 1; i <= b->n_art; ++i) {
        glp_set_row_bnds(b->lp, i, cover ? GLP_LO : GLP_FX, 1.0, 1.0);
    }
    for (int i = b->n_art + 1; i <= rows; ++i) {
        glp_set_row_bnds(b->lp, i, GLP_UP, 0.0, 1.0);
    }
    glp_add_cols(b->lp, b->n_art);
    for (int j = 1; j <= b->n_art; ++j) {
        int ind[2] = {0, j};
        double val[2] = {0.0, 1.0};
        glp_set_mat_col(b->lp, j, 1, ind, val);
        glp_set_col_bnds(b->lp, j, GLP_LO, 0.0, 0.0);
        glp_set_obj_coef(b->lp, j, BIG_MS);
    }
    return HV_OK;
}

/* ---- nodes -------------------------------------------------------------------------------- */

static int node_new(bp_t *b, int32_t parent, node_kind_t kind, uint32_t fruit, uint32_t lo,
                    uint32_t hi, int32_t rhs, double lb)
{
    if (!hv_grow((void **)&b->nodes, &b->nodes_cap, b->n_nodes + 1, sizeof *b->nodes)) {
        return -1;
    }
    uint32_t depth = parent < 0 ? 0 : b->nodes[parent].depth + 1;
    b->nodes[b->n_nodes] = (node_t){parent, kind, fruit, lo, hi, rhs, depth, lb, -1, 0.0};
    return (int)b->n_nodes++;
}

/* Heap order: lower bound first, then deeper first (reaches plans sooner). */
static int heap_less(const bp_t *b, int32_t x, int32_t y)
{
    const node_t *u = &b->nodes[x], *v = &b->nodes[y];
    return u->lb_ms < v->lb_ms || (u->lb_ms == v->lb_ms && u->depth > v->depth);
}

static int heap_push(bp_t *b, int32_t k)
{
    if (!hv_grow((void **)&b->heap, &b->heap_cap, b->heap_len + 1, sizeof *b->heap)) {
        return 0;
    }
    size_t i = b->heap_len++;
    while (i > 0 && heap_less(b, k, b->heap[(i - 1) / 2])) {
        b->heap[i] = b->heap[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    b->heap[i] = k;
    return 1;
}

static int32_t heap_pop(bp_t *b)
{
    int32_t top = b->heap[0], last = b->heap[--b->heap_len];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= b->heap_len) {
            break;
        }
        if (c + 1 < b->heap_len && heap_less(b, b->heap[c + 1], b->heap[c])) {
            ++c;
        }
        if (!heap_less(b, b->heap[c], last)) {
            break;
        }
        b->heap[i] = b->heap[c];
        i = c;
    }
    if (b->heap_len > 0) {
        b->heap[i] = last;
    }
    return top;
}

/* Duals per pi vector: the fruits' and then the subset-row cuts'. */
static size_t n_pi(const bp_t *b)
{
    return b->nf + b->src.n;
}

/* A basis of nr rows and nc columns (statuses `stat`, rows first) with its centre (`duals`:
 * n_pi fruit and cut duals, then n_sg count-row duals; bound lag) joins b->bases, which
 * takes both arrays: returns its index, or -1 (both freed) past the memory cap. */
static int32_t basis_keep(bp_t *b, int nr, int nc, unsigned char *stat, double *duals,
                          size_t n_pi, size_t n_sg, double lag)
{
    size_t bytes = (size_t)nr + (size_t)nc + (n_pi + n_sg) * sizeof(double);
    if (b->bases_bytes + bytes > ((size_t)256 << 20) ||
        !hv_grow((void **)&b->bases, &b->bases_cap, b->n_bases + 1, sizeof *b->bases)) {
        free(stat);
        free(duals);
        return -1;
    }
    b->bases[b->n_bases] = (basis_t){nr, nc, stat, duals, duals + n_pi, n_pi, n_sg, lag};
    b->bases_bytes += bytes;
    return (int32_t)b->n_bases++;
}

/* Keep the master's current basis; returns its index, -1 when not kept (memory). */
static int32_t basis_save(bp_t *b)
{
    int nr = glp_get_num_rows(b->lp), nc = glp_get_num_cols(b->lp);
    size_t npi = n_pi(b);
    unsigned char *st = malloc((size_t)nr + (size_t)nc);
    double *duals = malloc((npi + b->n_crow + 1) * sizeof *duals);
    if (st == NULL || duals == NULL) {
        free(st);
        free(duals);
        return -1;
    }
    memcpy(duals, b->pi_c, npi * sizeof *duals);
    if (b->n_crow > 0) {
        memcpy(duals + npi, b->sg_c, b->n_crow * sizeof *duals);
    }
    for (int i = 1; i <= nr; ++i) {
        st[i - 1] = (unsigned char)glp_get_row_stat(b->lp, i);
    }
    for (int j = 1; j <= nc; ++j) {
        st[nr + j - 1] = (unsigned char)glp_get_col_stat(b->lp, j);
    }
    return basis_keep(b, nr, nc, st, duals, npi, b->n_crow,
                      isfinite(b->center_lag) ? b->center_lag : -INFINITY);
}

/* Restore a kept basis: rows made since are basic, columns made since non-basic, so it
 * stays a valid basis of the grown master. */
static void basis_restore(bp_t *b, int32_t k)
{
    const basis_t *s = &b->bases[k];
    int nr = glp_get_num_rows(b->lp), nc = glp_get_num_cols(b->lp);
    for (int i = 1; i <= nr; ++i) {
        glp_set_row_stat(b->lp, i, i <= s->n_rows ? s->stat[i - 1] : GLP_BS);
    }
    for (int j = 1; j <= nc; ++j) {
        glp_set_col_stat(b->lp, j, j <= s->n_cols ? s->stat[s->n_rows + j - 1] : GLP_NL);
    }
}

/* The count row of the interval [lo, hi], made on first use. NULL when out of memory. */
static count_row_t *crow_get(bp_t *b, uint32_t lo, uint32_t hi)
{
    for (size_t r = 0; r < b->n_crow; ++r) {
        if (b->crow[r].lo == lo && b->crow[r].hi == hi) {
            return &b->crow[r];
        }
    }
    if (!iv_reserve(b, b->n_pat) ||
        !hv_grow((void **)&b->crow, &b->crow_cap, b->n_crow + 1, sizeof *b->crow)) {
        return NULL;
    }
    count_row_t *c = &b->crow[b->n_crow++];
    *c = (count_row_t){lo, hi, glp_add_rows(b->lp, 1), glp_add_cols(b->lp, 1), -INFINITY,
                       INFINITY};
    int len = 0;
    for (size_t j = 0; j < b->n_pat; ++j) {
        if (lo <= b->pat[j].stop && b->pat[j].stop <= hi) {
            b->ind[++len] = b->pat[j].col;
            b->val[len] = 1.0;
        }
    }
    glp_set_mat_row(b->lp, c->row, len, b->ind, b->val);
    glp_set_row_bnds(b->lp, c->row, GLP_FR, 0.0, 0.0);
    glp_set_row_stat(b->lp, c->row, GLP_BS); /* keeps the current basis valid */
    int ind[2] = {0, c->row};
    double val[2] = {0.0, 1.0};
    glp_set_mat_col(b->lp, c->art, 1, ind, val);
    glp_set_col_bnds(b->lp, c->art, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(b->lp, c->art, BIG_MS);
    return c;
}

/* Fruit f may be left uncovered (hv_price_bound). */
static int skippable(const bp_t *b, size_t f)
{
    return b->skip_ms != NULL && isfinite(b->skip_ms[f]);
}

/* ... and the current node allows that (its interval holds the virtual stop ns). */
static int skip_open(const bp_t *b, size_t f)
{
    return skippable(b, f) && b->hi[f] == b->ns;
}

/* The node's restrictions: its fruits' stop intervals with the master columns that respect
 * them opened, and its count rows. */
static hv_status_t node_apply(bp_t *b, int32_t k, int *infeasible)
{
    *infeasible = 0;
    for (size_t f = 0; f < b->nf; ++f) {
        b->lo[f] = 0;
        b->hi[f] = (uint32_t)(skippable(b, f) ? b->ns : b->ns - 1);
    }
    for (size_t r = 0; r < b->n_crow; ++r) {
        b->crow[r].min = -INFINITY;
        b->crow[r].max = INFINITY;
    }
    for (size_t p = 0; p < b->ns; ++p) {
        b->fixed_pat[p] = -1;
    }
    /* deeper restrictions of a fruit lie inside shallower ones: intersect along the path */
    for (int32_t q = k; q >= 0; q = b->nodes[q].parent) {
        const node_t *n = &b->nodes[q];
        if (n->kind == KIND_FRUIT) {
            if (n->lo > b->lo[n->fruit]) {
                b->lo[n->fruit] = n->lo;
            }
            if (n->hi < b->hi[n->fruit]) {
                b->hi[n->fruit] = n->hi;
            }
        } else if (n->kind == KIND_PATTERN) {
            const pattern_t *pt = &b->pat[n->rhs];
            b->fixed_pat[pt->stop] = n->rhs;
            for (uint32_t q = 0; q < pt->n; ++q) {
                b->lo[b->pf[pt->first + q]] = b->hi[b->pf[pt->first + q]] = pt->stop;
            }
        } else if (n->kind != KIND_ROOT) {
            count_row_t *c = crow_get(b, n->lo, n->hi);
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
    for (size_t r = 0; r < b->n_crow; ++r) {
        const count_row_t *c = &b->crow[r];
        int lo_set = isfinite(c->min), hi_set = isfinite(c->max);
        if (c->min > c->max) {
            *infeasible = 1; /* "at least" above "at most" on one interval */
            continue;
        }
        int type = lo_set && hi_set ? (c->min == c->max ? GLP_FX : GLP_DB)
                   : lo_set         ? GLP_LO
                   : hi_set         ? GLP_UP
                                    : GLP_FR;
        glp_set_row_bnds(b->lp, c->row, type, lo_set ? c->min : 0.0, hi_set ? c->max : 0.0);
    }
    for (size_t j = 0; j < b->n_pat; ++j) {
        const pattern_t *p = &b->pat[j];
        unsigned char ok = 1;
        for (uint32_t q = 0; q < p->n && ok; ++q) {
            uint32_t f = b->pf[p->first + q];
            ok = b->lo[f] <= p->stop && p->stop <= b->hi[f];
        }
        int32_t fx = b->fixed_pat[p->stop];
        col_open(b, j, fx == (int32_t)j ? 2 : (ok && fx < 0 && !b->pat_dead[j]));
    }
    for (size_t f = 0; b->skip_ms != NULL && f < b->nf; ++f) {
        if (skippable(b, f) && b->row_of_fruit[f] != 0) { /* the artificial stays: feasibility */
            glp_set_obj_coef(b->lp, b->row_of_fruit[f], skip_open(b, f) ? b->skip_ms[f] : BIG_MS);
        }
    }
    b->cur_basis = b->nodes[k].basis;
    if (b->cur_basis >= 0) {
        basis_restore(b, b->cur_basis);
    }
    return HV_OK;
}

/* ---- column generation at one node -------------------------------------------------------- */

/* The master's duals: pi per fruit (pi_lp), mu per stop row (mu_lp), and per count row
 * (sg_lp) clamped to the sign valid for the restriction in force (a dual of the wrong sign
 * would make the Lagrangian bound invalid). */
static int duals_read(bp_t *b)
{
    if (!hv_grow((void **)&b->sg_lp, &b->sg_cap, b->n_crow + 1, sizeof *b->sg_lp)) {
        return 0;
    }
    for (size_t f = 0; f < b->nf; ++f) {
        b->pi_lp[f] = b->row_of_fruit[f] ? glp_get_row_dual(b->lp, b->row_of_fruit[f]) : 0.0;
    }
    for (size_t c = 0; c < b->src.n; ++c) { /* "<= 1" rows: a dual above 0 is round-off */
        b->pi_lp[b->nf + c] = fmin(0.0, glp_get_row_dual(b->lp, b->src_row[c]));
    }
    for (size_t p = 0; p < b->ns; ++p) {
        b->mu_lp[p] = b->row_of_stop[p] ? glp_get_row_dual(b->lp, b->row_of_stop[p]) : 0.0;
    }
    for (size_t r = 0; r < b->n_crow; ++r) {
        const count_row_t *c = &b->crow[r];
        double d = glp_get_row_dual(b->lp, c->row);
        b->sg_lp[r] = d < 0.0 && isfinite(c->max) ? d : (d > 0.0 && isfinite(c->min) ? d : 0.0);
    }
    return 1;
}

/* sigma(p) of count-row duals sg into out[p]: the sum over the rows counting stop p. */
static void sigma_per_stop(const bp_t *b, const double *sg, double *out)
{
    for (size_t p = 0; p < b->ns; ++p) {
        out[p] = 0.0;
    }
    for (size_t r = 0; r < b->n_crow; ++r) {
        for (uint32_t p = b->crow[r].lo; sg[r] != 0.0 && p <= b->crow[r].hi; ++p) {
            out[p] += sg[r];
        }
    }
}

/* The pricing items of stop p at duals pi into itl / itr: its reachable fruits with a
 * positive dual and a pair not fixed out, and when node_only those the current node allows
 * there. Records each fruit's pair at p in pair_at. */
static void stop_items(bp_t *b, size_t p, const double *pi, int node_only, size_t *nl,
                       size_t *nr)
{
    const hv_instance_t *in = b->inst;
    *nl = *nr = 0;
    for (size_t q = b->stop_begin[p]; q < b->stop_begin[p + 1]; ++q) {
        size_t k = b->stop_pair[q];
        uint32_t f = in->pairs[k].fruit;
        b->pair_at[f] = k;
        if (pi[f] <= 1e-9 || b->pair_dead[k] || (node_only && (b->lo[f] > p || b->hi[f] < p))) {
            continue;
        }
        hv_price_item_t it = {f, 1000.0 * in->pairs[k].cost_s, pi[f], 0};
        if (in->fruits[f].side == HV_SIDE_LEFT) {
            b->itl[(*nl)++] = it;
        } else {
            b->itr[(*nr)++] = it;
        }
    }
}

/* The penalty the subset-row cuts at the duals pi put on a pattern of the fruits
 * f[0 .. n): -pi of every cut holding two or more of them. */
static double cut_penalty(bp_t *b, const uint32_t *f, size_t n, const double *pi)
{
    double s = 0.0;
    size_t nh = hv_src_hits(&b->src, f, n, b->src_hit);
    for (size_t h = 0; h < nh; ++h) {
        s -= pi[b->nf + b->src_hit[h]];
    }
    return s;
}

/* The cut bits of the stop's items itl[0 .. nl), itr[0 .. nr) (milp_pricing.h): one per
 * cut with a negative dual in pi that holds two or more of them, its penalty in b->pen.
 * Beyond 64 such cuts the rest are left out (*overflow = 1), which can only lower the
 * pricing's v, so bounds stay valid. Returns b->pen, or NULL when no item has a bit. */
static const double *cut_bits(bp_t *b, const double *pi, size_t nl, size_t nr, int *overflow)
{
    const hv_src_t *sr = &b->src;
    size_t n_touched = 0;
    int nbits = 0;
    *overflow = 0;
    for (size_t i = 0; i < nl + nr && sr->n > 0; ++i) {
        uint32_t f = i < nl ? b->itl[i].fruit : b->itr[i - nl].fruit;
        for (size_t q = sr->fbeg[f]; q < sr->fbeg[f + 1]; ++q) {
            uint32_t c = sr->fcut[q];
            if (pi[b->nf + c] >= 0.0) {
                continue;
            }
            if (b->src_bit[c] == -1) { /* met once */
                b->src_bit[c] = -2;
                b->src_hit[n_touched++] = c;
            } else if (b->src_bit[c] == -2) { /* twice: it can bite here */
                if (nbits < 64) {
                    b->pen[nbits] = -pi[b->nf + c];
                    b->src_bit[c] = nbits++;
                } else {
                    *overflow = 1;
                }
            }
        }
    }
    for (size_t i = 0; i < nl + nr && nbits > 0; ++i) { /* stop_items left every mask 0 */
        hv_price_item_t *it = i < nl ? &b->itl[i] : &b->itr[i - nl];
        for (size_t q = sr->fbeg[it->fruit]; q < sr->fbeg[it->fruit + 1]; ++q) {
            int32_t bit = b->src_bit[sr->fcut[q]];
            it->cuts |= bit >= 0 ? (uint64_t)1 << bit : 0;
        }
    }
    for (size_t t = 0; t < n_touched; ++t) {
        b->src_bit[b->src_hit[t]] = -1;
    }
    b->src_bits += nbits;
    b->src_stops += sr->n > 0;
    return nbits > 0 ? b->pen : NULL;
}

/* Price every stop at the duals (pi, sg): the Lagrangian bound
 *     T_travel + sum_f pi_f + sum_c pi_c + sum_r sg_r rhs_r + sum_p min(0, v_p)
 * with v_p the least tau + max(W_L, W_R) - pi(S) - sigma(p) + (the cut penalties) over the
 * patterns the node allows at p (pi_c <= 0: the subset-row cuts' duals); valid for any pi
 * and any sg of the right signs. Each stop's best pattern is
 * added to the master when its reduced cost at the master's own duals (pi_lp, mu_lp,
 * sg_lp) is negative. */
static hv_status_t price_at(bp_t *b, const double *pi, const double *sg, double *lag_ms,
                            int *added)
{
    const hv_instance_t *in = b->inst;
    double sum = b->travel_ms;
    for (size_t f = 0; f < n_pi(b); ++f) {
        sum += pi[f]; /* the fruits' duals, then the cuts' (right-hand sides 1) */
    }
    for (size_t r = 0; r < b->n_crow; ++r) {
        if (sg[r] != 0.0) {
            sum += sg[r] * (sg[r] < 0.0 ? b->crow[r].max : b->crow[r].min);
        }
    }
    sigma_per_stop(b, sg, b->sigma_stop);
    sigma_per_stop(b, b->sg_lp, b->sigma_lp);
    *added = 0;
    b->cf_len = 0;
    for (size_t p = 0; p < b->ns; ++p) {
        b->cand[p].rc = 0.0;
    }
    memset(b->cover, 0, b->nf * sizeof *b->cover);
    for (size_t f = 0; b->skip_ms != NULL && f < b->nf; ++f) {
        if (b->row_of_fruit[f] != 0 && skip_open(b, f) && b->skip_ms[f] < pi[f]) {
            sum += b->skip_ms[f] - pi[f]; /* left uncovered in the Lagrangian's optimum */
            b->cover[f] += 1.0;
        }
    }
    for (size_t p = 0; p < b->ns; ++p) {
        b->stop_v[p] = 0.0;
        if (b->row_of_stop[p] == 0) {
            continue;
        }
        if (b->fixed_pat[p] >= 0) {
            /* the one pattern allowed here, and it must be used: no min with 0 */
            const pattern_t *pt = &b->pat[b->fixed_pat[p]];
            double v = pt->cost_ms - b->sigma_stop[p] +
                       cut_penalty(b, b->pf + pt->first, pt->n, pi);
            for (uint32_t q = 0; q < pt->n; ++q) {
                v -= pi[b->pf[pt->first + q]];
                b->cover[b->pf[pt->first + q]] += 1.0;
            }
            sum += v;
            b->stop_v[p] = v;
            continue;
        }
        size_t nl, nr;
        stop_items(b, p, pi, 1, &nl, &nr);
        int overflow;
        const double *pen = cut_bits(b, pi, nl, nr, &overflow);
        b->src_overflow += overflow;
        /* last round's best pattern here, at today's duals: a threshold for the pricing */
        double offset = b->tau_ms - b->sigma_stop[p], v0 = INFINITY, t0 = 0.0;
        size_t *warm = b->warm_pair + b->stop_begin[p];
        if (b->warm_n[p] != SIZE_MAX) {
            double wl = 0.0, wr = 0.0, prof = 0.0;
            int ok = 1;
            for (size_t q = 0; q < b->warm_n[p] && ok; ++q) {
                const hv_pair_t *pa = &in->pairs[warm[q]];
                ok = b->lo[pa->fruit] <= p && p <= b->hi[pa->fruit] && !b->pair_dead[warm[q]];
                *(in->fruits[pa->fruit].side == HV_SIDE_LEFT ? &wl : &wr) += 1000.0 * pa->cost_s;
                prof += pi[pa->fruit];
                b->sel[q] = pa->fruit;
            }
            if (ok) {
                t0 = fmax(wl, wr);
                v0 = offset + t0 - prof + cut_penalty(b, b->sel, b->warm_n[p], pi);
            }
        }
        double v, time;
        size_t n_sel;
        hv_status_t st = hv_pricer_best(&b->pricer, b->itl, nl, b->itr, nr, offset, pen,
                                        fmin(0.0, v0), &v, b->sel, &n_sel, &time);
        if (st != HV_OK) {
            return st;
        }
        if (time >= 0.0) {
            b->warm_n[p] = n_sel;
            for (size_t q = 0; q < n_sel; ++q) {
                warm[q] = b->pair_at[b->sel[q]];
            }
        } else if (v0 < 0.0) {
            v = v0; /* nothing beats the warm pattern: it is the best */
            time = t0;
            n_sel = b->warm_n[p];
            for (size_t q = 0; q < n_sel; ++q) {
                b->sel[q] = in->pairs[warm[q]].fruit;
            }
        }
        sum += v; /* v <= 0 by construction */
        b->stop_v[p] = v;
        if (time < 0.0) {
            continue;
        }
        for (size_t q = 0; q < n_sel; ++q) {
            b->cover[b->sel[q]] += 1.0;
        }
        double cost = b->tau_ms + time, rc = cost - b->mu_lp[p] - b->sigma_lp[p] +
                                              cut_penalty(b, b->sel, n_sel, b->pi_lp);
        for (size_t q = 0; q < n_sel; ++q) {
            rc -= b->pi_lp[b->sel[q]];
        }
        if (rc < -RC_EPS_MS) {
            if (!hv_grow((void **)&b->cf, &b->cf_cap, b->cf_len + n_sel + 1, sizeof *b->cf)) {
                return HV_ERR_PLAN_NOMEM;
            }
            b->cand[p] = (cand_t){rc, cost, (uint32_t)b->cf_len, (uint32_t)n_sel};
            memcpy(b->cf + b->cf_len, b->sel, n_sel * sizeof *b->sel);
            b->cf_len += n_sel;
        }
    }
    /* neighbouring stops price near-identical patterns: add a stop's pattern only where
     * its reduced cost is the least within +-CAND_WINDOW stops */
    long w = CAND_WINDOW;
    for (size_t p = 0; p < b->ns; ++p) {
        double rc = b->cand[p].rc;
        int best = rc < -RC_EPS_MS;
        for (long d = -w; best && d <= w; ++d) {
            long q = (long)p + d;
            if (d != 0 && q >= 0 && q < (long)b->ns &&
                (b->cand[q].rc < rc || (b->cand[q].rc == rc && d < 0))) {
                best = 0;
            }
        }
        if (best) {
            const cand_t *c = &b->cand[p];
            memcpy(b->sel, b->cf + c->first, c->n * sizeof *b->sel);
            int r = pattern_add(b, (uint32_t)p, b->sel, c->n, c->cost);
            if (r < 0) {
                return HV_ERR_PLAN_NOMEM;
            }
            *added += r;
        }
    }
    *lag_ms = sum;
    return HV_OK;
}

/* Automatic smoothing (after Pessoa, Sadykov, Uchoa and Vanderbeck, 2018): the subgradient
 * at the duals just priced (1 - the times each fruit is covered by the stops' best
 * patterns) shows whether the bound rises towards the master's duals or back towards the
 * centre; the weight of the centre for the next round falls by SMOOTH_STEP in the first
 * case and rises by SMOOTH_STEP of what is left to 1 in the other. A child starts again
 * from SMOOTHING. Traced at alpha 2.5, a child's fixed weight of 0.8 held its bound far
 * below its master's value for 15 rounds (SOLVER.md). A weight of 0 adapts too: kept at 0,
 * a stalled master above the incumbent was priced at its own degenerate duals for up to
 * 1,400 rounds at alpha 4 seed 4 (SOLVER.md). */
static void smooth_adapt(bp_t *b, double alpha)
{
    double dot = 0.0;
    for (size_t f = 0; f < b->nf; ++f) {
        double g = (b->row_of_fruit[f] ? 1.0 : 0.0) - b->cover[f];
        dot += g * (b->pi_lp[f] - b->pi_c[f]);
    }
    b->smooth = dot > 0.0 ? fmax(0.0, alpha - SMOOTH_STEP)
                          : fmin(SMOOTH_MAX, alpha + SMOOTH_STEP * (1.0 - alpha));
}

/* One pricing round with Wentges smoothing: price at alpha * (the duals of the best bound
 * so far at this node) + (1 - alpha) * (the master's duals), which damps the master's
 * oscillating duals; when that finds no column (mis-pricing) price at the master's duals.
 * `lag_ms` is the best bound of the round. */
static hv_status_t price_round(bp_t *b, int fresh_node, double *lag_ms, int *added)
{
    size_t ncr = b->n_crow;
    if (!duals_read(b) || !hv_grow((void **)&b->sg_c, &b->sgc_cap, ncr + 1, sizeof *b->sg_c) ||
        !hv_grow((void **)&b->sg_sep, &b->sgs_cap, ncr + 1, sizeof *b->sg_sep)) {
        return HV_ERR_PLAN_NOMEM;
    }
    if (fresh_node && !b->root_centre) {
        b->center_lag = -INFINITY;
        const basis_t *pb = b->cur_basis >= 0 ? &b->bases[b->cur_basis] : NULL;
        if (pb != NULL && isfinite(pb->lag)) { /* start from the parent's centre */
            for (size_t f = 0; f < n_pi(b); ++f) {
                b->pi_c[f] = f < pb->n_pi ? pb->pi[f] : 0.0;
            }
            for (size_t r = 0; r < ncr; ++r) {
                b->sg_c[r] = r < pb->n_sg ? pb->sg[r] : 0.0;
            }
            b->center_lag = pb->lag;
        }
    }
    b->root_centre = 0;
    if (fresh_node || !b->opt->auto_smoothing) {
        b->smooth = SMOOTHING;
    }
    double alpha = isfinite(b->center_lag) ? b->smooth : 0.0;
    *lag_ms = -INFINITY;
    int retry = 0; /* pricing again at the master's duals after a mis-pricing */
    for (;;) {
        for (size_t f = 0; f < n_pi(b); ++f) {
            b->pi_sep[f] = alpha * b->pi_c[f] + (1.0 - alpha) * b->pi_lp[f];
        }
        for (size_t r = 0; r < ncr; ++r) {
            b->sg_sep[r] = alpha * b->sg_c[r] + (1.0 - alpha) * b->sg_lp[r];
        }
        double lag;
        hv_status_t st = price_at(b, b->pi_sep, b->sg_sep, &lag, added);
        if (st != HV_OK) {
            return st;
        }
        *lag_ms = fmax(*lag_ms, lag);
        if (b->opt->auto_smoothing && !retry && isfinite(b->center_lag)) {
            smooth_adapt(b, alpha);
        }
        if (lag > b->center_lag) {
            b->center_lag = lag;
            memcpy(b->pi_c, b->pi_sep, n_pi(b) * sizeof *b->pi_c);
            memcpy(b->sg_c, b->sg_sep, ncr * sizeof *b->sg_c);
        }
        if (*added > 0) {
            return HV_OK;
        }
        if (alpha == 0.0) {
            return HV_OK;
        }
        alpha = 0.0; /* mis-pricing: the smoothed duals found nothing */
        retry = 1;
    }
}

/* The time to the deadline as GLPK's tm_lim. */
static int ms_left(const bp_t *b)
{
    return hv_milp_limit_ms(b->t_deadline - hv_milp_now_s());
}

/* first: after a node switch only bounds changed, so the last basis stays dual feasible
 * and the dual simplex repairs it; after new columns the primal simplex continues. */
static hv_status_t lp_solve(bp_t *b, int first)
{
    glp_smcp sp;
    glp_init_smcp(&sp);
    sp.msg_lev = GLP_MSG_OFF;
    sp.meth = first ? GLP_DUALP : GLP_PRIMAL;
    double t0 = hv_milp_now_s();
    sp.tm_lim = ms_left(b);
    sp.it_lim = STALL_ITERS_PER_ROW * glp_get_num_rows(b->lp) + 1000;
    int r = glp_simplex(b->lp, &sp);
    if (r == GLP_EITLIM) {
        /* the master is highly degenerate and GLPK's primal simplex can stall on it (seen:
         * 300,000 iterations, 22 s, on one call); the dual simplex from the same basis
         * finishes such a call in milliseconds */
        b->lp_stalls++;
        sp.it_lim = INT_MAX;
        sp.meth = GLP_DUALP;
        sp.tm_lim = ms_left(b); /* what the stalled call left, not what it started with */
        r = glp_simplex(b->lp, &sp);
    }
    if (r == GLP_EBADB || r == GLP_ESING || r == GLP_ECOND) {
        b->lp_restarts++;
        glp_adv_basis(b->lp, 0); /* an unusable warm start (singular, invalid): start afresh */
        sp.tm_lim = ms_left(b);
        r = glp_simplex(b->lp, &sp);
    }
    b->t_lp += hv_milp_now_s() - t0;
    if (r == GLP_ETMLIM) {
        return HV_OK; /* the caller sees the deadline */
    }
    if (r == 0 && glp_get_status(b->lp) != GLP_OPT) {
        r = -glp_get_status(b->lp); /* artificials make every master feasible */
    }
    if (r != 0) {
        if (b->opt->verbose >= 1) {
            fprintf(stderr, "price: master LP failed: glp_simplex %d, status %d\n", r,
                    glp_get_status(b->lp));
        }
        return HV_ERR_MILP_GLPK;
    }
    return HV_OK;
}

/* Plan `a` (makespan t_s) is the incumbent, and the helper and the other tree worker hear
 * of it: a worker prunes by its own incumbent, so the plan it prunes by must reach the
 * result. */
static void set_incumbent(bp_t *b, const hv_assignment_t *a, double t_s)
{
    b->ub_ms = 1000.0 * t_s;
    memcpy(b->best, a->fruit_stop, b->nf * sizeof *b->best);
    if (b->helper != NULL) {
        hv_helper_offer(b->helper, a, t_s);
    }
    if (b->share != NULL) {
        hv_share_offer(b->share, b->best, b->ub_ms);
    }
}

/* A master solution in which every column is 0 or 1 as an assignment, into b->best when it
 * is better. Returns 1 when the master point was integral. */
static int take_integral(bp_t *b, const double *x)
{
    double skipped_ms = 0.0; /* hv_price_bound: the fruits left uncovered */
    for (size_t f = 0; f < b->nf; ++f) {
        double v = b->row_of_fruit[f] ? x[b->row_of_fruit[f]] : 0.0;
        if (v > LAMBDA_EPS && !(skip_open(b, f) && v > 1.0 - LAMBDA_EPS)) {
            return 0;
        }
        skipped_ms += v > LAMBDA_EPS ? b->skip_ms[f] : 0.0;
    }
    for (size_t r = 0; r < b->n_crow; ++r) {
        if (x[b->crow[r].art] > LAMBDA_EPS) {
            return 0;
        }
    }
    for (size_t k = 0; k < b->n_pat; ++k) {
        double v = x[b->pat[k].col];
        if (v > LAMBDA_EPS && v < 1.0 - LAMBDA_EPS) {
            return 0;
        }
    }
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return 0;
    }
    for (size_t k = 0; k < b->n_pat; ++k) {
        if (x[b->pat[k].col] > 0.5) {
            for (uint32_t q = 0; q < b->pat[k].n; ++q) {
                a.fruit_stop[b->pf[b->pat[k].first + q]] = b->pat[k].stop;
            }
        }
    }
    double t;
    if (b->skip_ms != NULL) { /* a plan with uncovered fruits: the master's own value */
        t = b->travel_ms + skipped_ms;
        for (size_t k = 0; k < b->n_pat; ++k) {
            t += x[b->pat[k].col] > 0.5 ? b->pat[k].cost_ms : 0.0;
        }
        if (t < b->ub_ms) {
            set_incumbent(b, &a, t / 1000.0);
        }
    } else if (hv_assignment_makespan(b->inst, &a, &t) == HV_OK && 1000.0 * t < b->ub_ms) {
        set_incumbent(b, &a, t);
    }
    hv_assignment_free(&a);
    return 1;
}

/* Where to branch: KIND_FRUIT: fruit's stop <= stop, or > stop; KIND_COUNT_LE: at most
 * rhs stops in [lo, hi], or at least rhs + 1. */
typedef struct split {
    node_kind_t kind;
    uint32_t fruit, stop;
    uint32_t lo, hi;
    int32_t rhs;
    double score;
    int up; /* the second child (> stop, >= rhs + 1) holds more of the master's mass */
    double mass_hi, mass_lo; /* KIND_FRUIT: the fruit's mass above / at or below `stop` */
} split_t;

typedef struct mass {
    uint32_t fruit, stop;
    double x;
    double x_binds; /* the part of x in patterns where the fruit's arm binds */
} mass_t;

static int by_fruit_stop(const void *a, const void *c)
{
    const mass_t *u = a, *v = c;
    if (u->fruit != v->fruit) {
        return u->fruit < v->fruit ? -1 : 1;
    }
    return u->stop < v->stop ? -1 : (u->stop > v->stop);
}

/* Entry i's average pseudocost in direction d: its own when it has records, else the
 * average over all entries, else `none`. */
static double pc_mean(const hv_share_pc_t *pc, size_t i, int d, double none)
{
    if (pc->n[d][i] > 0) {
        return pc->sum[d][i] / (double)pc->n[d][i];
    }
    return pc->all_n[d] > 0 ? pc->all[d] / (double)pc->all_n[d] : none;
}

static void pc_add(hv_share_pc_t *pc, size_t i, int d, double g)
{
    pc->sum[d][i] += g;
    pc->n[d][i]++;
    pc->all[d] += g;
    pc->all_n[d]++;
}

/* The average pseudocost of fruit f's split in direction d (0 "<= stop", 1 "> stop"): its
 * own when it was branched on in that direction, else the average over all fruits, else 1. */
static double pseudocost(const bp_t *b, uint32_t f, int d)
{
    return pc_mean(&b->pc, f, d, 1.0);
}

/* Child k of a fruit or interval-count split is solved: its bound rise over its parent's,
 * per unit of mass (or count) its restriction forbade, goes to the pseudocosts (capped at
 * the incumbent, where a child is pruned however far its bound would have risen). The
 * whole row's count children forbid nothing recorded (frac 0). */
static void pseudocost_record(bp_t *b, int32_t k)
{
    const node_t *c = &b->nodes[k];
    if (c->frac <= LAMBDA_EPS || c->parent < 0) {
        return;
    }
    double plb = b->nodes[c->parent].lb_ms, lb = fmin(c->lb_ms, b->ub_ms);
    if (!isfinite(plb) || !isfinite(lb)) {
        return;
    }
    double g = fmax(0.0, lb - plb) / c->frac;
    if (c->kind == KIND_COUNT_LE || c->kind == KIND_COUNT_GE) {
        if (c->hi - c->lo < b->ivpc_w) {
            pc_add(&b->ivpc, (size_t)c->lo * b->ivpc_w + (c->hi - c->lo),
                   c->kind == KIND_COUNT_GE, g);
        }
    } else if (c->kind == KIND_FRUIT) {
        int d = c->rhs == 1; /* the "> stop" child */
        if (b->share != NULL) {
            hv_share_pc_add(b->share, c->fruit, d, g); /* both workers learn from it */
        } else {
            pc_add(&b->pc, c->fruit, d, g);
        }
    }
}

/* The fruit whose stop is split most evenly by the master point, at the stop that halves
 * its mass (with opt->pseudocost: the fruit and stop of the largest product of the two
 * children's estimated bound rises, mass times pseudocost). score 0 when no fruit is
 * split. */
static hv_status_t choose_split(bp_t *b, const double *x, split_t *best)
{
    size_t n = 0, cap = 0;
    mass_t *m = NULL;
    for (size_t k = 0; k < b->n_pat; ++k) {
        double v = x[b->pat[k].col];
        if (v <= LAMBDA_EPS) {
            continue;
        }
        if (!hv_grow((void **)&m, &cap, n + b->pat[k].n, sizeof *m)) {
            free(m);
            return HV_ERR_PLAN_NOMEM;
        }
        for (uint32_t q = 0; q < b->pat[k].n; ++q) {
            uint32_t f = b->pf[b->pat[k].first + q];
            int binds = (b->pat[k].binds >> b->inst->fruits[f].side) & 1;
            m[n++] = (mass_t){f, b->pat[k].stop, v, binds ? v : 0.0};
        }
    }
    for (size_t f = 0; b->skip_ms != NULL && f < b->nf; ++f) {
        double v = b->row_of_fruit[f] ? x[b->row_of_fruit[f]] : 0.0;
        if (skip_open(b, f) && v > LAMBDA_EPS) { /* uncovered: mass at the virtual stop */
            if (!hv_grow((void **)&m, &cap, n + 1, sizeof *m)) {
                free(m);
                return HV_ERR_PLAN_NOMEM;
            }
            m[n++] = (mass_t){(uint32_t)f, (uint32_t)b->ns, v, 0.0};
        }
    }
    qsort(m, n, sizeof *m, by_fruit_stop);
    if (b->share != NULL && b->opt->pseudocost) {
        hv_share_pc_get(b->share, &b->pc); /* what both workers learnt */
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
         * binds), so a split of it rarely raises the bound (SOLVER.md) */
        double w_binds = b->opt->binding_splits ? fmax(tot_binds / tot, BIND_MIN_WEIGHT) : 1.0;
        double cum = 0.0;
        double pc_lo = b->opt->pseudocost ? pseudocost(b, m[i].fruit, 0) : 0.0;
        double pc_hi = b->opt->pseudocost ? pseudocost(b, m[i].fruit, 1) : 0.0;
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
                *best = (split_t){KIND_FRUIT, m[i].fruit, m[k - 1].stop, 0, 0, 0, score,
                                  cum < 0.5 * tot, tot - cum, cum};
            }
        }
        i = e;
    }
    free(m);
    return HV_OK;
}

/* Plan `a` (makespan t_s) becomes the incumbent when it beats the incumbent, with its
 * patterns as columns unless `defer_cols` (then they join once the root is solved). */
static hv_status_t offer_plan_cols(bp_t *b, const hv_assignment_t *a, double t_s, int defer_cols)
{
    if (1000.0 * t_s < b->ub_ms - 1e-6) {
        b->heur_wins++;
        set_incumbent(b, a, t_s);
        b->plan_cols_due = defer_cols;
        if (!defer_cols && add_assignment_columns(b, b->best) < 0) {
            return HV_ERR_PLAN_NOMEM;
        }
    }
    return HV_OK;
}

static hv_status_t offer_plan(bp_t *b, const hv_assignment_t *a, double t_s)
{
    return offer_plan_cols(b, a, t_s, 0);
}

/* Local search from plan `a` with `kicks` kicks; kept when it beats the incumbent. */
static hv_status_t improve_plan(bp_t *b, hv_assignment_t *a, unsigned kicks)
{
    hv_ls_options_t lo;
    hv_ls_options_default(&lo);
    lo.kicks = kicks;
    lo.seed = 0x9e3779b97f4a7c15ull * (uint64_t)(b->heur_runs + 1);
    double t;
    hv_status_t st = hv_local_search(b->inst, &lo, a, &t);
    b->heur_runs++;
    return st == HV_OK ? offer_plan(b, a, t) : st;
}

/* The master point x rounded into a (fresh) assignment: each fruit at the stop holding most
 * of its mass, or left out (HV_NO_STOP) when it has none there or, where it may be left
 * out (hv_price_bound), its artificial holds more. */
static hv_status_t round_point(const bp_t *b, const double *x, hv_assignment_t *a)
{
    double *mass = malloc((b->nf + 1) * sizeof *mass);
    if (mass == NULL || hv_assignment_alloc(a, b->nf) != HV_OK) {
        free(mass);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < b->nf; ++f) {
        mass[f] = skippable(b, f) && b->row_of_fruit[f] ? x[b->row_of_fruit[f]] : 0.0;
    }
    for (size_t k = 0; k < b->n_pat; ++k) {
        double v = x[b->pat[k].col];
        for (uint32_t q = 0; v > LAMBDA_EPS && q < b->pat[k].n; ++q) {
            uint32_t f = b->pf[b->pat[k].first + q];
            if (v > mass[f]) {
                mass[f] = v;
                a->fruit_stop[f] = b->pat[k].stop;
            }
        }
    }
    free(mass);
    return HV_OK;
}

/* Round a fractional master point to a plan (round_point), improve it by local search and
 * keep it when it beats the incumbent. */
static hv_status_t round_and_improve(bp_t *b, const double *x)
{
    double t0 = hv_milp_now_s();
    hv_assignment_t a;
    if (round_point(b, x, &a) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    int complete = 1;
    for (size_t f = 0; f < b->nf; ++f) {
        if (b->row_of_fruit[f] != 0 && a.fruit_stop[f] == HV_NO_STOP) {
            complete = 0; /* covered by an artificial only */
        }
    }
    hv_status_t st = complete ? improve_plan(b, &a, 20) : HV_OK;
    hv_assignment_free(&a);
    b->t_heur += hv_milp_now_s() - t0;
    return st;
}

/* hv_price_bound's rounding, at every node (round_point), valued as the master values it
 * (the local search knows no fruit left out). */
static hv_status_t round_skip(bp_t *b, const double *x)
{
    hv_assignment_t a;
    double *arm = calloc(2 * b->ns + 1, sizeof *arm);
    unsigned char *used = calloc(b->ns + 1, 1);
    if (arm == NULL || used == NULL || round_point(b, x, &a) != HV_OK) {
        free(arm);
        free(used);
        return HV_ERR_PLAN_NOMEM;
    }
    double t = b->travel_ms;
    int complete = 1;
    for (size_t f = 0; f < b->nf && complete; ++f) {
        if (a.fruit_stop[f] == HV_NO_STOP) {
            complete = !b->row_of_fruit[f] || skippable(b, f);
            t += complete && b->row_of_fruit[f] ? b->skip_ms[f] : 0.0;
        }
    }
    stop_arms(b, a.fruit_stop, arm, used);
    for (size_t p = 0; p < b->ns; ++p) {
        t += stop_cost_ms(b, arm, used, p);
    }
    hv_status_t st = HV_OK;
    if (complete && t < b->ub_ms - 1e-6) {
        set_incumbent(b, &a, t / 1000.0);
        b->heur_wins++;
        if (add_assignment_columns(b, b->best) < 0) {
            st = HV_ERR_PLAN_NOMEM;
        }
    }
    hv_assignment_free(&a);
    free(arm);
    free(used);
    return st;
}

/* The polish's length: polish_work * 100 / n^2 kicks (a descent costs ~n^2), at least
 * POLISH_CHUNK, at most POLISH_MAX_KICKS; 0 when polish_work is 0. */
static unsigned polish_kicks(const bp_t *b)
{
    if (b->opt->polish_work <= 0) {
        return 0;
    }
    size_t n = b->nf ? b->nf : 1;
    size_t kicks = (size_t)b->opt->polish_work * 100u / (n * n);
    return (unsigned)(kicks < POLISH_CHUNK ? POLISH_CHUNK
                                           : (kicks > POLISH_MAX_KICKS ? POLISH_MAX_KICKS : kicks));
}

/* Without a helper thread (which polishes from the start of the solve), when the root
 * leaves more than PRIMAL_ROOT_GAP: a long local search from the incumbent, before the pair
 * fixing, which a better incumbent makes stronger. */
static hv_status_t polish_incumbent(bp_t *b)
{
    unsigned kicks = polish_kicks(b);
    if (kicks == 0 || !isfinite(b->ub_ms)) {
        return HV_OK;
    }
    double t0 = hv_milp_now_s();
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(a.fruit_stop, b->best, b->nf * sizeof *b->best);
    hv_status_t st = HV_OK;
    /* in chunks, between which the clock is read: the local search does not poll it, and
     * at alpha 4 (250 fruits) 1000 kicks took 0.8 s, past a 10 s limit */
    for (unsigned done = 0; done < kicks && st == HV_OK && !must_stop(b); done += POLISH_CHUNK) {
        st = improve_plan(b, &a, kicks - done < POLISH_CHUNK ? kicks - done : POLISH_CHUNK);
    }
    hv_assignment_free(&a);
    b->t_heur += hv_milp_now_s() - t0;
    return st;
}

/* Pattern k's value at the master point x of columns 1..ncol (0 for the patterns added
 * since, which it does not hold). */
static double point_value(const bp_t *b, const double *x, int ncol, size_t k)
{
    return b->pat[k].col <= ncol ? x[b->pat[k].col] : 0.0;
}

/* The fruits on which the master point x (columns 1..ncol: the patterns added since are
 * not in it) and the incumbent disagree (x holds less than all of the fruit at its
 * incumbent stop), in order of their incumbent stop, into ord[]; returns their number. */
static size_t rins_disagree(const bp_t *b, const double *x, int ncol, double *agree,
                            uint32_t *ord)
{
    memset(agree, 0, b->nf * sizeof *agree);
    for (size_t k = 0; k < b->n_pat; ++k) {
        double v = point_value(b, x, ncol, k);
        for (uint32_t q = 0; v > LAMBDA_EPS && q < b->pat[k].n; ++q) {
            uint32_t f = b->pf[b->pat[k].first + q];
            agree[f] += b->best[f] == b->pat[k].stop ? v : 0.0;
        }
    }
    size_t n = 0;
    for (size_t f = 0; f < b->nf; ++f) {
        if (b->best[f] != HV_NO_STOP && agree[f] < 1.0 - LAMBDA_EPS) {
            ord[n++] = (uint32_t)f;
        }
    }
    for (size_t i = 1; i < n; ++i) { /* insertion sort: nearly ordered by fruit already */
        uint32_t f = ord[i];
        size_t j = i;
        for (; j > 0 && b->best[ord[j - 1]] > b->best[f]; --j) {
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
static hv_status_t rins_at(bp_t *b, const double *x, int ncol)
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
    for (size_t k = 0; k < b->n_pat; ++k) {
        if (point_value(b, x, ncol, k) <= LAMBDA_EPS) {
            continue; /* x does not hold it: its pairs stay closed */
        }
        for (uint32_t q = 0; q < b->pat[k].n; ++q) {
            size_t pk = hv_instance_pair_index(b->inst, b->pf[b->pat[k].first + q],
                                               b->pat[k].stop);
            if (pk != SIZE_MAX) {
                open[pk] = 1;
            }
        }
    }
    hv_status_t st = HV_OK;
    size_t at = 0; /* the first disagreeing fruit (in row order) of the next neighbourhood */
    size_t n = rins_disagree(b, x, ncol, agree, ord);
    for (;;) {
        double left = fmin(b->t_deadline, t0 + RINS_CALL_S) - hv_milp_now_s();
        if (at >= n || left <= 0.0 || must_stop(b)) {
            break;
        }
        size_t end = at + RINS_MAX_FREE < n ? at + RINS_MAX_FREE : n;
        for (size_t i = at; i < end; ++i) {
            freed[ord[i]] = 1;
        }
        memcpy(a.fruit_stop, b->best, nf * sizeof *b->best);
        double t = b->ub_ms / 1000.0;
        int better = 0;
        st = hv_rins_improve(b->inst, b->opt, freed, open, fmin(RINS_LIMIT_S, left), &a, &t,
                             &better, NULL);
        for (size_t i = at; i < end; ++i) {
            freed[ord[i]] = 0;
        }
        b->rins.calls++;
        b->rins.freed += (long)(end - at);
        if (st == HV_OK && better) {
            b->rins.better++;
            if (b->opt->verbose >= 1) {
                fprintf(stderr, "price: %.2f s: a neighbourhood of %zu fruits: %.3f -> %.3f s\n",
                        hv_milp_now_s() - b->t_start, end - at, b->ub_ms / 1000.0, t);
            }
            st = offer_plan(b, &a, t);
        }
        if (st != HV_OK) {
            break;
        }
        if (better) {
            n = rins_disagree(b, x, ncol, agree, ord); /* against the new incumbent */
        } else {
            at = end >= n ? n : at + RINS_MAX_FREE / 2; /* the next overlapping run */
        }
    }
    hv_assignment_free(&a);
    free(agree);
    free(ord);
    free(freed);
    free(open);
    b->rins.t_s += hv_milp_now_s() - t0;
    return st;
}

/* m: prefix sums of the master's mass per stop (choose_count) */
static int stop_has_mass(const double *m, size_t p)
{
    return m[p + 1] - m[p] >= LAMBDA_EPS;
}

/* Branching on the number of stops: the LP likes two stops at 0.8 with a third between
 * them at 0.2; "at most k stops" / "at least k + 1" separates those. First over the whole
 * row; when that count is (nearly) integral, over intervals [lo, hi] of up to
 * opt->interval_branching stops. An interval qualifies when both its end stops carry
 * master mass and its count is at least IV_MIN_FRAC from an integer; among those the score
 * q + IV_GAP_WEIGHT * g prefers the most fractional count q, then the interval with the
 * widest run g of empty stops on its sides: a cluster of stops the LP mixes, isolated from
 * the rest (SOLVER.md: of the rules tried, this one proved the most instances). With
 * opt->iv_pseudocost, once both kinds of count child have been solved somewhere, that
 * score is multiplied, per child, by the rise its interval's pseudocost predicts at this
 * count over the rise of an average interval's: the same intervals come back in many
 * subtrees, and those whose children rose steeply are branched on sooner (an interval
 * not yet branched on keeps its score). score 0 when no count is fractional. */
static void choose_count(bp_t *b, const double *x, split_t *best)
{
    double *m = b->stop_mass; /* m[p + 1] - m[p]: the master's mass at stop p */
    memset(m, 0, (b->ns + 1) * sizeof *m);
    for (size_t k = 0; k < b->n_pat; ++k) {
        m[b->pat[k].stop + 1] += x[b->pat[k].col];
    }
    for (size_t p = 0; p < b->ns; ++p) {
        m[p + 1] += m[p];
    }
    double tot = m[b->ns], ft = tot - floor(tot), sc = fmin(ft, 1.0 - ft);
    *best = (split_t){KIND_COUNT_LE, 0, 0, 0, (uint32_t)(b->ns - 1), (int32_t)floor(tot),
                      sc > LAMBDA_EPS ? sc : 0.0, ft >= 0.5, 0.0, 0.0};
    if (best->score >= COUNT_MIN_SCORE || b->opt->interval_branching <= 0) {
        return;
    }
    /* el[p]: the run of stops without mass that ends at p (p included), IV_EDGE_GAP when
     * it reaches the start of the row; er[p] the same from the right */
    uint32_t *el = b->stop_empty, *er = b->stop_empty + b->ns;
    for (size_t p = 0; p < b->ns; ++p) {
        uint32_t before = p == 0 ? IV_EDGE_GAP : el[p - 1];
        el[p] = stop_has_mass(m, p) ? 0 : (before == IV_EDGE_GAP ? IV_EDGE_GAP : before + 1);
    }
    for (size_t p = b->ns; p-- > 0;) {
        uint32_t after = p + 1 == b->ns ? IV_EDGE_GAP : er[p + 1];
        er[p] = stop_has_mass(m, p) ? 0 : (after == IV_EDGE_GAP ? IV_EDGE_GAP : after + 1);
    }
    size_t wmax = (size_t)b->opt->interval_branching;
    double bs = 0.0, bc = 0.0, bsc = 0.0;
    int use_pc = b->opt->iv_pseudocost && b->ivpc.all_n[0] > 0 && b->ivpc.all_n[1] > 0;
    double avg[2] = {0.0, 0.0};
    for (int d = 0; d < 2 && use_pc; ++d) {
        avg[d] = b->ivpc.all[d] / (double)b->ivpc.all_n[d];
    }
    /* narrowest first, then leftmost: the first of equal scores is kept */
    for (size_t w = 1; w <= wmax && w <= b->ns; ++w) {
        for (size_t a = 0, e = w - 1; e < b->ns; ++a, ++e) {
            if (!stop_has_mass(m, a) || !stop_has_mass(m, e)) {
                continue;
            }
            double c = m[e + 1] - m[a], f = c - floor(c), q = fmin(f, 1.0 - f);
            if (q < IV_MIN_FRAC) {
                continue;
            }
            uint32_t gl = a == 0 ? IV_EDGE_GAP : el[a - 1];
            uint32_t gr = e + 1 == b->ns ? IV_EDGE_GAP : er[e + 1];
            double s = q + IV_GAP_WEIGHT * (double)(gl < gr ? gl : gr), sc = s;
            for (int d = 0; d < 2 && use_pc; ++d) {
                /* each child's estimated rise over an average interval's at this count */
                double pc = pc_mean(&b->ivpc, a * b->ivpc_w + (e - a), d, avg[d]);
                double dist = d == 0 ? f : 1.0 - f;
                sc *= fmax(IV_PC_FLOOR_MS, pc * dist) / fmax(IV_PC_FLOOR_MS, avg[d] * dist);
            }
            if (sc > bsc * (1.0 + 1e-9) + 1e-12) {
                bsc = sc;
                bs = s;
                bc = c;
                best->lo = (uint32_t)a;
                best->hi = (uint32_t)e;
            }
        }
    }
    if (bs > 0.0) {
        best->rhs = (int32_t)floor(bc);
        best->score = bs;
        best->up = bc - floor(bc) >= 0.5;
        best->mass_lo = bc - floor(bc);
        best->mass_hi = 1.0 - best->mass_lo;
    }
}

/* Reduced-cost fixing of (fruit, stop) pairs from the root's duals pi (Lagrangian bound L):
 * a plan with fruit f at stop p costs at least L - min(0, v_p) + v_p(f), v_p(f) the best
 * pattern at p that contains f. Pairs for which that exceeds the incumbent less 1 ms (or
 * the relative gap) leave the pricing and their columns the master, for the whole tree. */
static hv_status_t fix_pairs(bp_t *b)
{
    const hv_instance_t *in = b->inst;
    const double *pi = b->root_pi;
    const double big = 1e7; /* forces an item into the pattern */
    double slack = b->ub_ms - b->root_lag - (b->whole_ms ? 1.0 : b->opt->rel_gap * b->ub_ms);
    double t0 = hv_milp_now_s();
    int stopped = 0;
    for (size_t p = 0; p < b->ns; ++p) {
        if (b->row_of_stop[p] == 0) {
            continue;
        }
        if (must_stop(b)) {
            stopped = 1; /* every pair fixed so far stays fixed: each was proven alone */
            break;
        }
        size_t nl, nr;
        stop_items(b, p, pi, 0, &nl, &nr); /* fixing is global: every pair not yet fixed */
        int overflow;
        const double *pen = cut_bits(b, pi, nl, nr, &overflow);
        if (overflow) {
            continue; /* v_p would be below the root's own: fixing from it is not safe */
        }
        double vp, time;
        size_t n_sel;
        hv_status_t st = hv_pricer_best(&b->pricer, b->itl, nl, b->itr, nr, b->tau_ms, pen, 0.0,
                                        &vp, b->sel, &n_sel, &time);
        if (st == HV_ERR_MILP_DEADLINE) {
            stopped = 1;
            break;
        }
        if (st != HV_OK) {
            return st;
        }
        for (size_t q = b->stop_begin[p]; q < b->stop_begin[p + 1] && !stopped; ++q) {
            size_t k = b->stop_pair[q];
            uint32_t f = in->pairs[k].fruit;
            if (b->pair_dead[k]) {
                continue;
            }
            hv_price_item_t *it = NULL; /* f's item (fruits with pi <= 0 force nothing) */
            for (size_t i = 0; i < nl && it == NULL; ++i) {
                it = b->itl[i].fruit == f ? &b->itl[i] : NULL;
            }
            for (size_t i = 0; i < nr && it == NULL; ++i) {
                it = b->itr[i].fruit == f ? &b->itr[i] : NULL;
            }
            double thr = slack + vp; /* keep the pair if v_p(f) <= thr */
            double v;
            if (it != NULL) {
                it->profit += big;
                /* without the cuts' penalties: v_p(f) only gets lower, so fixing stays
                 * valid, and a forced item makes the pricing with cut states slow */
                st = hv_pricer_best(&b->pricer, b->itl, nl, b->itr, nr, b->tau_ms, NULL,
                                    fmin(0.0, thr - big + 1e-6), &v, b->sel, &n_sel, &time);
                it->profit -= big;
                if (st == HV_ERR_MILP_DEADLINE) {
                    stopped = 1;
                    break;
                }
                if (st != HV_OK) {
                    return st;
                }
                if (time >= 0.0) {
                    continue; /* a pattern with f at or below the threshold: keep */
                }
            } else {
                continue; /* f's dual is not positive: no forced pricing, keep */
            }
            b->pair_dead[k] = 1;
            b->pairs_fixed++;
        }
    }
    for (size_t j = 0; j < b->n_pat; ++j) {
        const pattern_t *pt = &b->pat[j];
        for (uint32_t q = 0; q < pt->n && !b->pat_dead[j]; ++q) {
            size_t k = hv_instance_pair_index(b->inst, b->pf[pt->first + q], pt->stop);
            b->pat_dead[j] = b->pair_dead[k];
        }
        if (b->pat_dead[j]) {
            col_open(b, j, 0);
        }
    }
    if (!stopped) {
        b->fixed_ub = b->ub_ms;
    }
    b->t_fix += hv_milp_now_s() - t0;
    return HV_OK;
}

/* One round of subset-row cuts (milp_srcuts.h) on the master's point: the violated ones
 * become "<= 1" rows over the patterns holding two or more of their fruits; their duals
 * start at 0, where every bound so far stays valid. */
static hv_status_t separate_cuts(bp_t *b, size_t *added)
{
    *added = 0;
    b->sr_rounds++;
    size_t first = b->src.n, room = SR_MAX - first;
    hv_src_col_t *cols = malloc((b->n_pat + 1) * sizeof *cols);
    if (cols == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    size_t n = 0;
    for (size_t j = 0; j < b->n_pat; ++j) {
        double x = glp_get_col_prim(b->lp, b->pat[j].col);
        if (x > LAMBDA_EPS) {
            cols[n++] = (hv_src_col_t){b->pf + b->pat[j].first, b->pat[j].n, x};
        }
    }
    hv_status_t st = room == 0 ? HV_OK
                               : hv_src_separate(&b->src, b->inst, cols, n,
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
        for (size_t j = 0; j < b->n_pat; ++j) {
            size_t nh = hv_src_hits(&b->src, b->pf + b->pat[j].first, b->pat[j].n, b->src_hit);
            for (size_t h = 0; h < nh; ++h) {
                if (b->src_hit[h] >= first) {
                    size_t c = b->src_hit[h] - first;
                    if (pass == 0) {
                        beg[c + 2]++;
                    } else {
                        col[beg[c + 1]++] = b->pat[j].col;
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
    if (beg == NULL || col == NULL || !iv_reserve(b, len + 1)) {
        free(beg);
        free(col);
        return HV_ERR_PLAN_NOMEM;
    }
    int r0 = glp_add_rows(b->lp, (int)*added);
    for (size_t c = 0; c < *added; ++c) { /* beg[c] .. beg[c + 1]: cut first + c's columns */
        int row = r0 + (int)c, m = 0;
        for (size_t q = beg[c]; q < beg[c + 1]; ++q) {
            b->ind[++m] = col[q];
            b->val[m] = 1.0;
        }
        glp_set_mat_row(b->lp, row, m, b->ind, b->val);
        glp_set_row_bnds(b->lp, row, GLP_UP, 0.0, 1.0);
        glp_set_row_stat(b->lp, row, GLP_BS); /* keeps the current basis valid */
        b->src_row[first + c] = row;
        b->pi_lp[b->nf + first + c] = b->pi_c[b->nf + first + c] = 0.0;
        b->pi_sep[b->nf + first + c] = b->root_pi[b->nf + first + c] = 0.0;
    }
    free(beg);
    free(col);
    return HV_OK;
}

/* Deletes every cut row (at the root, before any count row or kept basis). The master is
 * re-solved without them; a basis left without a basic variable is rebuilt by lp_solve. */
static hv_status_t drop_cuts(bp_t *b)
{
    if (!iv_reserve(b, b->src.n + 1)) {
        return HV_ERR_PLAN_NOMEM;
    }
    int *num = b->ind;
    for (size_t c = 0; c < b->src.n; ++c) {
        num[c + 1] = b->src_row[c];
    }
    glp_del_rows(b->lp, (int)b->src.n, num);
    b->sr_dropped += (long)b->src.n;
    hv_src_clear(&b->src);
    b->sr_rounds = b->sr_max;
    b->center_lag = -INFINITY; /* the centre's bound counted the cuts' duals */
    return HV_OK;
}

/* Deletes the cut rows that are slack at the solved root (basic, a zero dual in the
 * master and in the centre): they cut nothing there, while every cut row makes each
 * master solve dearer in the tree (SOLVER.md). The centre and its bound stay as they are,
 * the basis stays valid (only basic rows go). *n_dropped: how many went. */
static hv_status_t purge_slack_cuts(bp_t *b, size_t *n_dropped)
{
    size_t n = b->src.n, nf = b->nf, m = 0, d = 0;
    unsigned char *keep = malloc(n + 1);
    if (keep == NULL || !iv_reserve(b, n + 1)) {
        free(keep);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t c = 0; c < n; ++c) {
        keep[c] = glp_get_row_stat(b->lp, b->src_row[c]) != GLP_BS ||
                  b->pi_lp[nf + c] < -RC_EPS_MS || b->pi_c[nf + c] < -RC_EPS_MS;
        if (!keep[c]) {
            b->ind[++d] = b->src_row[c];
        }
    }
    *n_dropped = d;
    if (d == 0) {
        free(keep);
        return HV_OK;
    }
    glp_del_rows(b->lp, (int)d, b->ind);
    for (size_t c = 0; c < n; ++c) {
        if (keep[c]) {
            int below = 0; /* GLPK renumbers the rows after a deleted one */
            for (size_t q = 1; q <= d; ++q) {
                below += b->ind[q] < b->src_row[c];
            }
            b->src_row[m] = b->src_row[c] - below;
            b->pi_c[nf + m] = b->pi_c[nf + c]; /* the master's duals are read afresh */
            ++m;
        }
    }
    hv_status_t st = hv_src_keep(&b->src, keep);
    free(keep);
    b->sr_dropped += (long)d;
    return st;
}

typedef enum node_end { NODE_PRUNED, NODE_INTEGRAL, NODE_BRANCH, NODE_TIMEOUT } node_end_t;

static void progress(bp_t *b, double lb_ms, int force)
{
    double t = hv_milp_now_s();
    if (b->opt->verbose < 1 || b->is_worker || (!force && t - b->t_print < 1.0)) {
        return;
    }
    b->t_print = t;
    double g = isfinite(b->ub_ms) ? (b->ub_ms - lb_ms) / b->ub_ms : INFINITY;
    fprintf(stderr,
            "price: %6.2f s  nodes %zu open %zu  columns %zu  T %.3f s  bound %.3f s  gap %.2e\n",
            t - b->t_start, b->n_nodes, b->heap_len, b->n_pat, b->ub_ms / 1000.0,
            lb_ms / 1000.0, g);
}

/* ---- regional bounds (milp_region.h) ------------------------------------------------------ */

/* At the root's converged master, before any cut: its best duals, their stop terms and
 * bound, which the regional bound uses (the cuts' duals would need their penalties in the
 * stretch's sub-problem, which it leaves out: measured, a rise of 0 where these give one). */
static hv_status_t region_capture(bp_t *b)
{
    if (b->opt->region_stops <= 0) { /* also in hv_price_bound's own solves (subsolve options) */
        return HV_OK;
    }
    double lag;
    int added;
    hv_status_t st = price_at(b, b->pi_c, b->sg_c, &lag, &added);
    if (st == HV_OK) {
        memcpy(b->region_pi, b->pi_c, b->nf * sizeof *b->region_pi);
        memcpy(b->region_v, b->stop_v, b->ns * sizeof *b->region_v);
        b->region_lag0 = lag;
    }
    return st;
}

/* The incumbent's gap over the captured bound, per stop: its pattern's cost less its fruits'
 * duals less the stop's term (0 where the plan does not stop: its term then). They sum to
 * incumbent - bound, so where they lie is where a stretch's rise can close the gap. */
static hv_status_t region_gaps(bp_t *b, double *g)
{
    double *arm = calloc(2 * b->ns + 1, sizeof *arm); /* per stop: the left, right arm's time */
    unsigned char *used = calloc(b->ns + 1, 1);
    if (arm == NULL || used == NULL) {
        free(arm);
        free(used);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t p = 0; p < b->ns; ++p) {
        g[p] = -b->region_v[p];
    }
    for (size_t f = 0; f < b->nf; ++f) {
        if (b->best[f] != HV_NO_STOP) {
            g[b->best[f]] -= b->region_pi[f];
        }
    }
    stop_arms(b, b->best, arm, used);
    for (size_t p = 0; p < b->ns; ++p) {
        g[p] += stop_cost_ms(b, arm, used, p);
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
static hv_status_t region_plan(bp_t *b, const uint32_t *plan, size_t s0, size_t s1)
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
        a.fruit_stop[f] = plan[f] != HV_NO_STOP ? plan[f]
                          : (b->best[f] != HV_NO_STOP && (b->best[f] < s0 || b->best[f] > s1))
                              ? b->best[f]
                              : HV_NO_STOP;
    }
    stop_arms(b, a.fruit_stop, arm, used);
    for (size_t f = 0; f < b->nf; ++f) {
        if (a.fruit_stop[f] != HV_NO_STOP || in->fruit_begin[f] == in->fruit_begin[f + 1]) {
            continue;
        }
        size_t side = in->fruits[f].side == HV_SIDE_LEFT ? 0 : 1, best = SIZE_MAX;
        double best_add = INFINITY;
        for (size_t k = in->fruit_begin[f]; k < in->fruit_begin[f + 1]; ++k) {
            uint32_t p = in->pairs[k].stop;
            double t = arm[2 * p + side] + 1000.0 * in->pairs[k].cost_s;
            double add = used[p] ? fmax(0.0, t - fmax(arm[2 * p], arm[2 * p + 1]))
                                 : b->tau_ms + t;
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
    hv_status_t st = improve_plan(b, &a, REGION_KICKS);
    hv_assignment_free(&a);
    return st;
}

/* [*s0, *s1] grown by REGION_GROW stops on either side, within the row. */
static void region_grow(const bp_t *b, size_t *s0, size_t *s1)
{
    *s0 = *s0 > REGION_GROW ? *s0 - REGION_GROW : 0;
    *s1 = *s1 + REGION_GROW < b->ns ? *s1 + REGION_GROW : b->ns - 1;
}

/* What the regional bound must prove for the incumbent to be optimal, above region_lag0. */
static double region_need(const bp_t *b)
{
    double target = b->whole_ms ? b->ub_ms - 1.0 + 1e-6 : b->ub_ms * (1.0 - b->opt->rel_gap);
    return target - b->region_lag0 + REGION_EPS_MS;
}

/* The stretch to try first: the shortest run of stops holding `need` of the incumbent's gap
 * (region_gaps), widened to every stop a fruit of those stops reaches, so that all of them
 * must be covered inside it (else the stretch's optimum leaves them out at no cost). 0 when
 * the gap lies nowhere shorter than the row. */
static int region_stretch(bp_t *b, double need, size_t *s0, size_t *s1)
{
    double *g = malloc((b->ns + 1) * sizeof *g);
    if (g == NULL || region_gaps(b, g) != HV_OK) {
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
        for (size_t q = b->stop_begin[p]; q < b->stop_begin[p + 1]; ++q) {
            uint32_t f = b->inst->pairs[b->stop_pair[q]].fruit;
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
static hv_status_t region_try(bp_t *b)
{
    b->region_tried_ub = b->ub_ms;
    size_t s0, s1;
    if (!region_stretch(b, region_need(b), &s0, &s1)) {
        return HV_OK;
    }
    if (b->region_s0 <= s0 && s1 <= b->region_s1) { /* inside one whose exact rise is known */
        s0 = b->region_s0;
        s1 = b->region_s1;
        region_grow(b, &s0, &s1);
    }
    uint32_t *plan = malloc((b->nf + 1) * sizeof *plan);
    if (plan == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    hv_status_t st = HV_OK;
    double last_rise = -INFINITY;
    while (st == HV_OK && s1 - s0 + 1 <= (size_t)b->opt->region_stops &&
           !(s0 == b->region_s0 && s1 == b->region_s1) && !prunable(b, b->region_lb)) {
        double t0 = hv_milp_now_s(), need = region_need(b);
        hv_region_result_t rr;
        st = hv_region_rise(b->inst, (uint32_t)s0, (uint32_t)s1, b->region_pi, b->region_v,
                            need, b->opt, t0 + REGION_SHARE * (b->t_deadline - t0), plan, &rr);
        if (st != HV_OK) {
            break;
        }
        b->region_tries++;
        b->region_nodes += rr.nodes;
        b->region_lb = fmax(b->region_lb, b->region_lag0 + rr.rise_ms);
        b->region_proofs += rr.rise_ms >= need - 1e-6;
        if (b->share != NULL) {
            hv_share_floor(b->share, b->region_lb);
        }
        if (b->opt->verbose >= 1) {
            fprintf(stderr, "price: regional bound over stops %zu-%zu: %.3f of the %.3f ms "
                    "needed above %.3f s (%.3f at its root), %ld nodes in %.2f s%s\n", s0, s1,
                    rr.rise_ms, need, b->region_lag0 / 1000.0, rr.root_rise_ms, rr.nodes,
                    hv_milp_now_s() - t0, rr.finished ? "" : ", stopped");
        }
        if (rr.has_plan && (st = region_plan(b, plan, s0, s1)) != HV_OK) {
            break;
        }
        b->t_region += hv_milp_now_s() - t0;
        if (!rr.finished) {
            b->region_stalled = 1; /* too hard for the time left */
            break;
        }
        b->region_s0 = s0; /* its exact rise is in region_lb: not again */
        b->region_s1 = s1;
        if (rr.rise_ms <= last_rise + REGION_EPS_MS) {
            break; /* growing did not raise it: the incumbent is likely not optimal */
        }
        last_rise = rr.rise_ms;
        region_grow(b, &s0, &s1);
    }
    free(plan);
    return st;
}

/* A regional bound is to be tried now: the main search, a captured root, a plan new since
 * the last try, REGION_AFTER_NODES nodes done, no sub-solve out of time, the gap open. */
static int region_due(const bp_t *b, long nodes_done)
{
    return !b->is_worker && isfinite(b->region_lag0) && !b->region_stalled &&
           b->ub_ms < b->region_tried_ub - 0.5 && nodes_done >= REGION_AFTER_NODES &&
           !prunable(b, b->region_lb);
}

/* The regional bound the other tree worker proved, if higher. */
static void region_floor(bp_t *b)
{
    if (b->share != NULL) {
        b->region_lb = fmax(b->region_lb, hv_share_floor_get(b->share));
    }
}

/* The helper's (from_helper) or else the other tree worker's better plan, if there is one,
 * becomes the incumbent. */
static hv_status_t take_plan(bp_t *b, int from_helper)
{
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    double t = 0.0, ub_ms = 0.0;
    int got = from_helper ? hv_helper_take(b->helper, b->ub_ms / 1000.0, &a, &t)
                          : hv_share_take(b->share, b->ub_ms - 1e-6, a.fruit_stop, &ub_ms);
    if (from_helper) {
        b->helper_plans += got;
    } else {
        t = ub_ms / 1000.0;
    }
    /* the helper's plans reach the root at times its thread sets: as columns they made the
     * root's column generation take 275-620 rounds at alpha 4 seed 8 instead of 376
     * (SOLVER.md), so they wait until the root is solved */
    hv_status_t st = got ? offer_plan_cols(b, &a, t, from_helper && !isfinite(b->root_lag))
                         : HV_OK;
    hv_assignment_free(&a);
    region_floor(b);
    return st;
}

static hv_status_t give_if_hungry(bp_t *b);

/* Column generation at node k until the master is optimal, the node is pruned, or time is
 * up. On NODE_BRANCH `sp` says where. */
static hv_status_t node_process(bp_t *b, int32_t k, node_end_t *end, split_t *sp)
{
    if (b->helper != NULL || b->share != NULL) {
        hv_status_t stp = take_plan(b, b->helper != NULL);
        if (stp != HV_OK) {
            return stp;
        }
    }
    if (isfinite(b->root_lag) && b->ub_ms < b->fixed_ub - 0.5) {
        hv_status_t stf = fix_pairs(b); /* a better incumbent fixes more */
        if (stf != HV_OK) {
            return stf;
        }
    }
    int infeasible;
    hv_status_t st0 = node_apply(b, k, &infeasible);
    if (st0 != HV_OK || infeasible) {
        if (infeasible) {
            b->nodes[k].lb_ms = INFINITY; /* what the pseudocosts learn from it */
        }
        *end = NODE_PRUNED;
        return st0;
    }
    /* tailing off (opt->tail_off_ms): below the root, a master whose value has not fallen
     * for TAIL_ROUNDS rounds and is within tail_off_ms of the node's Lagrangian bound is
     * branched on as it is; the children start from that bound, which is valid at any
     * round. With opt->tail_off_open, so is a stalled master that the incumbent does not
     * prune, however far that bound lies below: the node's LP value is at most the
     * master's, so no bound its column generation could reach would prune it (SOLVER.md:
     * such nodes priced one degenerate column a round for hundreds of rounds). When that
     * point cannot be branched on (integral, or no fractional count or fruit), the column
     * generation goes on to convergence, so nothing is closed on it. */
    double tail_ms = b->nodes[k].parent >= 0 ? (double)b->opt->tail_off_ms : 0.0;
    double best_master = INFINITY;
    int last_fall = 0, tailed = 0;
    for (int round = 0;; ++round) {
        if (must_stop(b)) {
            *end = NODE_TIMEOUT;
            return HV_OK;
        }
        hv_status_t st = lp_solve(b, round == 0 || b->lp_dual_next);
        b->lp_dual_next = 0;
        if (st != HV_OK) {
            return st;
        }
        if (must_stop(b)) {
            *end = NODE_TIMEOUT;
            return HV_OK;
        }
        if (round > 0 && b->helper != NULL && (st = take_plan(b, 1)) != HV_OK) {
            return st; /* the root can take seconds: take better plans as they come */
        }
        double lag;
        int added;
        double tp = hv_milp_now_s();
        st = price_round(b, round == 0, &lag, &added);
        b->t_price += hv_milp_now_s() - tp;
        if (st == HV_ERR_MILP_DEADLINE) {
            *end = NODE_TIMEOUT; /* this round's bound is unfinished: the node stays open */
            return HV_OK;
        }
        if (st != HV_OK) {
            return st;
        }
        b->cg_iters++;
        if ((st = give_if_hungry(b)) != HV_OK) {
            return st; /* an idle worker waited out whole nodes of 0.3-1 s (SOLVER.md) */
        }
        if (lag > b->nodes[k].lb_ms) {
            b->nodes[k].lb_ms = lag;
        }
        region_floor(b);
        if (prunable(b, b->nodes[k].lb_ms)) {
            *end = NODE_PRUNED;
            return HV_OK;
        }
        progress(b, b->heap_len ? fmin(b->nodes[k].lb_ms, b->nodes[b->heap[0]].lb_ms)
                                : b->nodes[k].lb_ms, 0);
        double master_ms = glp_get_obj_val(b->lp) + b->travel_ms;
        if (master_ms < best_master - TAIL_FALL_MS) {
            best_master = master_ms;
            last_fall = round;
        }
        tailed = added > 0 && tail_ms > 0.0 && round - last_fall >= TAIL_ROUNDS &&
                 (best_master - b->nodes[k].lb_ms <= tail_ms ||
                  (b->opt->tail_off_open && !prunable(b, best_master)));
        if (added > 0 && !tailed) {
            continue;
        }
        /* the master is optimal over all columns of this node (or tails off, below it) */
        if (b->nodes[k].parent < 0 && !isfinite(b->root_lag) && b->sr_rounds == 0 &&
            !isfinite(b->region_lag0) && (st = region_capture(b)) != HV_OK) {
            return st;
        }
        if (b->nodes[k].parent < 0 && !isfinite(b->root_lag) && b->sr_rounds < b->sr_max) {
            size_t n_cuts;
            if (b->sr_rounds == 0) {
                b->sr_lb0 = b->nodes[k].lb_ms;
            }
            if ((st = separate_cuts(b, &n_cuts)) != HV_OK) {
                return st;
            }
            if (n_cuts > 0) {
                b->lp_dual_next = 1; /* the point violates the new rows: repair by the dual */
                /* the centre stays valid (its cut duals 0) while the new duals of the cuts
                 * can be extreme: priced unsmoothed they blew the pricing up (alpha 4 seed
                 * 5: 200,000 frontier points a round, SOLVER.md) */
                b->smooth = SMOOTHING;
                continue;
            }
        }
        if (b->nodes[k].parent < 0 && !isfinite(b->root_lag) && b->src.n > 0 &&
            b->nodes[k].lb_ms - b->sr_lb0 < b->opt->sr_keep_gain * b->sr_lb0) {
            if ((st = drop_cuts(b)) != HV_OK) { /* not worth their cost in the tree */
                return st;
            }
            continue; /* the root keeps its bound; the master converges without them */
        }
        if (b->nodes[k].parent < 0 && !isfinite(b->root_lag) && b->src.n > 0 &&
            b->opt->sr_purge) {
            size_t n_dropped;
            if ((st = purge_slack_cuts(b, &n_dropped)) != HV_OK) {
                return st;
            }
            if (n_dropped > 0) {
                continue; /* the same point and duals: one master solve restores them */
            }
        }
        if (b->nodes[k].parent < 0 && !isfinite(b->root_lag)) {
            /* the root is solved: its best duals fix pairs for the whole tree */
            memcpy(b->root_pi, b->pi_c, n_pi(b) * sizeof *b->root_pi);
            b->root_lag = b->center_lag;
            if (b->plan_cols_due && add_assignment_columns(b, b->best) < 0) {
                return HV_ERR_PLAN_NOMEM;
            }
            b->plan_cols_due = 0;
            if (b->ub_ms - b->root_lag > PRIMAL_ROOT_GAP * b->ub_ms && b->helper == NULL &&
                (st = polish_incumbent(b)) != HV_OK) {
                return st;
            }
            if ((st = fix_pairs(b)) != HV_OK) {
                return st;
            }
        }
        int ncol = glp_get_num_cols(b->lp);
        double *x = malloc(((size_t)ncol + 1) * sizeof *x);
        if (x == NULL) {
            return HV_ERR_PLAN_NOMEM;
        }
        for (int j = 1; j <= ncol; ++j) {
            x[j] = glp_get_col_prim(b->lp, j);
        }
        if (take_integral(b, x)) {
            free(x); /* the node's LP optimum is a plan: the node is solved */
            if (tailed) {
                tail_ms = 0.0; /* ... unless the master was not optimal yet */
                continue;
            }
            *end = NODE_INTEGRAL;
            return HV_OK;
        }
        /* x covers the columns up to now: choose the branch before the rounding adds any */
        split_t fs = {KIND_FRUIT, 0, 0, 0, 0, 0, 0.0, 0, 0.0, 0.0};
        choose_count(b, x, sp);
        if (sp->score < COUNT_MIN_SCORE) {
            st = choose_split(b, x, &fs);
            if (fs.score > 0.0) {
                *sp = fs;
            }
        }
        /* the rounding pays near the root, and at every node while the plan is more than
         * PRIMAL_ROOT_GAP above the root's bound (node 0's; the second worker's node 0 is a
         * copy of the root): alpha 2.5 seed 4 found its optimal plan only so (SOLVER.md) */
        int far = b->ub_ms - b->nodes[0].lb_ms > PRIMAL_ROOT_GAP * b->ub_ms;
        if (st == HV_OK && b->skip_ms != NULL) {
            st = round_skip(b, x);
        } else if (st == HV_OK &&
                   (far || b->nodes[k].depth <= 2 || b->n_nodes % ROUND_EVERY == 0) &&
                   !must_stop(b)) {
            st = round_and_improve(b, x);
        }
        /* the neighbourhoods: every rins_every nodes once the plan is near the root's bound,
         * and at the root while it is far: there alpha 4 seed 4 found its optimum 2-3 s
         * sooner (SOLVER.md) */
        int root_far = far && b->nodes[k].parent < 0 && !b->is_worker;
        if (st == HV_OK && b->opt->rins_every > 0 &&
            (root_far || (!far && ++b->rins_wait >= b->opt->rins_every)) && !must_stop(b)) {
            b->rins_wait = 0;
            st = rins_at(b, x, ncol);
        }
        free(x);
        if (st != HV_OK) {
            return st;
        }
        if (sp->score <= 0.0 && tailed) {
            tail_ms = 0.0;
            continue;
        }
        if (sp->score <= 0.0) {
            /* every fruit sits at one stop, so the point is integral up to round-off:
             * close the node, but do not claim a proof on it */
            b->inexact = 1;
            *end = NODE_PRUNED;
            return HV_OK;
        }
        b->tailed += tailed;
        *end = NODE_BRANCH;
        return HV_OK;
    }
}

/* A stabilisation centre for the root from the paper's model: its LP relaxation's duals of
 * the assignment rows are duals for the master too, and the Lagrangian bound at them is at
 * least that LP's bound. Best effort: on any failure the root starts without a centre. */
static void compact_centre(bp_t *b, double limit_s)
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
            b->pi_c[f] = b->row_of_fruit[f]
                             ? 1000.0 * glp_get_row_dual(m.lp, b->row_of_fruit[f])
                             : 0.0;
        }
        double lag;
        int added;
        if (price_at(b, b->pi_c, b->sg_lp, &lag, &added) == HV_OK) {
            b->center_lag = lag;
            b->root_centre = 1;
        }
    }
    hv_milp_model_free(&m);
    if (b->opt->verbose >= 1) {
        fprintf(stderr, "price: centre from the paper's LP, bound %.3f s in %.2f s\n",
                b->center_lag / 1000.0, hv_milp_now_s() - t0);
    }
}

/* The root's first stabilisation centre by subgradient ascent on the Lagrangian of the
 * fruit rows, from zero duals: a step prices every stop (about 2 ms at alpha 4, against
 * about 8 ms for a round of the master LP), so `steps` steps bring the bound near the root
 * LP's before the master's first solve, and the column generation only has to finish
 * from there (SOLVER.md). Polyak steps towards the incumbent along the subgradient
 * deflected by ASCENT_DEFLECT of the last direction (it zig-zags less), halved after 4
 * steps without a better bound; the duals stay >= 0, so every step's value is a valid
 * bound. The best pattern of every stop in the second half of the steps joins the master. */
static hv_status_t ascent_centre(bp_t *b, int steps)
{
    size_t nf = b->nf;
    double *pi = calloc(nf + 1, sizeof *pi), *g = malloc((nf + 1) * sizeof *g),
           *d = calloc(nf + 1, sizeof *d), *pi_best = calloc(nf + 1, sizeof *pi_best);
    hv_status_t st = pi != NULL && g != NULL && d != NULL && pi_best != NULL
                         ? HV_OK
                         : HV_ERR_PLAN_NOMEM;
    double best = -INFINITY, theta = 1.0, t0 = hv_milp_now_s();
    int since = 0, it = 0;
    long added = 0;
    for (; st == HV_OK && it < steps && !must_stop(b); ++it) {
        double lag = b->travel_ms;
        for (size_t f = 0; f < nf; ++f) {
            lag += pi[f];
            g[f] = b->row_of_fruit[f] ? 1.0 : 0.0; /* 1 - the times f is covered */
        }
        for (size_t p = 0; p < b->ns && st == HV_OK; ++p) {
            if (b->row_of_stop[p] == 0) {
                continue;
            }
            size_t nl, nr, n_sel;
            double v, time;
            stop_items(b, p, pi, 1, &nl, &nr);
            st = hv_pricer_best(&b->pricer, b->itl, nl, b->itr, nr, b->tau_ms, NULL, 0.0, &v,
                                b->sel, &n_sel, &time);
            if (st != HV_OK || time < 0.0) {
                continue; /* time < 0: no pattern below 0, the stop stays closed */
            }
            lag += v;
            for (size_t q = 0; q < n_sel; ++q) {
                g[b->sel[q]] -= 1.0;
            }
            int r = 2 * it >= steps ? pattern_add(b, (uint32_t)p, b->sel, (uint32_t)n_sel,
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
        if (g2 == 0.0 || !isfinite(b->ub_ms)) {
            break; /* every fruit covered once (these duals are optimal), or no target */
        }
        double step = theta * (b->ub_ms - lag) / norm;
        for (size_t f = 0; f < nf; ++f) {
            pi[f] = fmax(0.0, pi[f] + step * d[f]);
        }
    }
    if (st == HV_ERR_MILP_DEADLINE) {
        st = HV_OK; /* the search sees the deadline */
    }
    if (st == HV_OK && isfinite(best)) {
        memcpy(b->pi_c, pi_best, nf * sizeof *pi_best);
        b->center_lag = best;
        b->root_centre = 1;
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

/* A primal dive by column fixing: from node `from` (just solved), repeatedly fix the master's
 * heaviest fractional pattern (its column at 1; its stop and its fruits in no other column)
 * and re-solve by column generation, until the master point is a plan or the dive's bound
 * reaches the incumbent. The dive's nodes are never queued: they take no part in the proof. */
static hv_status_t column_dive(bp_t *b, int32_t from)
{
    int inexact = b->inexact; /* a dive node closed as doubtful says nothing about the tree */
    double t0 = hv_milp_now_s();
    int32_t k = from;
    hv_status_t st = HV_OK;
    for (;;) {
        int32_t jbest = -1;
        double xbest = LAMBDA_EPS;
        for (size_t j = 0; j < b->n_pat; ++j) {
            double v = glp_get_col_prim(b->lp, b->pat[j].col);
            if (v > xbest && v < 1.0 - LAMBDA_EPS) {
                xbest = v;
                jbest = (int32_t)j;
            }
        }
        if (jbest < 0) {
            break;
        }
        k = node_new(b, k, KIND_PATTERN, 0, b->pat[jbest].stop, b->pat[jbest].stop, jbest,
                     b->nodes[k].lb_ms);
        if (k < 0) {
            return HV_ERR_PLAN_NOMEM;
        }
        node_end_t end;
        split_t sp;
        if ((st = node_process(b, k, &end, &sp)) != HV_OK || end != NODE_BRANCH) {
            break;
        }
    }
    b->inexact = inexact;
    b->t_dive += hv_milp_now_s() - t0;
    b->dives++;
    return st;
}

/* Row windows of the incumbent re-planned exactly (milp_window.h), for up to WINDOW_SHARE of
 * the time left; a better plan becomes the incumbent. */
static hv_status_t window_reopt(bp_t *b)
{
    double t0 = hv_milp_now_s();
    hv_assignment_t a;
    if (hv_assignment_alloc(&a, b->nf) != HV_OK) {
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(a.fruit_stop, b->best, b->nf * sizeof *b->best);
    double t = b->ub_ms / 1000.0;
    hv_window_stats_t ws;
    hv_status_t st = hv_window_improve(b->inst, b->opt, (unsigned)b->opt->window_width,
                                       WINDOW_LIMIT_S, t0 + WINDOW_SHARE * (b->t_deadline - t0),
                                       &a, &t, &ws, NULL, NULL, NULL);
    if (st == HV_OK) {
        st = offer_plan(b, &a, t);
    }
    hv_assignment_free(&a);
    b->t_window += hv_milp_now_s() - t0;
    b->windows += ws.windows;
    b->windows_better += ws.improved;
    return st;
}

/* ---- the search --------------------------------------------------------------------------- */

/* Node k ended in NODE_BRANCH at `sp`: its two children are made and queued, except the one
 * a dive goes on with (*dive, when `diving`; else *dive = -1). */
static hv_status_t branch(bp_t *b, int32_t k, const split_t *sp, int diving, int32_t *dive)
{
    uint32_t f = sp->fruit;
    double lb = b->nodes[k].lb_ms;
    int32_t c1, c2;
    if (sp->kind == KIND_FRUIT) {
        c1 = node_new(b, k, KIND_FRUIT, f, b->lo[f], sp->stop, 0, lb);
        c2 = node_new(b, k, KIND_FRUIT, f, sp->stop + 1, b->hi[f], 1, lb); /* rhs: up */
        if (c1 >= 0 && c2 >= 0) {
            b->nodes[c1].frac = sp->mass_hi;
            b->nodes[c2].frac = sp->mass_lo;
        }
    } else {
        c1 = node_new(b, k, KIND_COUNT_LE, 0, sp->lo, sp->hi, sp->rhs, lb);
        c2 = node_new(b, k, KIND_COUNT_GE, 0, sp->lo, sp->hi, sp->rhs + 1, lb);
        if (c1 >= 0 && c2 >= 0) {
            b->nodes[c1].frac = sp->mass_lo; /* the count's distance each child forbids */
            b->nodes[c2].frac = sp->mass_hi;
        }
        b->iv_branches += sp->lo > 0 || sp->hi + 1 < b->ns;
    }
    if (c1 < 0 || c2 < 0) {
        return HV_ERR_PLAN_NOMEM;
    }
    b->nodes[c1].basis = b->nodes[c2].basis = basis_save(b);
    *dive = diving ? (sp->up ? c2 : c1) : -1;
    if ((*dive != c1 && !heap_push(b, c1)) || (*dive != c2 && !heap_push(b, c2))) {
        return HV_ERR_PLAN_NOMEM;
    }
    return HV_OK;
}

/* This search's index among the tree workers (milp_share.h): 0 the main one, 1 the second. */
static size_t worker_id(const bp_t *b)
{
    return b->is_worker ? 1u : 0u;
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

static int warm_put(hv_share_node_t *m, const void *p, size_t len)
{
    if (!hv_grow((void **)&m->warm, &m->warm_cap, m->warm_len + len, 1)) {
        return 0;
    }
    memcpy(m->warm + m->warm_len, p, len);
    m->warm_len += len;
    return 1;
}

/* Basis bi (b->bases) as a warm start into m->warm (none when bi < 0). Returns 1, or 0
 * when out of memory. */
static int warm_pack(bp_t *b, int32_t bi, hv_share_node_t *m)
{
    m->warm_len = 0;
    if (bi < 0) {
        return 1;
    }
    const basis_t *s = &b->bases[bi];
    size_t nr = (size_t)s->n_rows, nc = (size_t)s->n_cols;
    if (!hv_grow((void **)&b->col_pat, &b->col_pat_cap, nr + nc + 1, sizeof *b->col_pat)) {
        return 0;
    }
    uint32_t *pat_of = b->col_pat, *crow_of = b->col_pat + nc + 1; /* by column / row */
    for (size_t j = 0; j <= nc; ++j) {
        pat_of[j] = UINT32_MAX;
    }
    for (size_t i = 0; i < nr; ++i) {
        crow_of[i] = UINT32_MAX;
    }
    for (size_t k = 0; k < b->n_pat; ++k) {
        if ((size_t)b->pat[k].col <= nc) {
            pat_of[b->pat[k].col] = (uint32_t)k;
        }
    }
    for (size_t r = 0; r < b->n_crow; ++r) {
        if ((size_t)b->crow[r].row <= nr) {
            crow_of[b->crow[r].row - 1] = (uint32_t)r;
        }
    }
    warm_head_t h = {0, 0, 0, 0, (uint32_t)s->n_pi, s->lag};
    int ok = warm_put(m, &h, sizeof h);
    for (size_t i = 0; ok && i < nr; ++i) {
        if (crow_of[i] == UINT32_MAX && s->stat[i] != GLP_BS) {
            warm_item_t it = {(int32_t)i + 1, s->stat[i]};
            ok = warm_put(m, &it, sizeof it);
            h.n_rows++;
        }
    }
    for (size_t i = 0; ok && i < nr; ++i) {
        if (crow_of[i] != UINT32_MAX) {
            const count_row_t *c = &b->crow[crow_of[i]];
            warm_crow_t it = {c->lo, c->hi, s->stat[i],
                              (size_t)c->art <= nc ? s->stat[nr + (size_t)c->art - 1] : GLP_NL,
                              crow_of[i] < s->n_sg ? s->sg[crow_of[i]] : 0.0};
            ok = warm_put(m, &it, sizeof it);
            h.n_crow++;
        }
    }
    for (size_t j = 1; ok && j <= (size_t)b->n_art && j <= nc; ++j) {
        if (s->stat[nr + j - 1] != GLP_NL) {
            warm_item_t it = {(int32_t)j, s->stat[nr + j - 1]};
            ok = warm_put(m, &it, sizeof it);
            h.n_art++;
        }
    }
    for (size_t j = 1; ok && j <= nc; ++j) {
        if (pat_of[j] != UINT32_MAX && s->stat[nr + j - 1] == GLP_BS) {
            const pattern_t *pt = &b->pat[pat_of[j]];
            warm_pat_t it = {pt->stop, pt->n};
            ok = warm_put(m, &it, sizeof it) &&
                 warm_put(m, b->pf + pt->first, pt->n * sizeof *b->pf);
            h.n_basic++;
        }
    }
    ok = ok && warm_put(m, s->pi, s->n_pi * sizeof *s->pi);
    if (ok) {
        memcpy(m->warm, &h, sizeof h);
    }
    return ok;
}

/* Reads len bytes at *at of warm start m into p: 1, or 0 past its end. */
static int warm_get(const hv_share_node_t *m, size_t *at, void *p, size_t len)
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
static int warm_patterns(bp_t *b, const hv_share_node_t *m, size_t *at, int32_t *pat, uint32_t n)
{
    for (uint32_t q = 0; q < n; ++q) {
        warm_pat_t wp;
        if (!warm_get(m, at, &wp, sizeof wp) || wp.n > b->nf || wp.stop >= b->ns ||
            !warm_get(m, at, b->sel, wp.n * sizeof *b->sel)) {
            return 0;
        }
        double w[2];
        for (uint32_t i = 0; i < wp.n; ++i) {
            if (b->sel[i] >= b->nf) {
                return 0;
            }
        }
        if (!pattern_times(b, wp.stop, b->sel, wp.n, w)) {
            return 0;
        }
        if (pattern_add(b, wp.stop, b->sel, wp.n, b->tau_ms + fmax(w[0], w[1])) < 0) {
            return -1;
        }
        pat[q] = pattern_find(b, wp.stop, b->sel, wp.n); /* pattern_add sorted b->sel */
    }
    return 1;
}

/* The statuses of warm start m (header h; its count rows and basic patterns pat[] exist
 * here) over this worker's master of nr rows and nc columns, rows first, into st, and its
 * count rows' duals into sg (by count row here). Returns 1 when they make a basis here. */
static int warm_statuses(bp_t *b, const hv_share_node_t *m, const warm_head_t *h,
                         const int32_t *pat, int nr, int nc, unsigned char *st, double *sg)
{
    memset(st, GLP_BS, (size_t)nr); /* rows not named: basic; columns: at 0 */
    memset(st + nr, GLP_NL, (size_t)nc);
    size_t at = sizeof *h;
    warm_item_t it;
    for (uint32_t q = 0; q < h->n_rows; ++q) {
        warm_get(m, &at, &it, sizeof it);
        if (it.index < 1 || it.index > nr) {
            return 0;
        }
        st[it.index - 1] = (unsigned char)it.stat;
    }
    for (uint32_t q = 0; q < h->n_crow; ++q) {
        warm_crow_t wc;
        warm_get(m, &at, &wc, sizeof wc);
        const count_row_t *c = crow_get(b, wc.lo, wc.hi); /* made by warm_unpack: found */
        st[c->row - 1] = (unsigned char)wc.stat;
        st[nr + c->art - 1] = (unsigned char)wc.art_stat;
        sg[c - b->crow] = wc.sg;
    }
    for (uint32_t q = 0; q < h->n_art; ++q) {
        warm_get(m, &at, &it, sizeof it);
        if (it.index < 1 || it.index > b->n_art) {
            return 0;
        }
        st[nr + it.index - 1] = (unsigned char)it.stat;
    }
    for (uint32_t q = 0; q < h->n_basic; ++q) {
        st[nr + b->pat[pat[q]].col - 1] = GLP_BS;
    }
    int n_basic = 0;
    for (int i = 0; i < nr + nc; ++i) {
        n_basic += st[i] == GLP_BS;
    }
    return n_basic == nr;
}

/* The warm start of m as a basis of this worker's master in b->bases (the count rows and
 * patterns it names are made here when missing): its index in *bi, -1 when m has none, is
 * malformed, or does not make a basis here (the node then starts from the current one).
 * Returns HV_OK or HV_ERR_PLAN_NOMEM. */
static hv_status_t warm_unpack(bp_t *b, const hv_share_node_t *m, int32_t *bi)
{
    *bi = -1;
    warm_head_t h;
    size_t at = 0;
    if (!warm_get(m, &at, &h, sizeof h)) {
        return HV_OK;
    }
    size_t pat_at = at + (h.n_rows + h.n_art) * sizeof(warm_item_t) +
                    h.n_crow * sizeof(warm_crow_t);
    size_t pi_len = h.n_pi * sizeof(double);
    if (pat_at + pi_len > m->warm_len || h.n_basic > m->warm_len) {
        return HV_OK;
    }
    at += h.n_rows * sizeof(warm_item_t);
    for (uint32_t q = 0; q < h.n_crow; ++q) {
        warm_crow_t wc;
        warm_get(m, &at, &wc, sizeof wc);
        if (crow_get(b, wc.lo, wc.hi) == NULL) {
            return HV_ERR_PLAN_NOMEM;
        }
    }
    int32_t *pat = malloc(((size_t)h.n_basic + 1) * sizeof *pat);
    double *duals = NULL;
    unsigned char *st = NULL;
    int ok = pat != NULL ? warm_patterns(b, m, &(size_t){pat_at}, pat, h.n_basic) : -1;
    int nr = glp_get_num_rows(b->lp), nc = glp_get_num_cols(b->lp);
    size_t npi = n_pi(b);
    if (ok == 1) {
        st = malloc((size_t)nr + (size_t)nc);
        duals = calloc(npi + b->n_crow + 1, sizeof *duals);
        ok = st != NULL && duals != NULL ? 1 : -1;
    }
    if (ok == 1 && warm_statuses(b, m, &h, pat, nr, nc, st, duals + npi)) {
        int centre = h.n_pi == npi; /* the same cuts: always, as the root made them all */
        if (centre) {
            memcpy(duals, m->warm + m->warm_len - pi_len, pi_len);
        }
        *bi = basis_keep(b, nr, nc, st, duals, npi, b->n_crow, centre ? h.lag : -INFINITY);
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
static hv_status_t give_if_hungry(bp_t *b)
{
    while (b->share != NULL && b->heap_len > 0 && hv_share_hungry(b->share, worker_id(b))) {
        int32_t k = heap_pop(b);
        if (prunable(b, b->nodes[k].lb_ms)) {
            continue;
        }
        hv_share_node_t *m = &b->msg;
        size_t n = 0;
        for (int32_t q = k; b->nodes[q].parent >= 0; q = b->nodes[q].parent) {
            n++;
        }
        if (!hv_grow((void **)&m->path, &m->cap, n + 1, sizeof *m->path) ||
            !warm_pack(b, b->opt->warm_transfer ? b->nodes[k].basis : -1, m)) {
            return HV_ERR_PLAN_NOMEM;
        }
        m->n = n;
        m->lb_ms = b->nodes[k].lb_ms;
        for (int32_t q = k; b->nodes[q].parent >= 0; q = b->nodes[q].parent) {
            const node_t *d = &b->nodes[q];
            m->path[--n] = (hv_share_step_t){(int)d->kind, d->fruit, d->lo, d->hi, d->rhs};
        }
        b->given++;
        return hv_share_give(b->share, m);
    }
    return HV_OK;
}

/* The node the other worker gave (in b->msg) made a node here, into *k, with its warm
 * start when that makes a basis here (no pseudocost learning: its parent's bound is not
 * known here). Returns 1, or -1 when out of memory. */
static int import_shared(bp_t *b, int32_t *k)
{
    const hv_share_node_t *m = &b->msg;
    int32_t q = 0;
    for (size_t i = 0; i < m->n && q >= 0; ++i) {
        const hv_share_step_t *st = &m->path[i];
        q = node_new(b, q, (node_kind_t)st->kind, st->fruit, st->lo, st->hi, st->rhs,
                     m->lb_ms);
    }
    int32_t bi = -1;
    if (q < 0 || warm_unpack(b, m, &bi) != HV_OK) {
        return -1;
    }
    b->nodes[q].basis = bi;
    b->taken++;
    b->taken_warm += bi >= 0;
    *k = q;
    return 1;
}

/* This worker holds open nodes whose best bound is well above the other worker's: it asks
 * for the other's best (which comes at the other's next node) and queues what came of an
 * earlier ask, so that both search near the least bound. Returns 0, or -1 when out of
 * memory. */
static int balance_shared(bp_t *b)
{
    double lb = b->heap_len > 0 ? b->nodes[b->heap[0]].lb_ms : INFINITY;
    double margin = fmax(1.0, BALANCE_SHARE * (b->ub_ms - lb));
    if (!hv_share_balance(b->share, worker_id(b), lb, margin)) {
        return 0;
    }
    int32_t k;
    int r = hv_share_poll(b->share, worker_id(b), &b->msg);
    if (r == 0) {
        return 0;
    }
    if (r < 0 || import_shared(b, &k) < 0 || !heap_push(b, k)) {
        return -1;
    }
    return 0;
}

/* This worker has no open node: one from the other worker, made a node here (*k). Returns
 * 1 with a node, 0 when the search is over or time is up, -1 when out of memory. */
static int next_shared(bp_t *b, int32_t *k)
{
    for (;;) {
        if (must_stop(b)) {
            return 0;
        }
        int r = hv_share_wait(b->share, worker_id(b), &b->msg);
        if (r == 0 || r == -2) {
            return r == 0 ? 0 : -1;
        }
        if (r == 1) {
            return import_shared(b, k);
        }
    }
}

static hv_status_t tree_search(bp_t *b, double *root_lb, long *nodes_done);

/* The least bound of the nodes still queued at the end that the incumbent does not prune
 * (INFINITY none), their number in *n: the others (the limit came before they were popped)
 * cannot hold a better plan, as during the search. */
static double open_bound(const bp_t *b, size_t *n)
{
    double lb = INFINITY;
    *n = 0;
    for (size_t i = 0; i < b->heap_len; ++i) {
        if (!prunable(b, b->nodes[b->heap[i]].lb_ms)) {
            lb = fmin(lb, b->nodes[b->heap[i]].lb_ms);
            ++*n;
        }
    }
    return lb;
}

/* w (from bp_init) becomes a copy of b's state after the root: its master (same rows and
 * columns in the same order), pattern pool, cuts, count rows, fixed pairs and incumbent
 * (the pseudocosts come from the shared pool). Returns HV_OK or an error. */
static hv_status_t bp_clone(bp_t *w, const bp_t *b)
{
    size_t nf = b->nf, np = b->inst->n_pairs;
    glp_erase_prob(w->lp);
    glp_copy_prob(w->lp, b->lp, GLP_OFF);
    glp_set_obj_dir(w->lp, GLP_MIN);
    if (!hv_grow((void **)&w->pat, &w->pat_cap, b->n_pat + 1, sizeof *w->pat) ||
        !hv_grow((void **)&w->pf, &w->pf_cap, b->pf_len + 1, sizeof *w->pf) ||
        !hv_grow((void **)&w->pat_open, &w->open_cap, b->n_pat + 1, 1) ||
        !hv_grow((void **)&w->pat_dead, &w->dead_cap, b->n_pat + 1, 1) ||
        !hv_grow((void **)&w->crow, &w->crow_cap, b->n_crow + 1, sizeof *w->crow) ||
        !iv_reserve(w, b->iv_cap)) {
        return HV_ERR_PLAN_NOMEM;
    }
    w->n_pat = b->n_pat;
    w->pf_len = b->pf_len;
    memcpy(w->pat, b->pat, b->n_pat * sizeof *w->pat);
    memcpy(w->pf, b->pf, b->pf_len * sizeof *w->pf);
    memcpy(w->pat_open, b->pat_open, b->n_pat);
    memcpy(w->pat_dead, b->pat_dead, b->n_pat);
    w->n_crow = b->n_crow;
    if (b->n_crow > 0) { /* b->crow is NULL until the first count row */
        memcpy(w->crow, b->crow, b->n_crow * sizeof *w->crow);
    }
    if (!hash_rebuild(w, b->hcap)) {
        return HV_ERR_PLAN_NOMEM;
    }
    hv_status_t st = hv_src_copy(&w->src, &b->src);
    if (st != HV_OK) {
        return st;
    }
    memcpy(w->src_row, b->src_row, SR_MAX * sizeof *w->src_row);
    w->sr_rounds = b->sr_rounds;
    w->sr_lb0 = b->sr_lb0;
    memcpy(w->pair_dead, b->pair_dead, np);
    memcpy(w->root_pi, b->root_pi, n_pi(b) * sizeof *w->root_pi);
    w->root_lag = b->root_lag;
    w->fixed_ub = b->fixed_ub;
    memcpy(w->best, b->best, nf * sizeof *w->best);
    hv_share_pc_copy(&w->ivpc, &b->ivpc, b->ns * b->ivpc_w); /* from here each its own */
    w->ub_ms = b->ub_ms;
    memcpy(w->warm_pair, b->warm_pair, np * sizeof *w->warm_pair);
    memcpy(w->warm_n, b->warm_n, b->ns * sizeof *w->warm_n);
    w->t_deadline = w->pricer.t_deadline_s = b->t_deadline;
    w->t_start = w->t_print = b->t_start;
    w->is_worker = 1;
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
    long nodes, iv_branches, tailed, taken_warm;
    rins_stats_t rins;
    int inexact;
    double open_lb; /* of its nodes still open (INFINITY none), n_open of them */
    size_t n_open;
};

static void *worker_main(void *arg)
{
    worker_t *wk = arg;
    bp_t w;
    hv_status_t st = bp_init(&w, wk->main->inst, wk->main->opt);
    if (st == HV_OK) {
        st = bp_clone(&w, wk->main);
    }
    if (st == HV_OK && node_new(&w, -1, KIND_ROOT, 0, 0, 0, 0, wk->main->nodes[0].lb_ms) != 0) {
        st = HV_ERR_PLAN_NOMEM;
    }
    w.share = wk->share;
    pthread_mutex_lock(&wk->mu);
    wk->st_copy = st;
    wk->copied = 1;
    pthread_cond_signal(&wk->cv);
    pthread_mutex_unlock(&wk->mu);
    if (st == HV_OK) {
        double root_lb; /* the main search's */
        st = tree_search(&w, &root_lb, &w.nodes_done);
        if (st != HV_OK) {
            hv_share_fail(wk->share);
        }
        double ub;
        if (hv_share_take(wk->share, w.ub_ms, w.best, &ub)) {
            w.ub_ms = ub; /* prune what it leaves open by the best plan known */
        }
        wk->open_lb = open_bound(&w, &wk->n_open);
        wk->st = st;
        wk->nodes = w.nodes_done;
        wk->iv_branches = w.iv_branches;
        wk->tailed = w.tailed;
        wk->rins = w.rins;
        wk->taken_warm = w.taken_warm;
        wk->inexact = w.inexact;
    }
    bp_free(&w);
    glp_free_env(); /* this thread's GLPK environment */
    return NULL;
}

static void worker_free(worker_t *wk)
{
    pthread_cond_destroy(&wk->cv);
    pthread_mutex_destroy(&wk->mu);
    hv_share_destroy(wk->share);
    free(wk);
}

/* The second tree worker starts from a copy of the main search after its root. When its
 * thread cannot start the main search goes on alone. */
static hv_status_t worker_start(bp_t *b)
{
    worker_t *wk = calloc(1, sizeof *wk);
    if (wk == NULL || hv_share_create(2, b->nf, &wk->share) != HV_OK) {
        free(wk);
        return HV_ERR_PLAN_NOMEM;
    }
    wk->main = b;
    pthread_mutex_init(&wk->mu, NULL);
    pthread_cond_init(&wk->cv, NULL);
    hv_share_offer(wk->share, b->best, b->ub_ms);
    hv_share_pc_set(wk->share, &b->pc);
    if (pthread_create(&wk->thread, NULL, worker_main, wk) != 0) {
        if (b->opt->verbose >= 1) {
            fprintf(stderr, "price: the second tree worker did not start: one worker\n");
        }
        worker_free(wk);
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
        worker_free(wk);
        return st;
    }
    b->share = wk->share;
    b->worker = wk;
    return HV_OK;
}

/* Stop (after an error: `failed`) and join the second worker. Its nodes, incumbent and
 * open bound come back: *open_lb the least bound of the nodes it or the queue still hold
 * (INFINITY none), *n_open their number. Returns the worker's status. */
static hv_status_t worker_join(bp_t *b, int failed, double *open_lb, size_t *n_open)
{
    worker_t *wk = b->worker;
    if (failed) {
        hv_share_fail(wk->share);
    }
    pthread_join(wk->thread, NULL);
    double ub;
    if (hv_share_take(wk->share, b->ub_ms, b->best, &ub)) {
        b->ub_ms = ub;
    }
    *open_lb = fmin(hv_share_open_lb(wk->share, n_open), wk->open_lb);
    *n_open += wk->n_open;
    if (prunable(b, *open_lb)) {
        *n_open = 0; /* every node left open is pruned by the final incumbent */
    }
    b->inexact |= wk->inexact;
    b->nodes_done = wk->nodes;
    b->iv_branches += wk->iv_branches;
    b->tailed += wk->tailed;
    b->rins.calls += wk->rins.calls;
    b->rins.better += wk->rins.better;
    b->rins.freed += wk->rins.freed;
    b->rins.t_s += wk->rins.t_s;
    b->taken_warm += wk->taken_warm;
    hv_status_t st = wk->st;
    b->share = NULL;
    b->worker = NULL;
    worker_free(wk);
    return st;
}

/* The helper's last plan (with `take`), then stop it. */
static hv_status_t helper_finish(bp_t *b, int take)
{
    hv_status_t sth = take ? take_plan(b, 1) : HV_OK;
    hv_window_stats_t ws;
    double tj = hv_milp_now_s();
    hv_status_t stj = hv_helper_stop(b->helper, &ws);
    if (b->opt->verbose >= 1) {
        fprintf(stderr,
                "price: helper thread joined after %.2f s in %.3f s: %ld windows (%ld better, "
                "%ld proven), %ld repeated windows skipped\n",
                tj - b->t_start, hv_milp_now_s() - tj, ws.windows, ws.improved, ws.proven,
                ws.repeats);
    }
    b->helper = NULL;
    b->windows += ws.windows;
    b->windows_better += ws.improved;
    return sth != HV_OK ? sth : stj;
}

static hv_status_t search(bp_t *b, double *root_lb, long *nodes_done)
{
    /* a centre set before the root is a proven bound already */
    int32_t root = node_new(b, -1, KIND_ROOT, 0, 0, 0, 0,
                            b->root_centre ? b->center_lag : -INFINITY);
    if (root != 0 || !heap_push(b, root)) { /* node 0: the root of shared paths too */
        return HV_ERR_PLAN_NOMEM;
    }
    *root_lb = -INFINITY;
    *nodes_done = 0;
    if (b->opt->window_width > 0 && b->opt->helper_thread && isfinite(b->ub_ms)) {
        /* the second core polishes the plan and re-plans its windows during the root */
        hv_assignment_t a = {b->nf, b->best};
        hv_status_t st = hv_helper_start(b->inst, b->opt, &a, b->ub_ms / 1000.0, b->t_deadline,
                                         polish_kicks(b), &b->helper);
        if (st != HV_OK) {
            return st;
        }
    }
    return tree_search(b, root_lb, nodes_done);
}

/* Best bound first, interrupted by dives: from the root and then every DIVE_EVERY nodes,
 * follow the child holding more of the master's mass until the dive is pruned or ends in
 * a plan. Dives find plans (the bound rarely closes before the incumbent is optimal); best
 * bound first proves them. With a second worker, a worker out of nodes takes one of the
 * other's; the second worker does not dive, and the root (node 0) is the main search's. */
static hv_status_t tree_search(bp_t *b, double *root_lb, long *nodes_done)
{
    const int32_t root = b->is_worker ? -1 : 0;
    int32_t dive = -1;
    int diving = !b->is_worker;
    long since_dive = 0;
    for (;;) {
        int32_t k = dive;
        if (b->share != NULL && b->opt->balance_workers && balance_shared(b) < 0) {
            return HV_ERR_PLAN_NOMEM;
        }
        if (region_due(b, *nodes_done)) {
            hv_status_t st = region_try(b);
            if (st != HV_OK) {
                return st;
            }
        }
        if (k >= 0) {
            dive = -1;
        } else if (b->heap_len > 0) {
            k = heap_pop(b);
        } else if (b->share == NULL) {
            break;
        } else {
            int r = next_shared(b, &k);
            if (r <= 0) {
                return r == 0 ? HV_OK : HV_ERR_PLAN_NOMEM;
            }
        }
        if (prunable(b, b->nodes[k].lb_ms)) {
            if (k == root) {
                *root_lb = b->nodes[k].lb_ms; /* closed by the ascent's bound, unsolved */
            }
            diving = 0;
            continue;
        }
        node_end_t end;
        split_t sp = {KIND_FRUIT, 0, 0, 0, 0, 0, 0.0, 0, 0.0, 0.0};
        hv_status_t st = node_process(b, k, &end, &sp);
        if (st != HV_OK) {
            return st;
        }
        ++*nodes_done;
        if (k == root) {
            *root_lb = b->nodes[k].lb_ms;
        }
        if (end == NODE_TIMEOUT) {
            return heap_push(b, k) ? HV_OK : HV_ERR_PLAN_NOMEM; /* still open */
        }
        pseudocost_record(b, k);
        if (end != NODE_BRANCH) {
            diving = 0;
            continue;
        }
        if (!diving && !b->is_worker && ++since_dive >= DIVE_EVERY) {
            diving = 1;
            since_dive = 0;
        }
        if ((st = branch(b, k, &sp, diving, &dive)) != HV_OK) {
            return st;
        }
        double lb = b->nodes[k].lb_ms;
        /* the root's plan may be far from optimal: a column-fixing dive finds better
         * ones than the branch dive (SOLVER.md) */
        if (k == root &&
            (b->opt->column_dive == 2 ||
             (b->opt->column_dive == 1 && b->ub_ms - lb > PRIMAL_ROOT_GAP * b->ub_ms &&
              b->inst->n_pairs < CENTRE_MIN_PAIRS)) &&
            (st = column_dive(b, root)) != HV_OK) {
            return st;
        }
        if (k == root && b->opt->window_width > 0 && b->ub_ms - lb > PRIMAL_ROOT_GAP * b->ub_ms &&
            b->helper == NULL) {
            if (b->opt->helper_thread) {
                hv_assignment_t a = {b->nf, b->best};
                st = hv_helper_start(b->inst, b->opt, &a, b->ub_ms / 1000.0, b->t_deadline,
                                     0, &b->helper); /* this thread has polished */
            } else {
                st = window_reopt(b);
            }
            if (st != HV_OK) {
                return st;
            }
        }
        /* The second core searches the tree too once the incumbent is near the bound: the
         * helper then stops (it rarely improves such a plan, and more nodes prove it). */
        if (b->opt->tree_threads > 1 && !b->is_worker && b->worker == NULL && b->heap_len > 0 &&
            b->ub_ms - b->nodes[b->heap[0]].lb_ms <= WORKER_GAP * b->ub_ms) {
            if ((b->helper != NULL && (st = helper_finish(b, 1)) != HV_OK) ||
                (st = worker_start(b)) != HV_OK) {
                return st;
            }
        }
        if ((st = give_if_hungry(b)) != HV_OK) {
            return st;
        }
    }
    return HV_OK;
}

/* bp_init, and the solve's clock started towards t_deadline_s. */
static hv_status_t bp_start(bp_t *b, const hv_instance_t *inst, const hv_milp_options_t *opt,
                            double t_deadline_s)
{
    hv_status_t st = bp_init(b, inst, opt);
    b->t_deadline = b->pricer.t_deadline_s = t_deadline_s;
    b->t_start = b->t_print = hv_milp_now_s();
    return st;
}

hv_status_t hv_price_solve(const hv_instance_t *inst, const hv_milp_options_t *opt,
                           const hv_assignment_t *inc, double inc_t, double t_deadline_s,
                           hv_assignment_t *out, hv_milp_result_t *res)
{
    bp_t b;
    hv_status_t st = bp_start(&b, inst, opt, t_deadline_s);
    if (st == HV_OK && inc != NULL) {
        memcpy(b.best, inc->fruit_stop, b.nf * sizeof *b.best);
        b.ub_ms = 1000.0 * inc_t;
        if (add_assignment_columns(&b, inc->fruit_stop) < 0) {
            st = HV_ERR_PLAN_NOMEM;
        }
    }
    if (st == HV_OK && add_start_columns(&b) < 0) {
        st = HV_ERR_PLAN_NOMEM;
    }
    double root_lb = -INFINITY;
    long nodes = 0;
    if (st == HV_OK && opt->ascent_steps > 0) {
        st = ascent_centre(&b, opt->ascent_steps);
    } else if (st == HV_OK && inst->n_pairs >= CENTRE_MIN_PAIRS) {
        compact_centre(&b, 0.25 * (t_deadline_s - hv_milp_now_s()));
    }
    if (st == HV_OK) {
        st = search(&b, &root_lb, &nodes);
    }
    double open_lb = INFINITY; /* of the nodes the second worker left open */
    size_t n_open = 0;
    if (b.worker != NULL) {
        hv_status_t stw = worker_join(&b, st != HV_OK, &open_lb, &n_open);
        st = st != HV_OK ? st : stw;
        nodes += b.nodes_done;
    }
    if (b.helper != NULL) { /* also after an error */
        hv_status_t sth = helper_finish(&b, st == HV_OK);
        st = st != HV_OK ? st : sth;
    }
    if (st == HV_OK) {
        size_t n_main;
        double lb = fmin(fmin(b.ub_ms, open_lb), open_bound(&b, &n_main));
        progress(&b, lb, 1);
        if (opt->verbose >= 1) {
            fprintf(stderr,
                    "price: %ld LP rounds in %.2f s (%d iterations, %ld restarts, %ld stalls), "
                    "pricing %.2f s (%llu stops, %.1f points each), heuristic %ld runs "
                    "(%ld better) in %.2f s, %ld column dives in %.2f s, %ld windows (%ld better) "
                    "in %.2f s, %ld plans from the helper thread, %ld of %zu pairs fixed in "
                    "%.2f s, "
                    "%zu subset-row cuts in %d rounds (%ld dropped; %.1f with a negative dual "
                    "per priced stop, %ld stops over 64), %ld interval count branches, %ld "
                    "nodes branched tailing off, second tree worker %ld nodes (%ld "
                    "nodes passed between the workers, %ld with a warm start)\n",
                    b.cg_iters, b.t_lp, glp_get_it_cnt(b.lp), b.lp_restarts, b.lp_stalls,
                    b.t_price, b.pricer.calls,
                    (double)b.pricer.points / (double)(b.pricer.calls ? b.pricer.calls : 1),
                    b.heur_runs, b.heur_wins, b.t_heur, b.dives, b.t_dive, b.windows,
                    b.windows_better, b.t_window, b.helper_plans, b.pairs_fixed,
                    inst->n_pairs, b.t_fix, b.src.n, b.sr_rounds, b.sr_dropped,
                    (double)b.src_bits / (double)(b.src_stops ? b.src_stops : 1),
                    b.src_overflow, b.iv_branches, b.tailed, b.nodes_done,
                    b.given + b.taken, b.taken_warm);
        }
        if (opt->verbose >= 1) {
            fprintf(stderr, "price: %ld relaxation-induced neighbourhoods (%ld better, %.1f "
                    "fruits freed each) in %.2f s; %ld regional bounds (%ld proofs, %ld nodes) "
                    "in %.2f s\n", b.rins.calls, b.rins.better,
                    (double)b.rins.freed / (double)(b.rins.calls ? b.rins.calls : 1),
                    b.rins.t_s, b.region_tries, b.region_proofs, b.region_nodes, b.t_region);
        }
        res->nodes = nodes;
        res->worker_nodes = b.nodes_done;
        res->columns = (long)b.n_pat;
        res->interval_branches = b.iv_branches;
        res->tailed_nodes = b.tailed;
        res->passed_nodes = b.given + b.taken;
        res->passed_warm = b.taken_warm;
        res->cuts = (long)b.src.n;
        res->root_bound_s = root_lb / 1000.0;
        if (!isfinite(b.ub_ms)) {
            res->status = b.heap_len == 0 ? HV_SOLVE_INFEASIBLE : HV_SOLVE_NO_SOLUTION;
        } else {
            memcpy(out->fruit_stop, b.best, b.nf * sizeof *b.best);
            res->objective_s = b.ub_ms / 1000.0;
            res->bound_s = fmin(lb, b.ub_ms) / 1000.0;
            res->gap = (res->objective_s - res->bound_s) / fmax(res->objective_s, DBL_EPSILON);
            res->status = n_main == 0 && n_open == 0 && !b.inexact ? HV_SOLVE_OPTIMAL
                                                                   : HV_SOLVE_FEASIBLE;
            if (res->status == HV_SOLVE_OPTIMAL) {
                res->bound_s = res->objective_s; /* every open node was pruned */
                res->gap = 0.0;
            }
        }
    }
    bp_free(&b);
    return st;
}

hv_status_t hv_price_bound(const hv_instance_t *inst, const hv_milp_options_t *opt,
                           const double *skip_ms, double cutoff_ms, double t_deadline_s,
                           uint32_t *plan, hv_price_bound_result_t *res)
{
    hv_milp_options_t o; /* what the virtual stops and the cutoff allow */
    hv_milp_subsolve_options(opt, t_deadline_s - hv_milp_now_s(), &o);
    o.column_dive = 0;   /* it fixes patterns of b.best, which may not be a plan yet */
    o.rel_gap = 0.0;     /* the cutoff is what may be left */
    o.helper_thread = 0; /* its plans cover every fruit */
    bp_t b;
    hv_status_t st = bp_start(&b, inst, &o, t_deadline_s);
    b.skip_ms = skip_ms;
    b.whole_ms = 0; /* the skip costs are duals, not whole ms */
    b.ub_ms = cutoff_ms; /* no plan yet: b.best is written by a better one only */
    *res = (hv_price_bound_result_t){-INFINITY, -INFINITY, 0, 0, 0};
    if (st == HV_OK && add_start_columns(&b) < 0) {
        st = HV_ERR_PLAN_NOMEM;
    }
    if (st == HV_OK) {
        st = search(&b, &res->root_lb_ms, &res->nodes);
    }
    if (st == HV_OK) {
        size_t n_open;
        res->lb_ms = fmin(b.ub_ms, open_bound(&b, &n_open));
        res->finished = n_open == 0;
        res->has_plan = b.ub_ms < cutoff_ms;
        if (res->has_plan && plan != NULL) {
            memcpy(plan, b.best, b.nf * sizeof *plan);
        }
    }
    bp_free(&b);
    return st;
}
