/* harvest-plan: plan a row (MILP, FOV or Serial) and write a checked plan file, or check
 * an existing plan file against its inputs. `harvest-plan --help`. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
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
#include "hv/version.h"

static const char k_prog[] = "harvest-plan";

static const char k_usage[] =
    "usage: harvest-plan --config CFG --fruits MAP.csv --method milp|fov|serial\n"
    "                    --out PLAN.json [--left LEFT.bin --right RIGHT.bin] [options]\n"
    "       harvest-plan check PLAN.json [--config CFG] [--left L.bin] [--right R.bin]\n"
    "                    [--fruits MAP.csv] [--quiet]\n"
    "\n"
    "Plans the vehicle's stops along a row and assigns every fruit to an arm at one stop,\n"
    "minimising the makespan (DESIGN §1). Every pick is solved by the exact IK the executor\n"
    "uses, so no planned fruit is refused at its stop; with row.stops_beyond_ends the stops\n"
    "extend beyond the row's ends as far as an arm reaches into the row. Every plan written\n"
    "has passed the independent checker; the file is written atomically. Plan format:\n"
    "docs/PLAN_FORMAT.md.\n"
    "\n"
    "options:\n"
    "  --left, --right  cost tables (costgen): optional; when given, refused unless built\n"
    "                   for the config's arm, mount, joint limits, home pose and grid, and\n"
    "                   named in the plan's inputs\n"
    "  --time-limit S   solver time limit per solve, s (default 60)\n"
    "  --gap G          relative gap at which the MILP stops (default 1e-6)\n"
    "  --fov-width M    fov: each arm's camera window along the row, m (default: fov.width\n"
    "                   of the config)\n"
    "  --fov-offset M   fov: window centre from its arm's base along the row, outward, m\n"
    "                   (default: fov.offset of the config; docs/FRAMES.md)\n"
    "  --horizon H      milp: receding horizon, plan H m windows (commit H/2 each)\n"
    "  --commit M       with --horizon: length committed per window, m (default H/2)\n"
    "  --compare-single with --horizon: also solve the whole row in one window and print\n"
    "                   both makespans (the plan written is the horizon's)\n"
    "  --row-length M   row length, m (default: row.length of the config)\n"
    "  --export-lp FILE milp: write the model in CPLEX LP format\n"
    "  --threads N      milp, price: 2 (default) uses a second thread, which polishes\n"
    "                   the plan, re-plans its row windows and, once that plan is within\n"
    "                   0.2 % of the bound, searches the tree beside the first; 1 keeps\n"
    "                   to one\n"
    "  --algorithm A    milp: price (branch-and-price over stop patterns, default) or\n"
    "                   compact (GLPK's branch-and-cut on the paper's model); both exact\n"
    "  --quiet          no progress lines on stderr (errors are still printed)\n"
    "  --help           this text\n"
    "  --version        the version and exit\n"
    "  --help-params    the solver's parameter table (options and constants, Markdown)\n"
    "\n"
    "check: re-reads the fruit map, tables and config (paths default to the plan's inputs,\n"
    "relative ones taken from the plan file's folder) and verifies the plan: exit 0 if it\n"
    "holds, 4 with the first violation otherwise.\n"
    "\n"
    "The plan names its inputs as given when absolute, else relative to its own folder.\n"
    "\n"
    "Ctrl-C or SIGTERM stops the solver as its time limit would: the best plan so far is\n"
    "checked and written with its status and gap (exit 5); a second one ends the program\n"
    "at once, writing nothing.\n"
    "\n" HV_EXIT_CODES_HELP ",\n"
    "3 no solution, 4 the plan failed the independent check, 5 interrupted: the best plan\n"
    "so far written)\n";

typedef struct args {
    const char *config, *left, *right, *fruits, *method, *out, *export_lp, *algorithm;
    double time_limit_s, gap, fov_width_m, fov_offset_m, horizon_m, commit_m, row_length_m;
    int quiet;
    int compare_single;
    int threads; /* 0: the default */
} args_t;

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

static int usage_error(const char *what, const char *why)
{
    hv_cli_usage_error(k_prog, what, why);
    return HV_EXIT_USAGE;
}

/* "harvest-plan: --flag: expected ..., got "text"" */
static int bad_value(const char *flag, const char *expected, const char *text)
{
    fprintf(stderr, "harvest-plan: %s: expected %s, got \"%s\"\n", flag, expected, text);
    return HV_EXIT_USAGE;
}

/* A positive finite number: 0, or HV_EXIT_USAGE with a message. */
static int parse_pos(const char *flag, const char *text, double *out)
{
    char *end = NULL;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(v) || v <= 0) {
        return bad_value(flag, "a positive number", text);
    }
    *out = v;
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* getopt_long's verdict on argv[optind - 1] when it returned ':' or '?'. */
static int option_error(int opt, char **argv)
{
    hv_cli_option_error(k_prog, opt, optopt, argv[optind - 1]);
    return HV_EXIT_USAGE;
}

static int run_check(int argc, char **argv)
{
    enum { OPT_CONFIG = 256, OPT_LEFT, OPT_RIGHT, OPT_FRUITS, OPT_QUIET };
    static const struct option longopts[] = {
        {"config", required_argument, NULL, OPT_CONFIG},
        {"left", required_argument, NULL, OPT_LEFT},
        {"right", required_argument, NULL, OPT_RIGHT},
        {"fruits", required_argument, NULL, OPT_FRUITS},
        {"quiet", no_argument, NULL, OPT_QUIET},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    const char *plan_path = NULL, *config = NULL, *left = NULL, *right = NULL, *fruits = NULL;
    int quiet = 0, opt;
    opterr = 0;
    optind = 2; /* after "check" */
    while ((opt = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'h': fputs(k_usage, stdout); return 0;
        case 'V': printf("harvest-plan %s\n", HV_VERSION); return 0;
        case OPT_QUIET: quiet = 1; break;
        case OPT_CONFIG: config = optarg; break;
        case OPT_LEFT: left = optarg; break;
        case OPT_RIGHT: right = optarg; break;
        case OPT_FRUITS: fruits = optarg; break;
        default: return option_error(opt, argv);
        }
    }
    if (optind < argc) {
        plan_path = argv[optind++];
    }
    if (optind < argc) {
        return usage_error(argv[optind], "more than one plan file");
    }
    if (plan_path == NULL) {
        return usage_error("check", "needs a PLAN.json");
    }
    char err[512] = "";
    hv_plan_t plan;
    hv_status_t st = hv_plan_load(plan_path, &plan, err, sizeof err);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-plan: %s\n", err);
        return HV_EXIT_USAGE;
    }
    st = hv_plan_check_files(&plan, plan_path, config, left, right, fruits, err, sizeof err);
    int rc = 0;
    if (st != HV_OK) {
        int is_check = st <= HV_ERR_PLAN_CHECK_DUPLICATE && st >= HV_ERR_PLAN_CHECK_PARAMS;
        if (is_check) {
            fprintf(stderr, "harvest-plan: %s: %s\n", plan_path, err);
        } else { /* an input of the plan: `err` names its file */
            fprintf(stderr, "harvest-plan: %s\n", err);
        }
        rc = is_check ? HV_EXIT_PLAN_CHECK : HV_EXIT_USAGE;
    } else if (!quiet) {
        printf("%s: OK: %s, %zu stops, %zu fruits planned, %zu unreachable, makespan %.3f s\n",
               plan_path, plan.method, plan.n_stops, plan.fruits_planned, plan.fruits_unreachable,
               plan.makespan_s);
    }
    hv_plan_free(&plan);
    return rc;
}

static int parse_args(int argc, char **argv, args_t *a)
{
    enum {
        OPT_CONFIG = 256,
        OPT_LEFT,
        OPT_RIGHT,
        OPT_FRUITS,
        OPT_METHOD,
        OPT_OUT,
        OPT_EXPORT_LP,
        OPT_TIME_LIMIT,
        OPT_GAP,
        OPT_FOV_WIDTH,
        OPT_FOV_OFFSET,
        OPT_HORIZON,
        OPT_COMMIT,
        OPT_ROW_LENGTH,
        OPT_ALGORITHM,
        OPT_THREADS,
        OPT_QUIET,
        OPT_COMPARE_SINGLE,
        OPT_HELP_PARAMS
    };
    static const struct option longopts[] = {
        {"config", required_argument, NULL, OPT_CONFIG},
        {"left", required_argument, NULL, OPT_LEFT},
        {"right", required_argument, NULL, OPT_RIGHT},
        {"fruits", required_argument, NULL, OPT_FRUITS},
        {"method", required_argument, NULL, OPT_METHOD},
        {"out", required_argument, NULL, OPT_OUT},
        {"export-lp", required_argument, NULL, OPT_EXPORT_LP},
        {"time-limit", required_argument, NULL, OPT_TIME_LIMIT},
        {"gap", required_argument, NULL, OPT_GAP},
        {"fov-width", required_argument, NULL, OPT_FOV_WIDTH},
        {"fov-offset", required_argument, NULL, OPT_FOV_OFFSET},
        {"horizon", required_argument, NULL, OPT_HORIZON},
        {"commit", required_argument, NULL, OPT_COMMIT},
        {"row-length", required_argument, NULL, OPT_ROW_LENGTH},
        {"algorithm", required_argument, NULL, OPT_ALGORITHM},
        {"threads", required_argument, NULL, OPT_THREADS},
        {"quiet", no_argument, NULL, OPT_QUIET},
        {"compare-single", no_argument, NULL, OPT_COMPARE_SINGLE},
        {"help-params", no_argument, NULL, OPT_HELP_PARAMS},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    memset(a, 0, sizeof *a);
    a->time_limit_s = 60.0;
    a->gap = 1e-6;
    a->fov_offset_m = NAN; /* 0 width and NAN offset: the config's */
    opterr = 0;
    int opt, idx = 0;
    while ((opt = getopt_long(argc, argv, ":h", longopts, &idx)) != -1) {
        const char *v = optarg;
        /* the option as given, for messages: --name even when written --name=value */
        char f[32];
        snprintf(f, sizeof f, "--%s", opt >= OPT_CONFIG ? longopts[idx].name : "");
        switch (opt) {
        case 'h': fputs(k_usage, stdout); return 1;
        case 'V': printf("harvest-plan %s\n", HV_VERSION); return 1;
        case OPT_HELP_PARAMS: hv_milp_params_write(stdout); return 1;
        case OPT_QUIET: a->quiet = 1; break;
        case OPT_COMPARE_SINGLE: a->compare_single = 1; break;
        case OPT_CONFIG: a->config = v; break;
        case OPT_LEFT: a->left = v; break;
        case OPT_RIGHT: a->right = v; break;
        case OPT_FRUITS: a->fruits = v; break;
        case OPT_METHOD: a->method = v; break;
        case OPT_OUT: a->out = v; break;
        case OPT_EXPORT_LP: a->export_lp = v; break;
        case OPT_ALGORITHM: a->algorithm = v; break;
        case OPT_THREADS:
            if (strcmp(v, "1") != 0 && strcmp(v, "2") != 0) {
                return bad_value("--threads", "1 or 2", v);
            }
            a->threads = v[0] - '0';
            break;
        case OPT_TIME_LIMIT:
            if (parse_pos(f, v, &a->time_limit_s))
                return HV_EXIT_USAGE;
            break;
        case OPT_GAP: {
            char *end = NULL;
            a->gap = strtod(v, &end);
            if (end == v || *end != '\0' || !isfinite(a->gap) || a->gap < 0 || a->gap >= 1) {
                return bad_value("--gap", "a number in [0, 1)", v);
            }
            break;
        }
        case OPT_FOV_WIDTH:
            if (parse_pos(f, v, &a->fov_width_m))
                return HV_EXIT_USAGE;
            break;
        case OPT_FOV_OFFSET: {
            char *end = NULL;
            a->fov_offset_m = strtod(v, &end);
            if (end == v || *end != '\0' || !isfinite(a->fov_offset_m)) {
                return bad_value("--fov-offset", "a number (m)", v);
            }
            break;
        }
        case OPT_HORIZON:
            if (parse_pos(f, v, &a->horizon_m))
                return HV_EXIT_USAGE;
            break;
        case OPT_COMMIT:
            if (parse_pos(f, v, &a->commit_m))
                return HV_EXIT_USAGE;
            break;
        case OPT_ROW_LENGTH:
            if (parse_pos(f, v, &a->row_length_m))
                return HV_EXIT_USAGE;
            break;
        default: return option_error(opt, argv);
        }
    }
    if (optind < argc) {
        return usage_error(argv[optind], "unexpected argument");
    }
    const char *missing = !a->config   ? "--config"
                          : !a->fruits ? "--fruits"
                          : !a->method ? "--method"
                          : !a->out    ? "--out"
                                       : NULL;
    if (missing != NULL) {
        return usage_error(missing, "required");
    }
    if (strcmp(a->method, "milp") != 0 && strcmp(a->method, "fov") != 0 &&
        strcmp(a->method, "serial") != 0) {
        return bad_value("--method", "milp, fov or serial", a->method);
    }
    if (a->algorithm != NULL && strcmp(a->algorithm, "price") != 0 &&
        strcmp(a->algorithm, "compact") != 0) {
        return bad_value("--algorithm", "price or compact", a->algorithm);
    }
    if (a->algorithm != NULL && strcmp(a->method, "milp") != 0) {
        return usage_error("--algorithm", "applies to --method milp only");
    }
    if (a->threads != 0 && strcmp(a->method, "milp") != 0) {
        return usage_error("--threads", "applies to --method milp only");
    }
    if (a->horizon_m > 0 && strcmp(a->method, "milp") != 0) {
        return usage_error("--horizon", "applies to --method milp only");
    }
    if (a->compare_single && !(a->horizon_m > 0)) {
        return usage_error("--compare-single", "needs --horizon");
    }
    if (a->commit_m > 0 && !(a->horizon_m > 0)) {
        return usage_error("--commit", "needs --horizon");
    }
    if (a->horizon_m > 0 && a->commit_m > a->horizon_m) {
        return usage_error("--commit", "must not exceed --horizon");
    }
    if (a->export_lp != NULL && (strcmp(a->method, "milp") != 0 || a->horizon_m > 0)) {
        return usage_error("--export-lp", "applies to a single-window --method milp");
    }
    return 0;
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

static int run_plan(const args_t *a)
{
    char err[512] = "";
    hv_config_t cfg;
    if (hv_config_load(a->config, &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-plan: %s\n", err);
        return HV_EXIT_USAGE;
    }
    hv_ik_model_t ik;
    hv_pick_model_t model;
    hv_status_t mst = hv_pick_model_ik(&cfg, &ik, &model);
    if (mst != HV_OK) {
        fprintf(stderr, "harvest-plan: %s: an arm reaches none of its fruit area (%s)\n", a->config,
                hv_status_name(mst));
        return HV_EXIT_USAGE;
    }
    hv_instance_params_t params;
    hv_instance_params_from_config(&cfg, &model, &params);
    if (a->row_length_m > 0) {
        params.row_length_m = a->row_length_m;
        params.travel_time_s = hv_instance_params_course_m(&params) / cfg.vehicle_speed_mps;
    }
    hv_fruitmap_t map = {0, NULL};
    hv_instance_t inst;
    memset(&inst, 0, sizeof inst);
    hv_assignment_t sol = {0, NULL};
    unsigned char *passes = NULL;
    hv_plan_t plan;
    memset(&plan, 0, sizeof plan);
    int rc = check_table(a->left, HV_SIDE_LEFT, &cfg);
    if (rc == 0) {
        rc = check_table(a->right, HV_SIDE_RIGHT, &cfg);
    }
    if (rc == 0) {
        hv_fruitmap_limits_t lim;
        hv_fruitmap_limits_from_config(&cfg, params.row_start_m, params.row_length_m, &lim);
        if (hv_fruitmap_load(a->fruits, &lim, &map, err, sizeof err) != HV_OK) {
            fprintf(stderr, "harvest-plan: %s\n", err);
            rc = HV_EXIT_USAGE;
        }
    }
    if (rc == 0) {
        hv_diag_t d;
        memset(&d, 0, sizeof d);
        double t0 = now_s();
        hv_status_t st = hv_instance_build(&params, map.fruits, map.n, &model, &inst, &d);
        if (st != HV_OK) {
            fprintf(stderr, "harvest-plan: instance: %s: %s\n", d.field, d.message);
            rc = HV_EXIT_USAGE;
        } else if (!a->quiet) {
            size_t nl = 0;
            for (size_t f = 0; f < map.n; ++f) {
                nl += map.fruits[f].side == HV_SIDE_LEFT;
            }
            char why[128];
            why_counts(&inst, why, sizeof why);
            fprintf(stderr,
                    "harvest-plan: %zu fruits (%zu left, %zu right), %zu candidate stops "
                    "(%.2f to %.2f m), %zu reachable pairs, %zu unreachable fruits%s "
                    "(%.3f s)\n",
                    map.n, nl, map.n - nl, inst.n_stops, inst.stop_y_m[0],
                    inst.stop_y_m[inst.n_stops - 1], inst.n_pairs,
                    hv_instance_unreachable_count(&inst), why, now_s() - t0);
        }
    }
    if (rc == 0 && hv_assignment_alloc(&sol, inst.n_fruits) != HV_OK) {
        fprintf(stderr, "harvest-plan: out of memory\n");
        rc = HV_EXIT_FAILURE;
    }

    /* the plan names its inputs relative to its own folder (plan_paths.h) */
    char inputs[4][HV_PLAN_PATH_LEN] = {{0}};
    const char *given[4] = {a->fruits, a->left, a->right, a->config};
    for (int k = 0; k < 4 && rc == 0; ++k) {
        if (given[k] != NULL && /* tables are optional */
            hv_plan_input_relative(a->out, given[k], inputs[k], sizeof inputs[k], err,
                                   sizeof err) != HV_OK) {
            fprintf(stderr, "harvest-plan: %s\n", err);
            rc = HV_EXIT_FAILURE;
        }
    }
    hv_plan_meta_t meta;
    memset(&meta, 0, sizeof meta);
    meta.method = a->method;
    meta.fruit_map = inputs[0];
    meta.cost_table_left = inputs[1]; /* "" when none was given */
    meta.cost_table_right = inputs[2];
    meta.config = inputs[3];
    meta.pick_time = hv_pick_model_name(&cfg);
    meta.params = params;
    meta.vehicle_speed_mps = cfg.vehicle_speed_mps;
    meta.time_limit_s = a->time_limit_s;
    meta.gap = -1.0;

    hv_milp_options_t mopt;
    hv_milp_options_default(&mopt);
    mopt.time_limit_s = a->time_limit_s;
    mopt.rel_gap = a->gap;
    mopt.verbose = a->quiet ? 0 : 1;
    mopt.export_lp_path = a->export_lp;
    if (a->algorithm != NULL) {
        mopt.algorithm =
            strcmp(a->algorithm, "compact") == 0 ? HV_MILP_ALG_COMPACT : HV_MILP_ALG_PRICE;
    }
    if (a->threads != 0) {
        mopt.helper_thread = a->threads == 2;
        mopt.tree_threads = a->threads;
    }
    mopt.stop = interrupted;

    if (rc == 0) {
        double t0 = now_s();
        hv_status_t st = HV_OK;
        if (strcmp(a->method, "fov") == 0) {
            hv_fov_stats_t fs;
            hv_config_t fcfg = cfg;
            if (a->fov_width_m > 0) {
                fcfg.fov_width_m = a->fov_width_m;
            }
            if (!isnan(a->fov_offset_m)) {
                fcfg.fov_offset_m = a->fov_offset_m;
            }
            hv_fov_params_t fp;
            hv_fov_params_from_config(&fcfg, &fp);
            st = hv_fov_solve_params(&inst, &fp, &sol, &fs);
            meta.solver_status = "heuristic";
            meta.time_limit_s = 0.0;
            if (st == HV_OK && !a->quiet) {
                fprintf(stderr,
                        "harvest-plan: fov width %.3f m, offset %.3f m: %zu windows, %zu stops, "
                        "%zu fruits moved (in view, out of reach of their stop), %zu extra "
                        "stops\n",
                        fcfg.fov_width_m, fcfg.fov_offset_m, fs.windows, fs.stops, fs.moved,
                        fs.extra_stops);
            }
        } else if (strcmp(a->method, "serial") == 0) {
            hv_serial_result_t sr;
            passes = malloc(inst.n_fruits ? inst.n_fruits : 1);
            st = passes ? hv_serial_solve(&inst, &mopt, &sol, passes, &sr) : HV_ERR_PLAN_NOMEM;
            if (st == HV_OK) {
                meta.solver_status = sr.optimal ? "optimal" : "feasible";
                meta.gap = sr.gap;
                meta.nodes = sr.nodes;
            }
        } else if (a->horizon_m > 0) {
            hv_horizon_options_t ho;
            hv_horizon_options_default(&ho);
            ho.window_m = a->horizon_m;
            ho.commit_m = a->commit_m > 0 ? a->commit_m : a->horizon_m / 2.0;
            ho.milp = mopt;
            ho.milp.verbose = 0;
            ho.progress = a->quiet ? NULL : stderr;
            hv_horizon_result_t hr;
            st = hv_horizon_solve(&inst, &ho, &sol, &hr);
            if (st == HV_OK) {
                /* each window may be optimal, the row as a whole is not proven */
                meta.solver_status = "heuristic";
                meta.nodes = hr.nodes;
                meta.horizon.used = 1;
                meta.horizon.window_m = ho.window_m;
                meta.horizon.commit_m = ho.commit_m;
                meta.horizon.windows = hr.windows;
                meta.horizon.windows_optimal = hr.windows_optimal;
            }
            if (st == HV_OK && a->compare_single) {
                st = compare_single(&inst, &mopt, &sol);
            }
        } else {
            hv_assignment_t warm = {0, NULL};
            hv_milp_result_t mr;
            memset(&mr, 0, sizeof mr);
            st = hv_assignment_alloc(&warm, inst.n_fruits);
            if (st == HV_OK) {
                st = hv_heuristic_solve(&inst, &warm);
            }
            if (st == HV_OK) {
                st = hv_milp_solve(&inst, &mopt, &warm, &sol, &mr);
            }
            hv_assignment_free(&warm);
            if (st == HV_OK && mr.status != HV_SOLVE_OPTIMAL && mr.status != HV_SOLVE_FEASIBLE) {
                fprintf(stderr, "harvest-plan: milp: %s after %.1f s: no plan written\n",
                        solve_status_name(mr.status), mr.runtime_s);
                rc = HV_EXIT_PLAN_NO_SOLUTION;
            } else if (st == HV_OK) {
                meta.solver_status = solve_status_name(mr.status);
                meta.gap = mr.gap;
                meta.nodes = mr.nodes;
            }
        }
        meta.runtime_s = now_s() - t0;
        if (interrupted(NULL)) {
            fprintf(stderr, "harvest-plan: interrupted after %.1f s: %s\n", meta.runtime_s,
                    rc == 0 && st == HV_OK ? "writing the best plan so far" : "no plan");
        }
        if (st != HV_OK && rc == 0) {
            fprintf(stderr, "harvest-plan: %s: solve failed: %s\n", a->method,
                    hv_plan_status_name(st));
            rc = st == HV_ERR_PLAN_NO_SOLUTION ? HV_EXIT_PLAN_NO_SOLUTION : HV_EXIT_FAILURE;
        }
    }
    if (rc == 0) {
        hv_status_t st = hv_plan_build(&inst, &sol, passes, &meta, &plan);
        if (st != HV_OK) {
            fprintf(stderr, "harvest-plan: building the plan: %s\n", hv_plan_status_name(st));
            rc = HV_EXIT_FAILURE;
        }
    }
    if (rc == 0) {
        /* the independent checker re-reads every input file */
        hv_status_t st = hv_plan_check_files(&plan, NULL, a->config, a->left, a->right, a->fruits,
                                             err, sizeof err);
        if (st != HV_OK) {
            fprintf(stderr, "harvest-plan: internal error, plan not written: %s\n", err);
            rc = HV_EXIT_PLAN_CHECK;
        }
    }
    if (rc == 0 && hv_plan_save(a->out, &plan, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-plan: %s\n", err);
        rc = HV_EXIT_FAILURE;
    }
    if (rc == 0 && !a->quiet) {
        char gap[32] = "n/a";
        if (plan.gap >= 0) {
            snprintf(gap, sizeof gap, "%.4f%%", 100.0 * plan.gap);
        }
        fprintf(stderr,
                "harvest-plan: %s %s (gap %s): makespan %.3f s = picks %.3f + stops %zu x %.1f "
                "+ travel %.1f; %zu fruits, %zu unreachable, %.4f fruit/s; %.2f s -> %s\n",
                plan.method, plan.solver_status, gap, plan.makespan_s, plan.pick_time_s,
                plan.n_stops, plan.stop_penalty_s, plan.total_travel_time_s, plan.fruits_planned,
                plan.fruits_unreachable, plan.throughput_fruit_per_s, plan.runtime_s, a->out);
    }
    if (rc == 0 && interrupted(NULL) && strcmp(plan.solver_status, "optimal") != 0) {
        rc = HV_EXIT_PLAN_INTERRUPTED; /* a proof that came in time lost nothing */
    }
    hv_plan_free(&plan);
    free(passes);
    hv_assignment_free(&sol);
    hv_instance_free(&inst);
    hv_fruitmap_free(&map);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "check") == 0) {
        return run_check(argc, argv);
    }
    args_t a;
    int rc = parse_args(argc, argv, &a);
    if (rc != 0) {
        return rc == 1 ? 0 : rc;
    }
    catch_stop_signals();
    return run_plan(&a);
}
