/* The branch-and-price's private context and its plugin records (planner/src/price/).
 *
 * The context bp_t is one search's state, in parts: the master LP and its column pool
 * (bp_master_t), the tree (bp_tree_t), the subset-row cuts (bp_cuts_t), the incumbent
 * (bp_incumbent_t), the reduced-cost fixing (bp_fixing_t), the regional bound
 * (bp_region_part_t) and counters (bp_stats_t). The core (master.c, pool.c, pricing.c,
 * node.c, tree.c, incumbent.c, fixing.c, centre.c, workers.c) calls the plugins only
 * through their records (bp_plugin_t), which solve.c registers from plugins.c's list, and
 * sub-solves only through the context's callbacks (b->sub, milp_subsolve.h): no file of
 * the core names a plugin, and none names hv_milp_solve. Times are in ms unless a name
 * says otherwise.
 */
#ifndef HV_PRICE_BP_H
#define HV_PRICE_BP_H

#include <glpk.h>
#include <stdint.h>

#include "hv/milp_helper.h"
#include "hv/milp_options.h"
#include "hv/milp_pricing.h"
#include "hv/milp_share.h"
#include "hv/milp_srcuts.h"
#include "hv/milp_subsolve.h"
#include "hv/plan_eval.h"
#include "hv/plan_instance.h"
#include "../milp_tunables.h"

#define BP_MAX_PLUGINS 16

typedef struct pattern {
    uint32_t stop;
    uint32_t first, n; /* fruits bp->pf[first .. first + n), ascending */
    double cost_ms;
    int col;             /* master column */
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
    int art;         /* artificial column: keeps an "at least" row feasible at every node */
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

/* The master LP, its rows and the column (pattern) pool, the duals, the pricing scratch. */
typedef struct bp_master {
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
    unsigned char *pat_open; /* the column is open in the master (2: fixed at 1) */
    size_t open_cap, dead_cap;
    unsigned char *pat_dead; /* uses a pair removed by reduced-cost fixing */
    int32_t *hslot;          /* open-addressing hash of patterns, -1 = empty */
    size_t hcap;
    hv_pricer_t pricer;
    int lp_dual_next; /* rows were added: the next master solve is a dual one */
    hv_price_item_t *itl, *itr;
    uint32_t *sel;
    double *pi_lp, *mu_lp, *sg_lp; /* the master's duals: fruit (+ cut), stop, count rows */
    double *pi_c, *sg_c;           /* the duals of the best bound at this node (centre) */
    double *pi_sep, *sg_sep;       /* the duals priced at */
    double *cover;                 /* per fruit: the patterns of the last pricing holding it */
    double smooth;                 /* this node's smoothing weight (auto_smoothing) */
    size_t sg_cap, sgc_cap, sgs_cap;
    double *sigma_lp;
    double center_lag;
    int root_centre; /* center_lag / pi_c were set before the root: keep them */
    cand_t *cand;    /* per stop */
    uint32_t *cf;
    size_t cf_len, cf_cap;
    size_t *warm_pair; /* per stop (slots at stop_begin[p]): its last best pattern's pairs */
    size_t *warm_n;    /* their number, SIZE_MAX when none yet */
    size_t *pair_at;   /* per fruit: its pair at the stop being priced */
    int *ind;
    double *val;
    size_t iv_cap;  /* entries of ind and val */
    double *stop_v; /* per stop: its term of the Lagrangian bound at the duals last priced */
} bp_master_t;

/* The branch-and-bound tree: nodes, saved bases, the queue, the current node's intervals,
 * pseudocosts, the two tree workers. */
typedef struct bp_tree {
    node_t *nodes;
    size_t n_nodes, nodes_cap;
    basis_t *bases;
    size_t n_bases, bases_cap, bases_bytes;
    int32_t cur_basis; /* what the current node's parent left it, -1 none */
    int32_t *heap;
    size_t heap_len, heap_cap;
    uint32_t *lo, *hi;    /* the current node's stop interval per fruit */
    double *stop_mass;    /* scratch of choose_count: prefix sums of the mass per stop */
    uint32_t *stop_empty; /* ... and the runs of stops without mass (2 ns) */
    int inexact;          /* a numerically doubtful node was closed: do not claim optimality */
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
    hv_share_t *share;     /* NULL while one worker searches */
    struct worker *worker; /* the second worker, NULL none */
    int is_worker;         /* this is the second worker: no progress lines */
    long nodes_done;       /* the second worker's nodes */
    long given, taken;     /* nodes passed to and taken from the other worker (after the
                            * join, the main worker's `given` counts both workers' gives) */
    long taken_warm;       /* of `taken`, those whose warm start made a basis here */
    hv_share_node_t msg;   /* scratch: a node passed between the workers */
    uint32_t *col_pat;     /* scratch (warm_pack): the pattern of each column, the count
                              row of each row */
    size_t col_pat_cap;
} bp_tree_t;

/* The subset-row cuts (milp_srcuts.h), separated at the root only. */
typedef struct bp_cuts {
    hv_src_t src;      /* subset-row cuts: their duals follow the fruits' in every pi */
    int *src_row;      /* per cut: its master row */
    uint32_t *src_hit; /* scratch: the cuts a pattern meets (SR_MAX) */
    int32_t *src_bit;  /* per cut: its bit in the stop being priced, -1 none */
    double pen[64];    /* the penalties of those bits */
    int sr_rounds;     /* separation rounds done at the root */
    int sr_max;        /* ... and to do: opt->sr_cuts, or sr_cuts_large from CENTRE_MIN_PAIRS */
    double sr_lb0;     /* the root's bound before the first cut */
    long src_overflow; /* stops priced with more than 64 cuts (the rest left out) */
    long src_bits, src_stops; /* cut bits given to priced stops, and those stops */
    long sr_dropped;          /* cuts deleted after the root as not worth their cost */
} bp_cuts_t;

/* The best plan and the helper thread that improves it. */
typedef struct bp_incumbent {
    uint32_t *best; /* incumbent assignment */
    double ub_ms;
    hv_helper_t *helper; /* re-plans windows on the second core, NULL when not running */
    long helper_plans;   /* incumbents taken from it */
    int plan_cols_due;   /* the incumbent came from it during the root: its columns wait */
} bp_incumbent_t;

/* Reduced-cost fixing from the root's duals. */
typedef struct bp_fixing {
    unsigned char *pair_dead; /* per pair: cannot be in a plan better than the incumbent */
    double *root_pi;          /* the root's best duals and their Lagrangian bound */
    double root_lag, fixed_ub;
    long pairs_fixed;
} bp_fixing_t;

/* The regional bound's state (plugin region.c). */
typedef struct bp_region_part {
    /* the regional bound (milp_region.h, opt->region_stops): the root's duals before any cut
     * (fruits), their stop terms and Lagrangian bound; the bound it proved, valid at every
     * node; the incumbent it last tried to prove; its sub-solves' tries, nodes and time */
    double *region_pi, *region_v, region_lag0;
    double region_lb, region_tried_ub;
    long region_tries, region_proofs, region_nodes;
    size_t region_s0, region_s1; /* the stretch whose sub-solve last finished */
    int region_stalled;          /* a sub-solve ran out of its time: no more tries */
    double t_region;
} bp_region_part_t;

/* Counters and times (s) for the verbose summary. */
typedef struct bp_stats {
    long cg_iters;
    double t_heur; /* time spent in the rounding heuristic (s) */
    double t_fix;  /* time spent in reduced-cost fixing (s) */
    double t_dive; /* time spent in column-fixing dives (s) */
    long dives;
    double t_window; /* time spent re-planning row windows (s) */
    long windows, windows_better;
    rins_stats_t rins;    /* the relaxation-induced neighbourhoods (both workers' at the end) */
    int rins_wait;        /* nodes solved since the last neighbourhoods */
    double t_lp, t_price; /* time in the master LP and in pricing (s) */
    long lp_restarts;     /* master bases rebuilt after a singular warm start */
    long lp_stalls;       /* primal simplex calls stopped as stalled, finished by the dual */
    long heur_runs, heur_wins;
    long iv_branches; /* branches on an interval's stop count (interval_branching) */
    long tailed;      /* nodes branched on before their column generation converged */
} bp_stats_t;

struct bp_plugin;

typedef struct bp {
    const hv_instance_t *inst;
    const hv_milp_options_t *opt;
    size_t nf, ns;
    double tau_ms, travel_ms;
    int whole_ms; /* every cost is whole ms: a better plan is better by >= 1 ms */
    double t_deadline;
    double t_start, t_print;
    /* hv_price_bound: per fruit the cost of leaving it uncovered (INFINITY: it must be
     * covered), NULL in a plain solve. A fruit that may be left out has the virtual stop
     * ns at the top of its interval, there its artificial column costs skip_ms, and a
     * branch on its stop can forbid that as it forbids real stops. */
    const double *skip_ms;
    const hv_milp_subsolver_t *sub; /* sub-solves (row windows, neighbourhoods, regions) */
    const struct bp_plugin *plugins[BP_MAX_PLUGINS]; /* by timing, then priority */
    size_t n_plugins;
    bp_master_t m;
    bp_tree_t tree;
    bp_cuts_t cuts;
    bp_incumbent_t inc;
    bp_fixing_t fix;
    bp_region_part_t region;
    bp_stats_t stats;
} bp_t;

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

typedef enum node_end { NODE_PRUNED, NODE_INTEGRAL, NODE_BRANCH, NODE_TIMEOUT } node_end_t;

/* ---- plugins ---------------------------------------------------------------------------- */

/* When the search calls a plugin. */
typedef enum bp_timing {
    BP_AT_START,    /* before the root, once per search */
    BP_PRICE,       /* each column-generation round of a node: the pricer */
    BP_ROOT_LP,     /* the root's master converged, the root not closed yet: separators */
    BP_ROOT_SOLVED, /* the root closed, before the reduced-cost fixing */
    BP_BRANCH,      /* a node's master converged on a fractional point: branching rules */
    BP_NODE_LP,     /* ... then the primal heuristics on that point */
    BP_AFTER_ROOT,  /* the root branched */
    BP_BEFORE_NODE  /* the tree loop, before it takes its next node */
} bp_timing_t;

/* One call's arguments and results; what a timing does not use stays 0. */
typedef struct bp_call {
    int32_t node;    /* the node */
    const double *x; /* BP_BRANCH, BP_NODE_LP: the master point, columns 1 .. ncol */
    int ncol;
    int far;         /* BP_NODE_LP: the plan is more than PRIMAL_ROOT_GAP above node 0's bound */
    double lb_ms;    /* BP_AFTER_ROOT: the root's bound */
    long nodes_done; /* BP_BEFORE_NODE: nodes solved by this search */
    int fresh_node;  /* BP_PRICE: the node's first round */
    split_t *split;  /* BP_BRANCH: the branch chosen so far, in and out */
    double lag_ms;   /* BP_PRICE: out, the round's Lagrangian bound */
    int added;       /* out: BP_PRICE columns added; BP_ROOT_LP the master's rows changed */
    int done;        /* out: the plugins after this one at this timing are not called */
} bp_call_t;

/* A plugin: the pricer, a branching rule, a separator, a primal heuristic or the regional
 * bound, registered by this record (plugins.c). */
typedef struct bp_plugin {
    const char *name;
    bp_timing_t timing;
    int priority;  /* higher first among the plugins of one timing */
    int frequency; /* nodes between calls, which the exec counts; 0: whenever its
                      conditions hold; -1: the option the exec names */
    hv_status_t (*exec)(bp_t *b, const struct bp_plugin *self, bp_call_t *call);
} bp_plugin_t;

/* The plugins of `timing` in order, until one fails or sets call->done. */
hv_status_t bp_plugins_run(bp_t *b, bp_timing_t timing, bp_call_t *call);
/* Register plugins[0 .. n) in b (at most BP_MAX_PLUGINS), ordered by timing then priority. */
void bp_plugins_include(bp_t *b, const bp_plugin_t *const *plugins, size_t n);

/* pool.c */
int bp_iv_reserve(bp_t *b, size_t n);
int bp_hash_rebuild(bp_t *b, size_t cap);
int32_t bp_pattern_find(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n);
void bp_col_open(bp_t *b, size_t j, unsigned char open);
void bp_stop_arms(const bp_t *b, const uint32_t *stop_of, double *arm, unsigned char *used);
double bp_stop_cost_ms(const bp_t *b, const double *arm, const unsigned char *used, size_t p);
int bp_pattern_times(const bp_t *b, uint32_t stop, const uint32_t *f, uint32_t n, double w[2]);
int bp_pattern_add(bp_t *b, uint32_t stop, uint32_t *f, uint32_t n, double cost_ms);
int bp_add_assignment_columns(bp_t *b, const uint32_t *stop_of);
int bp_add_start_columns(bp_t *b);

/* master.c */
void bp_free(bp_t *b);
hv_status_t bp_init(bp_t *b, const hv_instance_t *inst, const hv_milp_options_t *opt);
size_t bp_n_pi(const bp_t *b);
int32_t bp_basis_keep(bp_t *b, int nr, int nc, unsigned char *stat, double *duals, size_t n_pi,
                      size_t n_sg, double lag);
int32_t bp_basis_save(bp_t *b);
count_row_t *bp_crow_get(bp_t *b, uint32_t lo, uint32_t hi);
int bp_skippable(const bp_t *b, size_t f);
int bp_skip_open(const bp_t *b, size_t f);
hv_status_t bp_node_apply(bp_t *b, int32_t k, int *infeasible);
int bp_duals_read(bp_t *b);
hv_status_t bp_lp_solve(bp_t *b, int first);

/* pricing.c */
void bp_stop_items(bp_t *b, size_t p, const double *pi, int node_only, size_t *nl, size_t *nr);
const double *bp_cut_bits(bp_t *b, const double *pi, size_t nl, size_t nr, int *overflow);
hv_status_t bp_price_at(bp_t *b, const double *pi, const double *sg, double *lag_ms, int *added);

/* incumbent.c */
void bp_set_incumbent(bp_t *b, const hv_assignment_t *a, double t_s);
int bp_take_integral(bp_t *b, const double *x);
hv_status_t bp_offer_plan(bp_t *b, const hv_assignment_t *a, double t_s);
hv_status_t bp_improve_plan(bp_t *b, hv_assignment_t *a, unsigned kicks);
unsigned bp_polish_kicks(const bp_t *b);
void bp_progress(bp_t *b, double lb_ms, int force);
hv_status_t bp_take_plan(bp_t *b, int from_helper);
hv_status_t bp_helper_finish(bp_t *b, int take);

/* fixing.c */
hv_status_t bp_fix_pairs(bp_t *b);

/* dominance.c: fix out the pairs of every dominated stop; returns the number of stops. */
long bp_fix_dominated_stops(bp_t *b);

/* centre.c */
void bp_compact_centre(bp_t *b, double limit_s);
hv_status_t bp_ascent_centre(bp_t *b, int steps);

/* node.c */
hv_status_t bp_node_process(bp_t *b, int32_t k, node_end_t *end, split_t *sp);

/* tree.c */
int bp_must_stop(const bp_t *b);
int bp_prunable(const bp_t *b, double lb_ms);
int bp_node_new(bp_t *b, int32_t parent, node_kind_t kind, uint32_t fruit, uint32_t lo, uint32_t hi,
                int32_t rhs, double lb);
int bp_heap_push(bp_t *b, int32_t k);
int32_t bp_heap_pop(bp_t *b);
void bp_region_floor(bp_t *b);
double bp_open_bound(const bp_t *b, size_t *n);
hv_status_t bp_search(bp_t *b, double *root_lb, long *nodes_done);
hv_status_t bp_tree_search(bp_t *b, double *root_lb, long *nodes_done);
double bp_pc_mean(const hv_share_pc_t *pc, size_t i, int d, double none);
void bp_pseudocost_record(bp_t *b, int32_t k);

/* workers.c */
hv_status_t bp_give_if_hungry(bp_t *b);
int bp_balance_shared(bp_t *b);
int bp_next_shared(bp_t *b, int32_t *k);
hv_status_t bp_worker_start(bp_t *b);
hv_status_t bp_worker_join(bp_t *b, int failed, double *open_lb, size_t *n_open);

#endif /* HV_PRICE_BP_H */
