/* bench_milp: the paper's experiment (DESIGN §10) on the MILP, the heuristic and the
 * baselines, with the plain model measured in the same run as the reference.
 * Run `bench_milp --help`.
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_instances.h"
#include "hv/baselines.h"
#include "hv/file_io.h"
#include "hv/milp.h"
#include "hv/plan_eval.h"

#ifndef HV_BENCH_DEFAULT_CONFIG
#define HV_BENCH_DEFAULT_CONFIG "config/harvest.cfg"
#endif

#define MAX_ALPHAS 16
#define MAX_SEEDS  100

static void usage(FILE *f)
{
    fprintf(
        f,
        "usage: bench_milp [options]\n"
        "The paper's experiment: m_L = 50, m_R = alpha * 50, N = 201 stops, real arm costs.\n"
        "Per alpha: MILP solve times, proven optima, gaps, stops and throughput (fruits / T)\n"
        "against FOV and Serial, and the plain model (no improvements) as the reference.\n"
        "  --config PATH        harvest config (default %s)\n"
        "  --alphas A,B,..      alphas (default 0.25,0.4,1,2.5,4)\n"
        "  --seeds N            seeds per alpha (default 10)\n"
        "  --first-seed N       the first seed (default 1): --first-seed 4 --seeds 1 runs seed 4\n"
        "  --time-limit S       MILP limit per instance, s (default 10: DESIGN's max is 7 s)\n"
        "  --plain-seeds N      seeds per alpha also solved by the plain model (default 2)\n"
        "  --plain-limit S      its limit, s (default 10)\n"
        "  --set KEY=VALUE      an option of the MILP run (repeatable): a row of the\n"
        "                       table harvest-plan --help-params prints\n"
        "  --no-baselines       skip FOV and Serial\n"
        "  --given-plan         also solve each instance again from the plan its MILP run\n"
        "                       found, and print that time: what the proof alone takes\n"
        "                       once the plan is known (the rest waited for the plan)\n"
        "  -v                   solver progress on stderr\n"
        "  --help               this text\n",
        HV_BENCH_DEFAULT_CONFIG);
}

/* The model as the paper writes it, none of the solver's choices: the reference in the
 * same run. */
static void plain_options(hv_milp_options_t *o, double limit_s)
{
    hv_milp_options_default(o);
    o->time_limit_s = limit_s;
    o->heuristic_incumbent = 0;
    o->ms_granularity = 0;
    o->decompose = 0;
    o->glpk_cuts = HV_MILP_CUT_GMI | HV_MILP_CUT_MIR | HV_MILP_CUT_COVER | HV_MILP_CUT_CLIQUE;
    o->pcost_branching = 0;
    o->link_disaggregated = 0;
    o->pattern_cuts = -1;
    o->polish_work = 0;
    o->algorithm = HV_MILP_ALG_COMPACT;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, size_t n)
{
    qsort(v, n, sizeof *v, cmp_double);
    return n == 0 ? NAN : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

static double max_of(const double *v, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; ++i) {
        m = fmax(m, v[i]);
    }
    return m;
}

static const char *status_word(hv_solve_status_t s)
{
    switch (s) {
    case HV_SOLVE_OPTIMAL: return "optimal";
    case HV_SOLVE_FEASIBLE: return "feasible";
    case HV_SOLVE_INFEASIBLE: return "infeasible";
    case HV_SOLVE_NO_SOLUTION: return "no-solution";
    default: return "error";
    }
}

typedef struct row_stats {
    double t_milp[MAX_SEEDS], t_plain[MAX_SEEDS], t_given[MAX_SEEDS];
    size_t n, n_opt, n_plain, n_plain_opt, n_given, n_given_opt;
    double stops_milp, stops_fov, thr_milp, thr_fov, thr_serial, gap_max, gap_sum, plain_gap_max;
    double heur_excess_max; /* heuristic T over the MILP's T */
    size_t n_serial;
} row_stats_t;

int main(int argc, char **argv)
{
    const char *cfg_path = HV_BENCH_DEFAULT_CONFIG;
    double alphas[MAX_ALPHAS] = {0.25, 0.4, 1.0, 2.5, 4.0};
    size_t n_alpha = 5, n_seeds = 10, plain_seeds = 2, first_seed = 1;
    double plain_limit = 10.0;
    int baselines = 1, given_plan = 0;
    hv_milp_options_t mo;
    hv_milp_options_default(&mo);
    mo.time_limit_s = 10.0;
    enum {
        O_NO_BASELINES = 256,
        O_GIVEN_PLAN,
        O_CONFIG,
        O_ALPHAS,
        O_SEEDS,
        O_PLAIN_SEEDS,
        O_FIRST_SEED,
        O_TIME_LIMIT,
        O_PLAIN_LIMIT,
        O_SET
    };
    static const struct option longopts[] = {
        {"no-baselines", no_argument, NULL, O_NO_BASELINES},
        {"given-plan", no_argument, NULL, O_GIVEN_PLAN},
        {"config", required_argument, NULL, O_CONFIG},
        {"alphas", required_argument, NULL, O_ALPHAS},
        {"seeds", required_argument, NULL, O_SEEDS},
        {"plain-seeds", required_argument, NULL, O_PLAIN_SEEDS},
        {"first-seed", required_argument, NULL, O_FIRST_SEED},
        {"time-limit", required_argument, NULL, O_TIME_LIMIT},
        {"plain-limit", required_argument, NULL, O_PLAIN_LIMIT},
        {"set", required_argument, NULL, O_SET},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    opterr = 0;
    int opt, idx = 0;
    while ((opt = getopt_long(argc, argv, ":hv", longopts, &idx)) != -1) {
        const char *v = optarg, *a = opt >= O_NO_BASELINES ? longopts[idx].name : "";
        switch (opt) {
        case 'h': usage(stdout); return 0;
        case 'v': mo.verbose = mo.verbose + 1; break;
        case O_NO_BASELINES: baselines = 0; break;
        case O_GIVEN_PLAN: given_plan = 1; break;
        case O_CONFIG: cfg_path = v; break;
        case O_ALPHAS: {
            n_alpha = 0;
            char buf[256];
            snprintf(buf, sizeof buf, "%s", v);
            for (char *tok = strtok(buf, ","); tok && n_alpha < MAX_ALPHAS;
                 tok = strtok(NULL, ",")) {
                char *end;
                alphas[n_alpha] = strtod(tok, &end);
                if (*end != '\0' || !(alphas[n_alpha] > 0)) {
                    fprintf(stderr, "bench_milp: --alphas: bad value '%s'\n", tok);
                    return 2;
                }
                n_alpha++;
            }
            break;
        }
        case O_SEEDS:
        case O_PLAIN_SEEDS: {
            long n = strtol(v, NULL, 10);
            if (n < 0 || n > MAX_SEEDS) {
                fprintf(stderr, "bench_milp: --%s: 0..%d\n", a, MAX_SEEDS);
                return 2;
            }
            *(opt == O_SEEDS ? &n_seeds : &plain_seeds) = (size_t)n;
            break;
        }
        case O_FIRST_SEED: {
            char *end;
            long n = strtol(v, &end, 10);
            if (*end != '\0' || n < 1) {
                fprintf(stderr, "bench_milp: --first-seed: a whole number >= 1, not '%s'\n", v);
                return 2;
            }
            first_seed = (size_t)n;
            break;
        }
        case O_TIME_LIMIT:
        case O_PLAIN_LIMIT: {
            double t = strtod(v, NULL);
            if (!(t > 0)) {
                fprintf(stderr, "bench_milp: --%s: must be > 0\n", a);
                return 2;
            }
            *(opt == O_TIME_LIMIT ? &mo.time_limit_s : &plain_limit) = t;
            break;
        }
        case O_SET:
            if (hv_milp_option_set(&mo, v) != HV_OK) {
                fprintf(stderr, "bench_milp: --set: not an option or out of its range: '%s'\n", v);
                return 2;
            }
            break;
        default:
            fprintf(stderr, "bench_milp: %s %s (see --help)\n",
                    opt == ':' ? "a value is needed for" : "unknown option", argv[optind - 1]);
            return 2;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "bench_milp: unexpected argument %s (see --help)\n", argv[optind]);
        return 2;
    }

    hv_config_t cfg;
    char err[256];
    if (hv_config_load(cfg_path, &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "bench_milp: %s\n", err);
        return 1;
    }
    bench_model_t pm;
    if (bench_model_init(&cfg, &pm) != 0) {
        return 1;
    }
    printf("# MILP options: algorithm=%s disaggregated=%d heuristic=%d "
           "ms=%d decompose=%d cuts=%d pcost=%d limit=%.0fs; price: "
           "sr_cuts=%d/%d sr_purge=%d cover_rows=%d pseudocost=%d tree_threads=%d "
           "helper_thread=%d ascent_steps=%d auto_smoothing=%d interval_branching=%d "
           "iv_pseudocost=%d tail_off_ms=%d tail_off_open=%d binding_splits=%d "
           "balance_workers=%d warm_transfer=%d rins_every=%d region_stops=%d\n",
           mo.algorithm == HV_MILP_ALG_PRICE ? "price" : "compact", mo.link_disaggregated,
           mo.heuristic_incumbent, mo.ms_granularity, mo.decompose, mo.glpk_cuts,
           mo.pcost_branching, mo.time_limit_s, mo.sr_cuts, mo.sr_cuts_large, mo.sr_purge,
           mo.cover_rows, mo.pseudocost, mo.tree_threads, mo.helper_thread, mo.ascent_steps,
           mo.auto_smoothing, mo.interval_branching, mo.iv_pseudocost, mo.tail_off_ms,
           mo.tail_off_open, mo.binding_splits, mo.balance_workers, mo.warm_transfer, mo.rins_every,
           mo.region_stops);
    printf("%-5s %-4s %4s %6s | %-9s %9s %9s %8s %7s %7s %5s | %9s %9s | %-9s %8s %7s | %9s %5s | "
           "%9s\n",
           "alpha", "seed", "nf", "pairs", "milp", "T_s", "bound_s", "gap", "time_s", "nodes",
           "stops", "root_s", "heur_T_s", "plain", "plain_gap", "plain_s", "fov_T_s", "stops",
           "serial_T");
    row_stats_t rows[MAX_ALPHAS];
    memset(rows, 0, sizeof rows);
    int failures = 0;
    for (size_t ai = 0; ai < n_alpha; ++ai) {
        row_stats_t *r = &rows[ai];
        size_t n_right = (size_t)lround(alphas[ai] * 50.0);
        for (size_t seed = 0; seed < n_seeds; ++seed) {
            hv_instance_t inst;
            if (bench_instance_make(&cfg, &pm, 50, n_right, first_seed + seed, &inst) != 0) {
                return 1;
            }
            size_t nf = inst.n_fruits - hv_instance_unreachable_count(&inst);
            hv_assignment_t out, tmp;
            hv_assignment_alloc(&out, inst.n_fruits);
            hv_assignment_alloc(&tmp, inst.n_fruits);
            hv_milp_result_t res;
            hv_eval_t ev;
            memset(&ev, 0, sizeof ev);
            if (hv_milp_solve(&inst, &mo, NULL, &out, &res) != HV_OK) {
                fprintf(stderr, "bench_milp: solver error on alpha %g seed %zu\n", alphas[ai],
                        first_seed + seed);
                failures++;
                hv_instance_free(&inst);
                continue;
            }
            hv_assignment_eval(&inst, &out, &ev);
            r->t_milp[r->n] = res.runtime_s;
            r->n++;
            r->n_opt += res.status == HV_SOLVE_OPTIMAL;
            r->gap_max = fmax(r->gap_max, res.gap);
            r->gap_sum += res.gap;
            r->stops_milp += (double)ev.stops;
            r->thr_milp += (double)nf / res.objective_s;
            if (isfinite(res.incumbent_s)) {
                r->heur_excess_max =
                    fmax(r->heur_excess_max, res.incumbent_s / res.objective_s - 1.0);
            }
            printf("%-5g %-4zu %4zu %6zu | %-9s %9.3f %9.3f %8.2e %7.2f %7ld %5zu | %9.3f %9.3f |",
                   alphas[ai], first_seed + seed, nf, inst.n_pairs, status_word(res.status),
                   res.objective_s, res.bound_s, res.gap, res.runtime_s, res.nodes, ev.stops,
                   res.root_bound_s, res.incumbent_s);
            if (seed < plain_seeds) {
                hv_milp_options_t po;
                plain_options(&po, plain_limit);
                hv_milp_result_t pr;
                if (hv_milp_solve(&inst, &po, NULL, &tmp, &pr) == HV_OK) {
                    r->t_plain[r->n_plain++] = pr.runtime_s;
                    r->n_plain_opt += pr.status == HV_SOLVE_OPTIMAL;
                    /* the plain run's gap against the best bound either run proved */
                    double b = fmax(pr.bound_s, res.bound_s);
                    double g =
                        isfinite(pr.objective_s) ? (pr.objective_s - b) / pr.objective_s : INFINITY;
                    r->plain_gap_max = fmax(r->plain_gap_max, g);
                    printf(" %-9s %8.2e %7.2f |", status_word(pr.status), g, pr.runtime_s);
                }
            } else {
                printf(" %-9s %8s %7s |", "-", "-", "-");
            }
            if (baselines) {
                hv_eval_t fe;
                double st_serial = NAN;
                if (hv_fov_solve(&inst, HV_FOV_DEFAULT_WIDTH_M, &tmp, NULL) == HV_OK &&
                    hv_assignment_eval(&inst, &tmp, &fe) == HV_OK) {
                    r->stops_fov += (double)fe.stops;
                    r->thr_fov += (double)nf / fe.makespan_s;
                    printf(" %9.3f %5zu |", fe.makespan_s, fe.stops);
                }
                unsigned char *passes = malloc(inst.n_fruits + 1);
                hv_serial_result_t sr;
                hv_milp_options_t so;
                hv_milp_options_default(&so);
                so.time_limit_s = mo.time_limit_s;
                if (passes != NULL && hv_serial_solve(&inst, &so, &tmp, passes, &sr) == HV_OK) {
                    st_serial = sr.makespan_s;
                    r->thr_serial += (double)nf / sr.makespan_s;
                    r->n_serial++;
                }
                free(passes);
                printf(" %9.3f", st_serial);
            }
            printf("\n");
            if (given_plan && isfinite(res.objective_s)) {
                /* the same solve with its own plan as the incumbent from the start */
                hv_milp_result_t gr;
                if (hv_milp_solve(&inst, &mo, &out, &tmp, &gr) == HV_OK) {
                    r->t_given[r->n_given++] = gr.runtime_s;
                    r->n_given_opt += gr.status == HV_SOLVE_OPTIMAL;
                    printf("#   given its plan (%.3f s): %s %9.3f, gap %8.2e in %7.2f s, %ld "
                           "nodes\n",
                           res.objective_s, status_word(gr.status), gr.objective_s, gr.gap,
                           gr.runtime_s, gr.nodes);
                } else {
                    fprintf(stderr,
                            "bench_milp: solver error on alpha %g seed %zu, given its "
                            "plan\n",
                            alphas[ai], first_seed + seed);
                    failures++;
                }
            }
            fflush(stdout);
            hv_assignment_free(&out);
            hv_assignment_free(&tmp);
            hv_instance_free(&inst);
        }
    }

    printf("\n# Summary per alpha (times in s; throughput in fruits/s; plain = the model as the "
           "paper writes it: aggregated linking, GLPK cuts on, no incumbent, %.0f s limit)\n",
           plain_limit);
    printf("%-5s | %7s %7s %7s %8s %8s | %5s %8s | %5s %8s %9s | %9s %5s | %6s %7s %9s\n", "alpha",
           "median", "max", "optimal", "mean_gap", "max_gap", "stops", "thr", "FOVst", "FOV_thr",
           "MILP/FOV", "serial", "dual/s", "plain", "p_med", "p_max_gap");
    for (size_t ai = 0; ai < n_alpha; ++ai) {
        row_stats_t *r = &rows[ai];
        double n = (double)(r->n ? r->n : 1);
        double tmax = max_of(r->t_milp, r->n);
        size_t np = r->n_plain;
        double pmed = median(r->t_plain, np);
        /* the baselines' and the plain model's columns read "-" when they were not run */
        char fov[64] = "    -        -         -", serial[64] = "        -     -",
             plain[64] = " -          -         -";
        if (r->thr_fov > 0) {
            snprintf(fov, sizeof fov, "%5.2f %8.4f %+8.1f%%", r->stops_fov / n, r->thr_fov / n,
                     100.0 * (r->thr_milp / r->thr_fov - 1.0));
        }
        if (r->n_serial > 0) {
            snprintf(serial, sizeof serial, "%9.4f %4.2fx", r->thr_serial / (double)r->n_serial,
                     r->thr_milp / r->thr_serial);
        }
        if (np > 0) {
            snprintf(plain, sizeof plain, "%2zu/%-3zu %7.2f %9.2e", r->n_plain_opt, np, pmed,
                     r->plain_gap_max);
        }
        printf("%-5g | %7.3f %7.3f %3zu/%-3zu %8.2e %8.2e | %5.2f %8.4f | %s | %s | %s\n",
               alphas[ai], median(r->t_milp, r->n), tmax, r->n_opt, r->n, r->gap_sum / n,
               r->gap_max, r->stops_milp / n, r->thr_milp / n, fov, serial, plain);
    }
    if (given_plan) {
        printf("\n# Given its own plan from the start (the proof alone)\n%-5s | %7s %7s %7s\n",
               "alpha", "median", "max", "optimal");
        for (size_t ai = 0; ai < n_alpha; ++ai) {
            row_stats_t *r = &rows[ai];
            printf("%-5g | %7.3f %7.3f %3zu/%-3zu\n", alphas[ai], median(r->t_given, r->n_given),
                   max_of(r->t_given, r->n_given), r->n_given_opt, r->n_given);
        }
    }
    return failures ? 1 : 0;
}
