/* harvest-plan's command line (plan_args.h). */
#define _POSIX_C_SOURCE 200809L
#include "plan_args.h"

#include <getopt.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/cli.h"
#include "hv/milp.h"
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

/* getopt_long's verdict on argv[optind - 1] when it returned ':' or '?'. */
static int option_error(int opt, char **argv)
{
    hv_cli_option_error(k_prog, opt, optopt, argv[optind - 1]);
    return HV_EXIT_USAGE;
}

int plan_args_parse_check(int argc, char **argv, plan_check_args_t *c)
{
    enum { CK_CONFIG = 256, CK_LEFT, CK_RIGHT, CK_FRUITS, CK_QUIET };
    static const struct option longopts[] = {
        {"config", required_argument, NULL, CK_CONFIG},
        {"left", required_argument, NULL, CK_LEFT},
        {"right", required_argument, NULL, CK_RIGHT},
        {"fruits", required_argument, NULL, CK_FRUITS},
        {"quiet", no_argument, NULL, CK_QUIET},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    memset(c, 0, sizeof *c);
    int opt;
    opterr = 0;
    optind = 2; /* after "check" */
    while ((opt = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        switch (opt) {
        case 'h': fputs(k_usage, stdout); return 1;
        case 'V': printf("harvest-plan %s\n", HV_VERSION); return 1;
        case CK_QUIET: c->quiet = 1; break;
        case CK_CONFIG: c->config = optarg; break;
        case CK_LEFT: c->left = optarg; break;
        case CK_RIGHT: c->right = optarg; break;
        case CK_FRUITS: c->fruits = optarg; break;
        default: return option_error(opt, argv);
        }
    }
    if (optind < argc) {
        c->plan = argv[optind++];
    }
    if (optind < argc) {
        return usage_error(argv[optind], "more than one plan file");
    }
    if (c->plan == NULL) {
        return usage_error("check", "needs a PLAN.json");
    }
    return 0;
}

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

static const struct option k_longopts[] = {
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

/* An option that stores its argument in a member of plan_args_t. */
typedef struct opt_member {
    int opt;
    size_t at; /* offsetof the member */
} opt_member_t;

/* The options whose text is kept as given (a const char * member). */
static const opt_member_t k_text_opts[] = {
    {OPT_CONFIG, offsetof(plan_args_t, config)},
    {OPT_LEFT, offsetof(plan_args_t, left)},
    {OPT_RIGHT, offsetof(plan_args_t, right)},
    {OPT_FRUITS, offsetof(plan_args_t, fruits)},
    {OPT_METHOD, offsetof(plan_args_t, method)},
    {OPT_OUT, offsetof(plan_args_t, out)},
    {OPT_EXPORT_LP, offsetof(plan_args_t, export_lp)},
    {OPT_ALGORITHM, offsetof(plan_args_t, algorithm)},
};

/* The options that take a positive number (a double member). */
static const opt_member_t k_positive_opts[] = {
    {OPT_TIME_LIMIT, offsetof(plan_args_t, time_limit_s)},
    {OPT_FOV_WIDTH, offsetof(plan_args_t, fov_width_m)},
    {OPT_HORIZON, offsetof(plan_args_t, horizon_m)},
    {OPT_COMMIT, offsetof(plan_args_t, commit_m)},
    {OPT_ROW_LENGTH, offsetof(plan_args_t, row_length_m)},
};

/* The member of `a` that option `opt` of `table` stores into, or NULL. */
static void *opt_member(plan_args_t *a, const opt_member_t *table, size_t n, int opt)
{
    for (size_t i = 0; i < n; ++i) {
        if (table[i].opt == opt) {
            return (char *)a + table[i].at;
        }
    }
    return NULL;
}

/* One option `opt` with its argument `v` (`flag`: the option as given, --name even when
 * written --name=value): 0, 1 when it printed what was asked (help, version), else
 * HV_EXIT_USAGE with a message. */
static int parse_option(int opt, const char *v, const char *flag, plan_args_t *a, char **argv)
{
    const char **text = opt_member(a, k_text_opts, sizeof k_text_opts / sizeof *k_text_opts, opt);
    double *positive =
        opt_member(a, k_positive_opts, sizeof k_positive_opts / sizeof *k_positive_opts, opt);
    char *end = NULL;
    if (text != NULL) {
        *text = v;
        return 0;
    }
    if (positive != NULL) {
        return parse_pos(flag, v, positive);
    }
    switch (opt) {
    case 'h': fputs(k_usage, stdout); return 1;
    case 'V': printf("harvest-plan %s\n", HV_VERSION); return 1;
    case OPT_HELP_PARAMS: hv_milp_params_write(stdout); return 1;
    case OPT_QUIET: a->quiet = 1; return 0;
    case OPT_COMPARE_SINGLE: a->compare_single = 1; return 0;
    case OPT_THREADS:
        if (strcmp(v, "1") != 0 && strcmp(v, "2") != 0) {
            return bad_value("--threads", "1 or 2", v);
        }
        a->threads = v[0] - '0';
        return 0;
    case OPT_GAP:
        a->gap = strtod(v, &end);
        if (end == v || *end != '\0' || !isfinite(a->gap) || a->gap < 0 || a->gap >= 1) {
            return bad_value("--gap", "a number in [0, 1)", v);
        }
        return 0;
    case OPT_FOV_OFFSET:
        a->fov_offset_m = strtod(v, &end);
        if (end == v || *end != '\0' || !isfinite(a->fov_offset_m)) {
            return bad_value("--fov-offset", "a number (m)", v);
        }
        return 0;
    default: return option_error(opt, argv);
    }
}

/* The options together: what is required, and what applies only with what. */
static int check_args(const plan_args_t *a)
{
    const char *missing = !a->config   ? "--config"
                          : !a->fruits ? "--fruits"
                          : !a->method ? "--method"
                          : !a->out    ? "--out"
                                       : NULL;
    if (missing != NULL) {
        return usage_error(missing, "required");
    }
    int milp = strcmp(a->method, "milp") == 0;
    if (!milp && strcmp(a->method, "fov") != 0 && strcmp(a->method, "serial") != 0) {
        return bad_value("--method", "milp, fov or serial", a->method);
    }
    if (a->algorithm != NULL && strcmp(a->algorithm, "price") != 0 &&
        strcmp(a->algorithm, "compact") != 0) {
        return bad_value("--algorithm", "price or compact", a->algorithm);
    }
    if (a->algorithm != NULL && !milp) {
        return usage_error("--algorithm", "applies to --method milp only");
    }
    if (a->threads != 0 && !milp) {
        return usage_error("--threads", "applies to --method milp only");
    }
    if (a->horizon_m > 0 && !milp) {
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
    if (a->export_lp != NULL && (!milp || a->horizon_m > 0)) {
        return usage_error("--export-lp", "applies to a single-window --method milp");
    }
    return 0;
}

int plan_args_parse(int argc, char **argv, plan_args_t *a)
{
    memset(a, 0, sizeof *a);
    a->time_limit_s = 60.0;
    a->gap = 1e-6;
    a->fov_offset_m = NAN; /* 0 width and NAN offset: the config's */
    opterr = 0;
    int opt, idx = 0;
    while ((opt = getopt_long(argc, argv, ":h", k_longopts, &idx)) != -1) {
        char flag[32];
        snprintf(flag, sizeof flag, "--%s", opt >= OPT_CONFIG ? k_longopts[idx].name : "");
        int rc = parse_option(opt, optarg, flag, a, argv);
        if (rc != 0) {
            return rc;
        }
    }
    if (optind < argc) {
        return usage_error(argv[optind], "unexpected argument");
    }
    return check_args(a);
}
