/* harvest-plan: plan a row (MILP, FOV or Serial) and write a checked plan file, or check
 * an existing plan file against its inputs. `harvest-plan --help`. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hv/baselines.h"
#include "hv/cli.h"
#include "hv/file_io.h"
#include "hv/fruit_map.h"
#include "hv/horizon.h"
#include "hv/milp.h"
#include "hv/pick_model.h"
#include "hv/plan_build.h"
#include "hv/plan_check.h"
#include "hv/plan_eval.h"
#include "hv/plan_io.h"
#include "hv/plan_paths.h"
#include "plan_args.h"

/* Set by the first SIGINT / SIGTERM. The program's one piece of process-wide state: a
 * signal handler can reach nothing else. Lock-free, so the handler may store it and the
 * solver's threads read it. */
static atomic_int g_interrupted;

static void on_stop_signal(int sig)
{
    (void)sig;
    atomic_store(&g_interrupted, 1);
}

/* The solvers' stop callback (hv_milp_options_t.stop). */
static int interrupted(void *ctx)
{
    (void)ctx;
    return atomic_load(&g_interrupted);
}

/* The first Ctrl-C / SIGTERM asks the solver to stop; the handler then resets itself, so
 * a second one ends the program. Both are unblocked too: a parent may have started us with
 * them blocked (Python's subprocess passes its caller's mask on), and the solver's threads
 * inherit this mask. */
static void catch_stop_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sa.sa_flags = SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigprocmask(SIG_UNBLOCK, &set, NULL);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* `harvest-plan check PLAN.json`: the plan against its inputs, re-read. */
static int run_check(int argc, char **argv)
{
    plan_check_args_t c;
    int rc = plan_args_parse_check(argc, argv, &c);
    if (rc != 0) {
        return rc == 1 ? 0 : rc;
    }
    char err[512] = "";
    hv_plan_t plan;
    hv_status_t st = hv_plan_load(c.plan, &plan, err, sizeof err);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-plan: %s\n", err);
        return HV_EXIT_USAGE;
    }
    st = hv_plan_check_files(&plan, c.plan, c.config, c.left, c.right, c.fruits, err, sizeof err);
    if (st != HV_OK) {
        int is_check = st <= HV_ERR_PLAN_CHECK_DUPLICATE && st >= HV_ERR_PLAN_CHECK_PARAMS;
        if (is_check) {
            fprintf(stderr, "harvest-plan: %s: %s\n", c.plan, err);
        } else { /* an input of the plan: `err` names its file */
            fprintf(stderr, "harvest-plan: %s\n", err);
        }
        rc = is_check ? HV_EXIT_PLAN_CHECK : HV_EXIT_USAGE;
    } else if (!c.quiet) {
        printf("%s: OK: %s, %zu stops, %zu fruits planned, %zu unreachable, makespan %.3f s\n",
               c.plan, plan.method, plan.n_stops, plan.fruits_planned, plan.fruits_unreachable,
               plan.makespan_s);
    }
    hv_plan_free(&plan);
    return rc;
}

static const char *solve_status_name(hv_solve_status_t s)
{
    switch (s) {
    case HV_SOLVE_OPTIMAL: return "optimal";
    case HV_SOLVE_FEASIBLE: return "feasible";
    case HV_SOLVE_INFEASIBLE: return "infeasible";
    case HV_SOLVE_NO_SOLUTION: return "time_limit";
    default: return "error";
    }
}

/* The whole row in one MILP solve, against the horizon plan `hz` (printed on stdout). */
static hv_status_t compare_single(const hv_instance_t *inst, const hv_milp_options_t *mopt,
                                  const hv_assignment_t *hz)
{
    hv_assignment_t warm = {0, NULL}, one = {0, NULL};
    hv_milp_result_t mr;
    memset(&mr, 0, sizeof mr);
    hv_milp_options_t o = *mopt;
    o.verbose = 0;
    hv_status_t st = hv_assignment_alloc(&warm, inst->n_fruits);
    if (st == HV_OK) {
        st = hv_assignment_alloc(&one, inst->n_fruits);
    }
    if (st == HV_OK) {
        st = hv_heuristic_solve(inst, &warm);
    }
    if (st == HV_OK) {
        st = hv_milp_solve(inst, &o, &warm, &one, &mr);
    }
    double t_hz = 0.0, t_one = 0.0;
    if (st == HV_OK) {
        st = hv_assignment_makespan(inst, hz, &t_hz);
    }
    if (st == HV_OK && (mr.status == HV_SOLVE_OPTIMAL || mr.status == HV_SOLVE_FEASIBLE)) {
        st = hv_assignment_makespan(inst, &one, &t_one);
        if (st == HV_OK) {
            printf("compare: horizon makespan %.3f s, single window %.3f s (%s, gap %.2f%%, "
                   "%.1f s): horizon %+.2f%%\n",
                   t_hz, t_one, solve_status_name(mr.status), 100.0 * mr.gap, mr.runtime_s,
                   100.0 * (t_hz - t_one) / t_one);
        }
    } else if (st == HV_OK) {
        printf("compare: horizon makespan %.3f s, single window: %s after %.1f s\n", t_hz,
               solve_status_name(mr.status), mr.runtime_s);
    }
    hv_assignment_free(&warm);
    hv_assignment_free(&one);
    return st;
}

/* A cost table given on the command line must fit the configuration; the plan itself is
 * computed by the exact IK, so the table is only checked and named in the plan. */
static int check_table(const char *path, hv_side_t side, const hv_config_t *cfg)
{
    if (path == NULL) {
        return 0;
    }
    char err[512];
    if (hv_costtab_check_for(path, cfg, side, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-plan: %s\n", err);
        return HV_EXIT_USAGE;
    }
    return 0;
}

/* "N height, N depth, ..." of the unreachable fruits, or "" when there are none. */
static void why_counts(const hv_instance_t *inst, char *out, size_t len)
{
    size_t n[HV_WHY_ROW_END + 1] = {0};
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (inst->fruit_begin[f] == inst->fruit_begin[f + 1]) {
            ++n[inst->why[f] <= HV_WHY_ROW_END ? inst->why[f] : 0];
        }
    }
    out[0] = '\0';
    size_t used = 0;
    for (int w = 1; w <= HV_WHY_ROW_END && used < len; ++w) {
        if (n[w] > 0) {
            int k = snprintf(out + used, len - used, "%s%zu %s", used ? ", " : ": ", n[w],
                             hv_instance_why_name(w));
            used += k > 0 ? (size_t)k : 0;
        }
    }
}

/* One planning run: its inputs, the instance, the solution and the plan built from it. */
typedef struct run {
    const plan_args_t *a;
    hv_config_t cfg;
    hv_ik_model_t ik; /* model's context */
    hv_pick_model_t model;
    hv_instance_params_t params;
    hv_fruitmap_t map;
    hv_instance_t inst;
    hv_assignment_t sol;
    unsigned char *passes; /* serial: each fruit's pass */
    char inputs[4][HV_PLAN_PATH_LEN];
    hv_plan_meta_t meta;
    hv_milp_options_t mopt;
    hv_plan_t plan;
} run_t;

/* The config, its pick model and row, the cost tables (checked only) and the fruit map. */
static int load_inputs(run_t *r)
{
    const plan_args_t *a = r->a;
    char err[512] = "";
    if (hv_config_load(a->config, &r->cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-plan: %s\n", err);
        return HV_EXIT_USAGE;
    }
    hv_status_t mst = hv_pick_model_ik(&r->cfg, &r->ik, &r->model);
    if (mst != HV_OK) {
        fprintf(stderr, "harvest-plan: %s: an arm reaches none of its fruit area (%s)\n", a->config,
                hv_status_name(mst));
        return HV_EXIT_USAGE;
    }
    hv_instance_params_from_config(&r->cfg, &r->model, &r->params);
    if (a->row_length_m > 0) {
        r->params.row_length_m = a->row_length_m;
        r->params.travel_time_s =
            hv_instance_params_course_m(&r->params) / r->cfg.vehicle_speed_mps;
    }
    int rc = check_table(a->left, HV_SIDE_LEFT, &r->cfg);
    if (rc == 0) {
        rc = check_table(a->right, HV_SIDE_RIGHT, &r->cfg);
    }
    if (rc == 0) {
        hv_fruitmap_limits_t lim;
        hv_fruitmap_limits_from_config(&r->cfg, r->params.row_start_m, r->params.row_length_m,
                                       &lim);
        if (hv_fruitmap_load(a->fruits, &lim, &r->map, err, sizeof err) != HV_OK) {
            fprintf(stderr, "harvest-plan: %s\n", err);
            rc = HV_EXIT_USAGE;
        }
    }
    return rc;
}

/* The instance (candidate stops, reachable pairs) and room for its solution; a line on
 * what it holds unless quiet. */
static int build_instance(run_t *r)
{
    const hv_fruitmap_t *map = &r->map;
    hv_instance_t *inst = &r->inst;
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    double t0 = now_s();
    hv_status_t st = hv_instance_build(&r->params, map->fruits, map->n, &r->model, inst, &d);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-plan: instance: %s: %s\n", d.field, d.message);
        return HV_EXIT_USAGE;
    }
    if (!r->a->quiet) {
        size_t nl = 0;
        for (size_t f = 0; f < map->n; ++f) {
            nl += map->fruits[f].side == HV_SIDE_LEFT;
        }
        char why[128];
        why_counts(inst, why, sizeof why);
        fprintf(stderr,
                "harvest-plan: %zu fruits (%zu left, %zu right), %zu candidate stops "
                "(%.2f to %.2f m), %zu reachable pairs, %zu unreachable fruits%s "
                "(%.3f s)\n",
                map->n, nl, map->n - nl, inst->n_stops, inst->stop_y_m[0],
                inst->stop_y_m[inst->n_stops - 1], inst->n_pairs,
                hv_instance_unreachable_count(inst), why, now_s() - t0);
    }
    if (hv_assignment_alloc(&r->sol, inst->n_fruits) != HV_OK) {
        fprintf(stderr, "harvest-plan: out of memory\n");
        return HV_EXIT_FAILURE;
    }
    return 0;
}

/* What the plan says of its making: method, inputs (relative to the plan's own folder,
 * plan_paths.h), row, limits; the solver's part comes with the solve. */
static int describe_plan(run_t *r)
{
    const plan_args_t *a = r->a;
    const char *given[4] = {a->fruits, a->left, a->right, a->config};
    for (int k = 0; k < 4; ++k) {
        char err[512] = "";
        if (given[k] != NULL && /* tables are optional */
            hv_plan_input_relative(a->out, given[k], r->inputs[k], sizeof r->inputs[k], err,
                                   sizeof err) != HV_OK) {
            fprintf(stderr, "harvest-plan: %s\n", err);
            return HV_EXIT_FAILURE;
        }
    }
    hv_plan_meta_t *meta = &r->meta;
    meta->method = a->method;
    meta->fruit_map = r->inputs[0];
    meta->cost_table_left = r->inputs[1]; /* "" when none was given */
    meta->cost_table_right = r->inputs[2];
    meta->config = r->inputs[3];
    meta->pick_time = hv_pick_model_name(&r->cfg);
    meta->params = r->params;
    meta->vehicle_speed_mps = r->cfg.vehicle_speed_mps;
    meta->time_limit_s = a->time_limit_s;
    meta->gap = -1.0;
    return 0;
}

/* The MILP's options from the command line (Serial and the horizon solve MILPs too). */
static void milp_options(const plan_args_t *a, hv_milp_options_t *mopt)
{
    hv_milp_options_default(mopt);
    mopt->time_limit_s = a->time_limit_s;
    mopt->rel_gap = a->gap;
    mopt->verbose = a->quiet ? 0 : 1;
    mopt->export_lp_path = a->export_lp;
    if (a->algorithm != NULL) {
        mopt->algorithm =
            strcmp(a->algorithm, "compact") == 0 ? HV_MILP_ALG_COMPACT : HV_MILP_ALG_PRICE;
    }
    if (a->threads != 0) {
        mopt->helper_thread = a->threads == 2;
        mopt->tree_threads = a->threads;
    }
    mopt->stop = interrupted;
}

static hv_status_t solve_fov(run_t *r)
{
    const plan_args_t *a = r->a;
    hv_fov_stats_t fs;
    hv_config_t fcfg = r->cfg;
    if (a->fov_width_m > 0) {
        fcfg.fov_width_m = a->fov_width_m;
    }
    if (!isnan(a->fov_offset_m)) {
        fcfg.fov_offset_m = a->fov_offset_m;
    }
    hv_fov_params_t fp;
    hv_fov_params_from_config(&fcfg, &fp);
    hv_status_t st = hv_fov_solve_params(&r->inst, &fp, &r->sol, &fs);
    r->meta.solver_status = "heuristic";
    r->meta.time_limit_s = 0.0;
    if (st == HV_OK && !a->quiet) {
        fprintf(stderr,
                "harvest-plan: fov width %.3f m, offset %.3f m: %zu windows, %zu stops, "
                "%zu fruits moved (in view, out of reach of their stop), %zu extra "
                "stops\n",
                fcfg.fov_width_m, fcfg.fov_offset_m, fs.windows, fs.stops, fs.moved,
                fs.extra_stops);
    }
    return st;
}

static hv_status_t solve_serial(run_t *r)
{
    hv_serial_result_t sr;
    size_t n = r->inst.n_fruits;
    r->passes = malloc(n ? n : 1);
    hv_status_t st = r->passes ? hv_serial_solve(&r->inst, &r->mopt, &r->sol, r->passes, &sr)
                               : HV_ERR_PLAN_NOMEM;
    if (st == HV_OK) {
        r->meta.solver_status = sr.optimal ? "optimal" : "feasible";
        r->meta.gap = sr.gap;
        r->meta.nodes = sr.nodes;
    }
    return st;
}

/* The row in receding windows, each a MILP; with --compare-single, the whole row in one
 * too. */
static hv_status_t solve_horizon(run_t *r)
{
    const plan_args_t *a = r->a;
    hv_horizon_options_t ho;
    hv_horizon_options_default(&ho);
    ho.window_m = a->horizon_m;
    ho.commit_m = a->commit_m > 0 ? a->commit_m : a->horizon_m / 2.0;
    ho.milp = r->mopt;
    ho.milp.verbose = 0;
    ho.progress = a->quiet ? NULL : stderr;
    hv_horizon_result_t hr;
    hv_status_t st = hv_horizon_solve(&r->inst, &ho, &r->sol, &hr);
    if (st == HV_OK) {
        /* each window may be optimal, the row as a whole is not proven */
        r->meta.solver_status = "heuristic";
        r->meta.nodes = hr.nodes;
        r->meta.horizon.used = 1;
        r->meta.horizon.window_m = ho.window_m;
        r->meta.horizon.commit_m = ho.commit_m;
        r->meta.horizon.windows = hr.windows;
        r->meta.horizon.windows_optimal = hr.windows_optimal;
    }
    if (st == HV_OK && a->compare_single) {
        st = compare_single(&r->inst, &r->mopt, &r->sol);
    }
    return st;
}

/* The MILP from the heuristic's warm start; *rc = HV_EXIT_PLAN_NO_SOLUTION when it ends
 * with no plan. */
static hv_status_t solve_milp(run_t *r, int *rc)
{
    hv_assignment_t warm = {0, NULL};
    hv_milp_result_t mr;
    memset(&mr, 0, sizeof mr);
    hv_status_t st = hv_assignment_alloc(&warm, r->inst.n_fruits);
    if (st == HV_OK) {
        st = hv_heuristic_solve(&r->inst, &warm);
    }
    if (st == HV_OK) {
        st = hv_milp_solve(&r->inst, &r->mopt, &warm, &r->sol, &mr);
    }
    hv_assignment_free(&warm);
    if (st == HV_OK && mr.status != HV_SOLVE_OPTIMAL && mr.status != HV_SOLVE_FEASIBLE) {
        fprintf(stderr, "harvest-plan: milp: %s after %.1f s: no plan written\n",
                solve_status_name(mr.status), mr.runtime_s);
        *rc = HV_EXIT_PLAN_NO_SOLUTION;
    } else if (st == HV_OK) {
        r->meta.solver_status = solve_status_name(mr.status);
        r->meta.gap = mr.gap;
        r->meta.nodes = mr.nodes;
    }
    return st;
}

/* Solve by the method asked for, timed; an interruption and a failure each get a line. */
static int solve(run_t *r)
{
    const plan_args_t *a = r->a;
    int rc = 0;
    double t0 = now_s();
    hv_status_t st = strcmp(a->method, "fov") == 0      ? solve_fov(r)
                     : strcmp(a->method, "serial") == 0 ? solve_serial(r)
                     : a->horizon_m > 0                 ? solve_horizon(r)
                                                        : solve_milp(r, &rc);
    r->meta.runtime_s = now_s() - t0;
    if (interrupted(NULL)) {
        fprintf(stderr, "harvest-plan: interrupted after %.1f s: %s\n", r->meta.runtime_s,
                rc == 0 && st == HV_OK ? "writing the best plan so far" : "no plan");
    }
    if (st != HV_OK && rc == 0) {
        fprintf(stderr, "harvest-plan: %s: solve failed: %s\n", a->method, hv_plan_status_name(st));
        rc = st == HV_ERR_PLAN_NO_SOLUTION ? HV_EXIT_PLAN_NO_SOLUTION : HV_EXIT_FAILURE;
    }
    return rc;
}

/* Build the plan, pass it through the independent checker (which re-reads every input
 * file), write it, and say what it is unless quiet. */
static int write_plan(run_t *r)
{
    const plan_args_t *a = r->a;
    hv_plan_t *plan = &r->plan;
    hv_status_t st = hv_plan_build(&r->inst, &r->sol, r->passes, &r->meta, plan);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-plan: building the plan: %s\n", hv_plan_status_name(st));
        return HV_EXIT_FAILURE;
    }
    char err[512] = "";
    st = hv_plan_check_files(plan, NULL, a->config, a->left, a->right, a->fruits, err, sizeof err);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-plan: internal error, plan not written: %s\n", err);
        return HV_EXIT_PLAN_CHECK;
    }
    if (hv_plan_save(a->out, plan, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-plan: %s\n", err);
        return HV_EXIT_FAILURE;
    }
    if (!a->quiet) {
        char gap[32] = "n/a";
        if (plan->gap >= 0) {
            snprintf(gap, sizeof gap, "%.4f%%", 100.0 * plan->gap);
        }
        fprintf(stderr,
                "harvest-plan: %s %s (gap %s): makespan %.3f s = picks %.3f + stops %zu x %.1f "
                "+ travel %.1f; %zu fruits, %zu unreachable, %.4f fruit/s; %.2f s -> %s\n",
                plan->method, plan->solver_status, gap, plan->makespan_s, plan->pick_time_s,
                plan->n_stops, plan->stop_penalty_s, plan->total_travel_time_s,
                plan->fruits_planned, plan->fruits_unreachable, plan->throughput_fruit_per_s,
                plan->runtime_s, a->out);
    }
    return 0;
}

static int run_plan(const plan_args_t *a)
{
    run_t r;
    memset(&r, 0, sizeof r);
    r.a = a;
    milp_options(a, &r.mopt);
    int rc = load_inputs(&r);
    if (rc == 0) {
        rc = build_instance(&r);
    }
    if (rc == 0) {
        rc = describe_plan(&r);
    }
    if (rc == 0) {
        rc = solve(&r);
    }
    if (rc == 0) {
        rc = write_plan(&r);
    }
    if (rc == 0 && interrupted(NULL) && strcmp(r.plan.solver_status, "optimal") != 0) {
        rc = HV_EXIT_PLAN_INTERRUPTED; /* a proof that came in time lost nothing */
    }
    hv_plan_free(&r.plan);
    free(r.passes);
    hv_assignment_free(&r.sol);
    hv_instance_free(&r.inst);
    hv_fruitmap_free(&r.map);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "check") == 0) {
        return run_check(argc, argv);
    }
    plan_args_t a;
    int rc = plan_args_parse(argc, argv, &a);
    if (rc != 0) {
        return rc == 1 ? 0 : rc;
    }
    catch_stop_signals();
    return run_plan(&a);
}
