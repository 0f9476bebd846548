/* The MILP's options and results (milp.h solves with them). Every tunable of the solver,
 * option or constant, is in the parameter table (hv_milp_params; planner/SOLVER.md). */
#ifndef HV_MILP_OPTIONS_H
#define HV_MILP_OPTIONS_H

#include <stddef.h>
#include <stdio.h>

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

/* The solver's options. Every numeric field is a row of the parameter table
 * (hv_milp_params, milp_options.c: default, unit, range and meaning; `harvest-plan
 * --help-params` and planner/SOLVER.md print it), which hv_milp_options_default applies. */
typedef struct hv_milp_options {
    double time_limit_s;        /* wall-clock limit for the solver, > 0 */
    double rel_gap;             /* stop when (obj - bound) / obj <= rel_gap; 0 = exact */
    int verbose;                /* 0 quiet, 1 progress lines on stderr, 2 GLPK's own output */
    const char *export_lp_path; /* when not NULL: write the model in CPLEX LP format */

    /* the model and the search (the table says what each does) */
    int algorithm; /* HV_MILP_ALG_* */
    int link_disaggregated, heuristic_incumbent, ms_granularity, decompose;
    int glpk_cuts, glpk_cuts_phase2, pcost_branching, backtracking, pattern_cuts; /* compact */
    int polish_work;
    /* branch-and-price */
    int column_dive, window_width, helper_thread, rins_every, region_stops;
    int sr_cuts, sr_cuts_large, sr_purge, cover_rows;
    double sr_keep_gain;
    int interval_branching, iv_pseudocost, tail_off_ms, tail_off_open, pseudocost, binding_splits;
    int tree_threads, balance_workers, warm_transfer;
    int auto_smoothing, ascent_steps;

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
    double incumbent_s;     /* T of the starting incumbent (given or heuristic), INFINITY if none */
    int incumbent_taken;    /* 1 when GLPK accepted that incumbent through its callback */
    double root_bound_s;    /* LP relaxation bound at the root (with the added rows) */
    int components;         /* independent row segments solved (1 without decomposition) */
    long cuts;              /* compact: stop-pattern cuts added; price: subset-row cuts kept
                             in the tree */
    long columns;           /* stop-pattern columns generated (branch-and-price) */
    long worker_nodes;      /* price: of `nodes`, those the second tree worker solved */
    long interval_branches; /* price: branches on the stop count of an interval shorter
                               than the row (interval_branching) */
    long tailed_nodes;      /* price: nodes branched on before their column generation
                               converged (tail_off_ms) */
    long passed_nodes;      /* price: nodes passed between the two tree workers */
    long passed_warm;       /* price: of those, the ones whose warm start made a basis of
                               the taker's master (warm_transfer) */
} hv_milp_result_t;

/* Every field at its table default; no export, no stop callback. */
void hv_milp_options_default(hv_milp_options_t *opt);

/* One solver tunable: an option (a field of hv_milp_options_t, set per solve) or a
 * constant (fixed when the solver is built, named as in planner/src/milp_tunables.h). */
typedef struct hv_milp_param {
    const char *name;
    int is_option;    /* 1: hv_milp_options_t.<name>; 0: a constant */
    int is_integer;   /* the value is a whole number (an option: an int field) */
    double value;     /* the default (an option) or the value (a constant) */
    const char *unit; /* "" for a count, a flag or a choice */
    double lo, hi;    /* the range the value may take (an option: hv_milp_option_set checks) */
    const char *doc;  /* one line */
    size_t offset;    /* an option: offsetof(hv_milp_options_t, <name>) */
} hv_milp_param_t;

/* The table: the options first, then the constants; *n receives its length. */
const hv_milp_param_t *hv_milp_params(size_t *n);

/* Set the option of "NAME=VALUE" in `opt`. HV_ERR_ARG when NAME is no option, VALUE does
 * not parse (a whole number for an int field) or lies outside the option's range. */
hv_status_t hv_milp_option_set(hv_milp_options_t *opt, const char *name_value);

/* The table as Markdown (planner/SOLVER.md holds this text, `harvest-plan --help-params`
 * prints it). */
void hv_milp_params_write(FILE *f);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_OPTIONS_H */
