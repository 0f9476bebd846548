/* The MILP's options and results (milp.h solves with them). Every tunable of the solver,
 * option or constant, is in the parameter table (milp_params.h; planner/SOLVER.md). */
#ifndef HV_MILP_OPTIONS_H
#define HV_MILP_OPTIONS_H

#include "hv/plan_instance.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hv_solve_status {
    HV_SOLVE_OPTIMAL = 0,     /* proven optimal (within rel_gap) */
    HV_SOLVE_FEASIBLE = 1,    /* a solution, optimality not proven: see gap */
    HV_SOLVE_INFEASIBLE = 2,  /* no assignment exists (cannot happen for reachable fruit) */
    HV_SOLVE_NO_SOLUTION = 3, /* time limit hit before any solution */
    HV_SOLVE_ERROR = 4
} hv_solve_status_t;

typedef struct hv_milp_options {
    double time_limit_s;        /* wall-clock limit for the solver, > 0 */
    double rel_gap;             /* stop when (obj - bound) / obj <= rel_gap; 0 = exact */
    int verbose;                /* 0 quiet, 1 progress lines on stderr, 2 GLPK's own output */
    const char *export_lp_path; /* when not NULL: write the model in CPLEX LP format */

    /* Model and search choices; planner/SOLVER.md gives each one's measured effect.
     * hv_milp_options_default() sets the combination SOLVER.md keeps. */
    int link_disaggregated;  /* 0: sum_f a_fp <= n_p b_p per stop; 1: a_fp <= b_p per pair;
                                2: the per-stop rows plus a_fp <= b_p added where violated
                                (LP rounds at the root, cuts in the tree) */
    int heuristic_incumbent; /* 1: when `incumbent` is NULL, run hv_heuristic_solve first */
    int branch_stops_first;  /* 1: branch on a fractional b_p before any a_fp */
    int side_bounds;         /* 1: add sum C_p + tau sum b_p >= each side's own optimum */
    int ms_granularity;      /* 1: when every cost is a whole number of ms, prune nodes that
                                cannot beat the incumbent by 1 ms (exact, not a tolerance) */
    int decompose;           /* 1: solve row segments that share no stop separately */
    int glpk_cuts;           /* GLPK cut families: HV_MILP_CUT_* bits */
    int glpk_cuts_phase2;    /* cut families added in the second (post-polish) phase */
    int pcost_branching;     /* 1: GLPK's pseudocost branching (else its default) */
    int backtracking;        /* GLPK node selection: 0 best local bound, 1 depth first,
                                2 best projection */
    int count_branching;     /* 1: integer stop-count columns (all stops, and per block of
                                block_stops stops when > 0), branched on first */
    int block_stops;
    int polish_work;         /* > 0: run the local search from the best plan with
                                polish_work * 100 / n_fruits^2 kicks (at most 1000) on the
                                helper thread from the start (price, helper_thread), else
                                when the root does not close the gap (price) or when the
                                root gap is > 0.2 % and phase 1 of the tree (20 % of the
                                limit) does not prove optimality (compact) */
    int algorithm;           /* HV_MILP_ALG_*: how the model is solved (both exact) */
    int pattern_cuts;        /* tree depth down to which stop-pattern cuts are separated
                                (milp_cuts.h); -1: none */
    int column_dive;         /* price: a primal dive by column fixing after the root;
                                0 never, 1 when the root leaves > 0.2 % on instances of
                                fewer than 9,000 (fruit, stop) pairs, 2 always */
    int window_width;        /* price: when the root leaves > 0.2 %, re-plan windows of this
                                many consecutive stops of the incumbent exactly
                                (milp_window.h) for up to a quarter of the limit; 0 never */
    int helper_thread;       /* price, with window_width > 0: 1 a second thread, from the
                                start of the solve, first runs the polish (polish_work)
                                and then re-plans windows for the rest of the solve,
                                cycling through widths 5, 4, 3, 6, 2 (milp_helper.h) */
    int sr_cuts;             /* price: rounds of subset-row cuts on fruit triples at the root
                                (milp_srcuts.h); 0 none */
    int sr_cuts_large;       /* price: the same on instances of 9,000+ pairs (alpha 4), where
                                each of the first five rounds raised the root's bound; with
                                interval branching two measured best (SOLVER.md) */
    int sr_purge;            /* price: 1 the cuts slack at the solved root (basic, zero duals)
                                are deleted before the tree, whose master solves each cut
                                row makes dearer; 0 they stay */
    int sr_cross;            /* price: 1 the cuts' triples may hold fruits of both sides, 0
                                one side only */
    int interval_branching;  /* price: when the row's stop count is integral, branch on the
                                count of stops in an interval of up to this many stops
                                before any fruit's stop (SOLVER.md); 0 the whole row only */
    int tail_off_ms;         /* price: below the root, branch without waiting for the column
                                generation to converge once the master value has not
                                fallen for 10 rounds and is within this many ms of the
                                node's Lagrangian bound; 0 never */
    int tail_off_open;       /* price, with tail_off_ms: 1 a master that has not fallen for
                                10 rounds is also branched on, however far below it the
                                Lagrangian bound lies, when the incumbent does not prune
                                it (no bound that node could reach would); 0 only within
                                tail_off_ms */
    int pseudocost;          /* price: 1 fruit splits are chosen by pseudocosts (the bound
                                rises seen per unit of mass moved), 0 the most balanced */
    int binding_splits;      /* price, with pseudocost: 1 a fruit's split score is weighted
                                by the share of its master mass in patterns where its
                                arm's time is the pattern's max (SOLVER.md); 0 unweighted */
    int iv_pseudocost;       /* price, with interval_branching: 1 an interval's count score
                                is weighted by the bound rises its count children showed
                                (pseudocosts per interval, SOLVER.md); 0 the score alone */
    int balance_workers;     /* price, with two tree workers: 1 a worker whose best open bound
                                lies well above the other's asks for the other's best node
                                (milp_share.h); 0 only a worker without nodes asks */
    int warm_transfer;       /* price, with two tree workers: 1 a node passed between them
                                carries the basis and stabilisation centre its parent left
                                it, its columns named by content (milp_share.h); 0 its path
                                only, the taker starting from its own last basis */
    int rins_every;          /* price: once the plan is within 0.2 % of the root's bound, every
                                this many nodes the fruits on which the node's LP point and
                                the plan disagree are re-planned exactly (milp_rins.h), and
                                at the solved root while it is further; 0 never */
    int region_stops;        /* price: after 16 nodes, try once per incumbent to prove it
                                optimal by a regional bound (milp_region.h, SOLVER.md): a
                                sub-solve over a stretch of at most this many stops around
                                where its gap over the root's bound (before the cuts) lies;
                                0 never */
    int tree_threads;        /* price: 2 (default) a second thread searches the tree too
                                once the incumbent is within 0.2 % of the bound, the
                                helper thread stopping then (milp_share.h); 1 one thread.
                                With 2, opt->stop is also called from that thread */
    int auto_smoothing;      /* price: 1 the dual smoothing weight adapts each round to the
                                pricing's subgradient (from 0.8 at each node); 0 fixed 0.8 */
    int ascent_steps;        /* price: subgradient steps on the fruit rows' Lagrangian
                                before the root (its first stabilisation centre and
                                columns); 0 none, the centre then comes from the paper's
                                LP on instances of 9,000+ pairs */
    double sr_keep_gain;     /* price: the cuts stay in the tree only when they raised the
                                root's bound by this share (they slow every master LP);
                                0 keeps them always */
    int cover_rows;          /* price: 1 the master's fruit rows are ">= 1" (set covering:
                                the same optimum, since dropping a fruit from a pattern never
                                costs more, and duals >= 0, on which the root's column
                                generation converges in fewer simplex iterations); 0 "= 1"
                                (set partitioning, whose tree measured better at alpha 2.5);
                                2 ">= 1" on instances of 9,000+ pairs (alpha 4), whose root
                                takes seconds, else "= 1" */
    /* When not NULL, polled by the branch-and-price at each node and pricing round and by
     * GLPK's branch-and-cut at each of its callbacks: a non-zero return ends the solve as
     * its time limit would (status FEASIBLE or NO_SOLUTION, never OPTIMAL unless proven).
     * harvest-plan sets it on Ctrl-C / SIGTERM. */
    int (*stop)(void *ctx);
    void *stop_ctx;
} hv_milp_options_t;

enum {
    HV_MILP_ALG_COMPACT = 0, /* GLPK's branch-and-cut on the paper's model (milp_model.h) */
    HV_MILP_ALG_PRICE = 1    /* branch-and-price over stop patterns (milp_price.h) */
};

enum { HV_MILP_CUT_GMI = 1, HV_MILP_CUT_MIR = 2, HV_MILP_CUT_COVER = 4, HV_MILP_CUT_CLIQUE = 8 };

typedef struct hv_milp_result {
    hv_solve_status_t status;
    double objective_s; /* T of the returned assignment, incl. tau * stops and T_travel */
    double bound_s;     /* best proven lower bound on T; when FEASIBLE at least T_travel +
                           tau + the larger arm's sum of cheapest picks */
    double gap;         /* (objective - bound) / objective; <= rel_gap when OPTIMAL */
    long nodes;         /* branch-and-bound nodes (summed over sub-solves if any) */
    double runtime_s;
    double incumbent_s;   /* T of the starting incumbent (given or heuristic), INFINITY if none */
    int incumbent_taken;  /* 1 when GLPK accepted that incumbent through its callback */
    double root_bound_s;  /* LP relaxation bound at the root (with the added rows) */
    int components;       /* independent row segments solved (1 without decomposition) */
    long cuts;            /* compact: stop-pattern cuts added; price: subset-row cuts kept
                             in the tree */
    long columns;         /* stop-pattern columns generated (branch-and-price) */
    long worker_nodes;    /* price: of `nodes`, those the second tree worker solved */
    long interval_branches; /* price: branches on the stop count of an interval shorter
                               than the row (interval_branching) */
    long tailed_nodes;      /* price: nodes branched on before their column generation
                               converged (tail_off_ms) */
    long passed_nodes;      /* price: nodes passed between the two tree workers */
    long passed_warm;       /* price: of those, the ones whose warm start made a basis of
                               the taker's master (warm_transfer) */
} hv_milp_result_t;

/* Defaults: 60 s limit, gap 1e-6, quiet, no export, the choices SOLVER.md keeps. */
void hv_milp_options_default(hv_milp_options_t *opt);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_OPTIONS_H */
