/* The parameter table and the options' defaults (milp_options.h). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_options.h"
#include "hv/plan_status.h"
#include "milp_tunables.h"

#define OPTION(name, integer, def, unit, lo, hi, doc)                                              \
    {                                                                                              \
#name, 1, integer, def, unit, lo, hi, doc, offsetof(hv_milp_options_t, name)               \
    }
#define CONSTANT(name, integer, unit, lo, hi, doc)                                                 \
    {                                                                                              \
#name, 0, integer, (double)(name), unit, lo, hi, doc, 0                                    \
    }

/* Options by concern (the whole solve, the compact model, the branch-and-price), then the
 * constants in the order of milp_tunables.h. */
static const hv_milp_param_t params[] = {
    OPTION(time_limit_s, 0, 60, "s", 0, INFINITY, "wall-clock limit of the solve"),
    OPTION(rel_gap, 0, 1e-6, "", 0, 1, "stop once (T - bound) / T is at most this; 0: exact"),
    OPTION(verbose, 1, 0, "", 0, 2,
           "0 quiet, 1 progress lines on stderr, 2 also GLPK's own output"),
    OPTION(algorithm, 1, 1, "", 0, 1,
           "0 GLPK's branch-and-cut on the paper's model (compact), 1 branch-and-price over "
           "stop patterns"),
    OPTION(heuristic_incumbent, 1, 1, "", 0, 1,
           "1: without a given plan, start from hv_heuristic_solve's"),
    OPTION(decompose, 1, 1, "", 0, 1, "1: row segments that share no stop are solved apart"),
    OPTION(ms_granularity, 1, 1, "", 0, 1,
           "1: when every cost is whole ms, prune what cannot beat the incumbent by 1 ms"),
    OPTION(polish_work, 1, 150000, "", 0, INFINITY,
           "local-search kicks on the plan, times 100 / fruits^2 (at most POLISH_MAX_KICKS); 0 "
           "none"),
    OPTION(link_disaggregated, 1, 1, "", 0, 2,
           "compact: 0 one linking row per stop, 1 a_fp <= b_p per pair, 2 the per-stop rows "
           "plus violated pair rows"),
    OPTION(glpk_cuts, 1, 0, "", 0, 15,
           "compact: GLPK cut families from the start (HV_MILP_CUT_* bits)"),
    OPTION(glpk_cuts_phase2, 1, 15, "", 0, 15,
           "compact: cut families after the polish phase (HV_MILP_CUT_* bits)"),
    OPTION(pcost_branching, 1, 0, "", 0, 1,
           "compact: 1 GLPK's pseudocost branching, 0 its default"),
    OPTION(backtracking, 1, 0, "", 0, 2,
           "compact: GLPK's node selection, 0 best local bound, 1 depth first, 2 best projection"),
    OPTION(pattern_cuts, 1, 0, "depth", -1, INFINITY,
           "compact: tree depth down to which stop-pattern cuts are separated; -1 none"),
    OPTION(column_dive, 1, 1, "", 0, 2,
           "price: a column-fixing dive after the root; 0 never, 1 when the root leaves more "
           "than PRIMAL_ROOT_GAP below CENTRE_MIN_PAIRS pairs, 2 always"),
    OPTION(window_width, 1, 4, "stops", 0, INFINITY,
           "price: stops per re-planned row window of the plan; 0 no windows"),
    OPTION(helper_thread, 1, 1, "", 0, 1,
           "price, with windows: 1 a second thread polishes and re-plans windows (widths 5, 4, "
           "3, 6, 2) from the start"),
    OPTION(rins_every, 1, 8, "nodes", 0, INFINITY,
           "price: nodes between relaxation-induced neighbourhoods once the plan is near the "
           "root's bound (and at the root while far); 0 none"),
    OPTION(region_stops, 1, 100, "stops", 0, INFINITY,
           "price: the longest stretch of a regional bound that tries to prove the incumbent "
           "optimal; 0 none"),
    OPTION(sr_cuts, 1, 1, "rounds", 0, INFINITY, "price: rounds of subset-row cuts at the root"),
    OPTION(sr_cuts_large, 1, 2, "rounds", 0, INFINITY,
           "price: the same from CENTRE_MIN_PAIRS pairs"),
    OPTION(sr_purge, 1, 1, "", 0, 1,
           "price: 1 the cuts slack at the solved root are deleted before the tree"),
    OPTION(sr_keep_gain, 0, 0, "", 0, 1,
           "price: the cuts stay in the tree only when they raised the root's bound by this "
           "share; 0 always"),
    OPTION(cover_rows, 1, 2, "", 0, 2,
           "price: fruit rows 0 \"= 1\", 1 \">= 1\", 2 \">= 1\" from CENTRE_MIN_PAIRS pairs"),
    OPTION(interval_branching, 1, 30, "stops", 0, INFINITY,
           "price: branch on the stop count of intervals of up to this many stops before "
           "fruits; 0 the whole row only"),
    OPTION(iv_pseudocost, 1, 1, "", 0, 1,
           "price: 1 interval counts scored by their children's bound rises"),
    OPTION(pseudocost, 1, 1, "", 0, 1,
           "price: 1 fruit splits chosen by pseudocosts, 0 the most balanced"),
    OPTION(binding_splits, 1, 1, "", 0, 1,
           "price, with pseudocost: 1 a fruit's score weighted by where its arm binds"),
    OPTION(tail_off_ms, 1, 20, "ms", 0, INFINITY,
           "price: below the root, branch on a stalled master within this of the node's bound; "
           "0 never"),
    OPTION(tail_off_open, 1, 1, "", 0, 1,
           "price, with tail_off_ms: 1 also a stalled master the incumbent does not prune"),
    OPTION(tree_threads, 1, 2, "threads", 1, 2,
           "price: 2 a second thread searches the tree once the plan is within WORKER_GAP of "
           "the bound"),
    OPTION(balance_workers, 1, 1, "", 0, 1,
           "price, two workers: 1 a worker far above the other's bound asks for its best node"),
    OPTION(warm_transfer, 1, 1, "", 0, 1,
           "price, two workers: 1 a passed node carries its parent's basis and centre"),
    OPTION(auto_smoothing, 1, 1, "", 0, 1,
           "price: 1 the smoothing weight adapts each round (from SMOOTHING), 0 fixed"),
    OPTION(ascent_steps, 1, 100, "steps", 0, INFINITY,
           "price: subgradient steps before the root for its first centre; 0 none"),
    CONSTANT(BIG_MS, 0, "ms", 1e3, 1e9,
             "the cost of an artificial column: keeps every node's master feasible"),
    CONSTANT(RC_EPS_MS, 0, "ms", 0, 1,
             "a column enters the master when its reduced cost is below -RC_EPS_MS"),
    CONSTANT(LAMBDA_EPS, 0, "", 0, 0.1, "a master value this close to 0 or 1 counts as integral"),
    CONSTANT(SMOOTHING, 0, "", 0, 1,
             "Wentges smoothing: the weight of the stabilisation centre in the duals priced"),
    CONSTANT(SMOOTH_STEP, 0, "", 0, 1, "auto_smoothing: the weight's step per round"),
    CONSTANT(SMOOTH_MAX, 0, "", 0, 1, "auto_smoothing: the weight's largest value"),
    CONSTANT(ASCENT_DEFLECT, 0, "", 0, 1,
             "the root's ascent: the share of the last direction kept"),
    CONSTANT(CAND_WINDOW, 1, "stops", 0, INFINITY,
             "a stop's column enters when its reduced cost is the least within this many stops"),
    CONSTANT(CENTRE_MIN_PAIRS, 1, "pairs", 0, INFINITY,
             "large instances: the root's centre from the paper's LP, cover_rows 2 covers, "
             "sr_cuts_large, no column_dive 1"),
    CONSTANT(PRIMAL_ROOT_GAP, 0, "", 0, 1,
             "the plan's gap above the root's bound beyond which polish, dive, windows and "
             "rounding at every node run"),
    CONSTANT(POLISH_MAX_KICKS, 1, "kicks", 0, INFINITY, "the polish's local-search kicks at most"),
    CONSTANT(POLISH_CHUNK, 1, "kicks", 1, INFINITY,
             "kicks between two readings of the clock (polish)"),
    CONSTANT(WORKER_GAP, 0, "", 0, 1,
             "the incumbent's gap from which the second core searches the tree"),
    CONSTANT(DIVE_EVERY, 1, "nodes", 1, INFINITY, "nodes between two branch dives"),
    CONSTANT(BALANCE_SHARE, 0, "", 0, 1,
             "balance_workers: a worker whose best bound lies this share of its gap above the "
             "other's asks for a node"),
    CONSTANT(ROUND_EVERY, 1, "nodes", 1, INFINITY,
             "nodes between roundings of the master point once the plan is near the root's bound"),
    CONSTANT(ROUND_TIME_SHARE, 0, "", 0, 1,
             "the rounding's share of the search's time at most (below depth 2): past it, nodes "
             "skip it"),
    CONSTANT(WINDOW_SHARE, 0, "", 0, 1,
             "the share of the time left after the root for row windows on the search's thread"),
    CONSTANT(WINDOW_LIMIT_S, 0, "s", 0, INFINITY,
             "a row window's sub-solve on the search's thread"),
    CONSTANT(RINS_LIMIT_S, 0, "s", 0, INFINITY, "a neighbourhood's sub-solve"),
    CONSTANT(RINS_MAX_FREE, 1, "fruits", 1, INFINITY, "fruits freed in one neighbourhood at most"),
    CONSTANT(RINS_CALL_S, 0, "s", 0, INFINITY, "time for the neighbourhoods at one master point"),
    CONSTANT(SR_MAX, 1, "cuts", 1, INFINITY, "subset-row cuts at most (all made at the root)"),
    CONSTANT(SR_PER_ROUND, 1, "cuts", 1, INFINITY, "subset-row cuts added per separation round"),
    CONSTANT(SR_PER_FRUIT, 1, "cuts", 1, INFINITY,
             "new cuts per fruit per round (spreads them over the row)"),
    CONSTANT(SR_MIN_VIOL, 0, "", 0, 1,
             "a subset-row cut enters when the master point violates it by this"),
    CONSTANT(REGION_AFTER_NODES, 1, "nodes", 0, INFINITY,
             "tree nodes before the first regional bound"),
    CONSTANT(REGION_SHARE, 0, "", 0, 1,
             "the share of the time left for each regional sub-solve at most"),
    CONSTANT(REGION_EPS_MS, 0, "ms", 0, INFINITY,
             "a grown stretch must raise its rise by more than this to grow again"),
    CONSTANT(REGION_KICKS, 1, "kicks", 0, INFINITY,
             "local-search kicks on the plan a stretch's solution gives"),
    CONSTANT(REGION_GROW, 1, "stops", 1, INFINITY, "stops a stretch grows by on either side"),
    CONSTANT(COUNT_MIN_SCORE, 0, "", 0, 0.5,
             "an interval count this far from an integer is branched on before any fruit"),
    CONSTANT(IV_MIN_FRAC, 0, "", 0, 0.5,
             "interval branching: the least fractional count considered"),
    CONSTANT(IV_GAP_WEIGHT, 0, "", 0, INFINITY,
             "interval branching: the weight of the empty stops around an interval"),
    CONSTANT(IV_EDGE_GAP, 1, "stops", 0, INFINITY,
             "interval branching: the empty run counted beyond an end of the row"),
    CONSTANT(IV_PC_FLOOR_MS, 0, "ms", 0, INFINITY,
             "iv_pseudocost: the least estimated bound rise of a child"),
    CONSTANT(TAIL_ROUNDS, 1, "rounds", 1, INFINITY,
             "tailing off: rounds without a fall of the master value"),
    CONSTANT(TAIL_FALL_MS, 0, "ms", 0, INFINITY,
             "tailing off: the fall of the master value that counts"),
    CONSTANT(BIND_MIN_WEIGHT, 0, "", 0, 1,
             "binding_splits: the weight of a fruit whose arm never binds"),
    CONSTANT(STALL_ITERS_PER_ROW, 1, "iterations", 1, INFINITY,
             "primal simplex iterations per master row before the dual simplex finishes the call"),
    CONSTANT(HELPER_WINDOW_LIMIT_S, 0, "s", 0, INFINITY, "helper thread: a row window's sub-solve"),
    CONSTANT(HELPER_KICKS, 1, "kicks", 0, INFINITY,
             "helper thread: local-search kicks after a round of widths found nothing"),
    CONSTANT(HELPER_KICKS_CHUNK, 1, "kicks", 1, INFINITY, "helper thread: kicks run at a time"),
    CONSTANT(HELPER_MEMO, 1, "windows", 1, INFINITY,
             "helper thread: windows remembered as solved without gain"),
    CONSTANT(CLOCK_EVERY_POINTS, 1, "points", 1, INFINITY,
             "pricing: frontier points made between two readings of the clock"),
    CONSTANT(WAIT_SLICE_NS, 1, "ns", 1, INFINITY,
             "a tree worker waiting for a node looks at its clock this often"),
    CONSTANT(FRAC_EPS, 0, "", 0, 0.1,
             "subset-row separation: a column this close to 0 or 1 is not fractional"),
    CONSTANT(HV_CUT_MAX_ROUNDS, 1, "rounds", 0, INFINITY,
             "compact: pattern-cut separation rounds over the whole tree"),
    CONSTANT(CUT_MIN_VIOLATION_S, 0, "s", 0, INFINITY,
             "compact: a smaller pattern-cut violation is not worth a row"),
    CONSTANT(CUT_MIN_VALUE, 0, "", 0, 0.1,
             "compact: a_fp below this counts as 0 in the pattern-cut separation"),
};

#define N_PARAMS (sizeof params / sizeof params[0])

const hv_milp_param_t *hv_milp_params(size_t *n)
{
    *n = N_PARAMS;
    return params;
}

/* Option p of opt := v (an int field takes v as a whole number). */
static void store(hv_milp_options_t *opt, const hv_milp_param_t *p, double v)
{
    char *field = (char *)opt + p->offset;
    if (p->is_integer) {
        *(int *)(void *)field = (int)v;
    } else {
        *(double *)(void *)field = v;
    }
}

void hv_milp_options_default(hv_milp_options_t *opt)
{
    memset(opt, 0, sizeof *opt); /* no export, no stop callback */
    for (size_t i = 0; i < N_PARAMS && params[i].is_option; ++i) {
        store(opt, &params[i], params[i].value);
    }
}

hv_status_t hv_milp_option_set(hv_milp_options_t *opt, const char *name_value)
{
    const char *eq = strchr(name_value, '=');
    if (eq == NULL || eq[1] == '\0') {
        return HV_ERR_ARG;
    }
    size_t n = (size_t)(eq - name_value);
    for (size_t i = 0; i < N_PARAMS && params[i].is_option; ++i) {
        const hv_milp_param_t *p = &params[i];
        if (strlen(p->name) != n || strncmp(name_value, p->name, n) != 0) {
            continue;
        }
        char *end;
        errno = 0;
        double v = p->is_integer ? (double)strtol(eq + 1, &end, 10) : strtod(eq + 1, &end);
        if (*end != '\0' || errno != 0 || !(v >= p->lo && v <= p->hi)) {
            return HV_ERR_ARG;
        }
        store(opt, p, v);
        return HV_OK;
    }
    return HV_ERR_ARG;
}

static void write_number(FILE *f, double v, int integer)
{
    if (isinf(v)) {
        fputs(v > 0 ? "inf" : "-inf", f);
    } else if (integer) {
        fprintf(f, "%.0f", v);
    } else {
        fprintf(f, "%g", v);
    }
}

void hv_milp_params_write(FILE *f)
{
    fputs("| name | kind | default | unit | range | meaning |\n"
          "| --- | --- | --- | --- | --- | --- |\n",
          f);
    for (size_t i = 0; i < N_PARAMS; ++i) {
        const hv_milp_param_t *p = &params[i];
        fprintf(f, "| %s | %s | ", p->name, p->is_option ? "option" : "constant");
        write_number(f, p->value, p->is_integer);
        fprintf(f, " | %s | ", p->unit);
        write_number(f, p->lo, p->is_integer);
        fputs(" .. ", f);
        write_number(f, p->hi, p->is_integer);
        fprintf(f, " | %s |\n", p->doc);
    }
}
