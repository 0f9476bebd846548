/* bench_milp: the MILP on paper-sized instances (DESIGN §10) in the product's model and in
 * the paper's, against HiGHS on the same exported model and against FOV and Serial, all
 * measured in the same run. Run `bench_milp --help`.
 */
#define _DEFAULT_SOURCE /* popen, mkstemps, getloadavg */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_instances.h"
#include "hv/baselines.h"
#include "hv/file_io.h"
#include "hv/fruit_map.h"
#include "hv/milp.h"
#include "hv/plan_eval.h"

#ifndef HV_BENCH_DEFAULT_CONFIG
#define HV_BENCH_DEFAULT_CONFIG "config/harvest.cfg"
#endif
#ifndef HV_BENCH_PYTHON
#define HV_BENCH_PYTHON "python3"
#endif
#ifndef HV_BENCH_HIGHS_SCRIPT
#define HV_BENCH_HIGHS_SCRIPT "bench/planner/highs_baseline.py"
#endif

#define MAX_ALPHAS 16
#define MAX_SEEDS  100
#define MAX_MODELS 2
#define N_SLOWEST  5 /* the slowest instances named per model */

/* HiGHS stops as ours does: our rel_gap, and an absolute gap just under 1 ms (the pick
 * costs are whole ms, so a plan within it of the bound is proven optimal: ms_granularity) */
#define HIGHS_ABS_GAP_S 0.000999

static void usage(FILE *f)
{
    fprintf(
        f,
        "usage: bench_milp [options]\n"
        "The paper's experiment, m_L = 50, m_R = alpha * 50 fruits uniform on a 2 m row with\n"
        "exact-IK whole-ms pick costs, in two models: the product's (config/harvest.cfg as\n"
        "harvest-plan builds it: stops beyond the row's ends, the whole pick cycle, tau = the\n"
        "drive's v/a) and the paper's (N = 201 stops on the row, one-way costs, tau =\n"
        "vehicle.stop_penalty). Per model and alpha: MILP solve times, proven optima, gaps,\n"
        "stops, throughput (fruits / T) against FOV and Serial, and HiGHS (highspy) on the\n"
        "model harvest-plan --export-lp writes, with the same stopping rule (relative gap\n"
        "rel_gap, absolute gap 0.999 ms: whole-ms costs), 2 threads and its own limit.\n"
        "The header and the end print the load average: other work on the machine slows it.\n"
        "  --config PATH        harvest config (default %s)\n"
        "  --models LIST        product,paper (default), or one of them\n"
        "  --alphas A,B,..      alphas (default 0.25,0.4,1,2.5,4)\n"
        "  --seeds N            seeds per alpha (default 10)\n"
        "  --first-seed N       the first seed (default 1): --first-seed 4 --seeds 1 runs seed 4\n"
        "  --quick              a smoke run: --alphas 0.25 --seeds 1 --highs-seeds 1\n"
        "                       --highs-limit 20 (options after it override it)\n"
        "  --time-limit S       MILP limit per instance, s (default: the config's\n"
        "                       online.horizon_limit_min, the least time the product gives\n"
        "                       a horizon of this size; DESIGN's max is 7 s)\n"
        "  --highs-seeds N      seeds per alpha also solved by HiGHS (default 2; 0 none)\n"
        "  --highs-limit S      its limit per instance, s (default 60)\n"
        "  --python PATH        the Python with highspy (default %s)\n"
        "  --set KEY=VALUE      an option of the MILP run (repeatable): a row of the\n"
        "                       table harvest-plan --help-params prints\n"
        "  --no-baselines       skip FOV and Serial\n"
        "  --export DIR         write each instance to DIR as <model>-a<alpha>-s<seed>.csv\n"
        "                       (its fruit map: harvest-plan --fruits) and .lp (the model\n"
        "                       HiGHS solves, as harvest-plan --export-lp writes it)\n"
        "  --given-plan         also solve each instance again from the plan its MILP run\n"
        "                       found, and print that time: what the proof alone takes\n"
        "                       once the plan is known (the rest waited for the plan)\n"
        "  -v                   solver progress on stderr\n"
        "  --help               this text\n",
        HV_BENCH_DEFAULT_CONFIG, HV_BENCH_PYTHON);
}

/* "# load average <when>: 1, 5, 15 min (N cores)": what else the machine runs */
static void print_load(const char *when)
{
    double la[3];
    if (getloadavg(la, 3) == 3) {
        printf("# load average %s: %.2f %.2f %.2f (1, 5, 15 min; %ld cores)\n", when, la[0], la[1],
               la[2], sysconf(_SC_NPROCESSORS_ONLN));
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of v[0 .. n) (sorts v); NAN when n = 0. */
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

/* One model's figures per alpha; the "all" row pools every alpha. */
typedef struct row_stats {
    double t_milp[MAX_ALPHAS * MAX_SEEDS], t_given[MAX_ALPHAS * MAX_SEEDS];
    /* instances HiGHS solved: its time and ours on them */
    double t_highs[MAX_ALPHAS * MAX_SEEDS], t_ours[MAX_ALPHAS * MAX_SEEDS];
    size_t n, n_opt, n_given, n_given_opt, n_highs, n_highs_opt, n_highs_disagree;
    double stops_milp, stops_fov, thr_milp, thr_fov, thr_serial, gap_max, gap_sum;
    double heur_excess_max; /* heuristic T over the MILP's T */
    size_t n_serial;
} row_stats_t;

/* What HiGHS reported on one model file. */
typedef struct highs_run {
    char status[32];
    double objective_s, bound_s, time_s;
    long nodes;
} highs_run_t;

typedef struct highs_cfg {
    const char *python;
    size_t seeds;
    double limit_s;
    double rel_gap;
    int broken; /* the first call failed: said once, not tried again */
} highs_cfg_t;

/* Solve the model file `lp` with HiGHS (highs_baseline.py). 0 on success. */
static int highs_solve(highs_cfg_t *h, const char *lp, highs_run_t *out)
{
    char cmd[4096];
    int len = snprintf(
        cmd, sizeof cmd, "'%s' '%s' '%s' --time-limit %g --threads 2 --rel-gap %g --abs-gap %g",
        h->python, HV_BENCH_HIGHS_SCRIPT, lp, h->limit_s, h->rel_gap, HIGHS_ABS_GAP_S);
    if (len < 0 || (size_t)len >= sizeof cmd) {
        return -1; /* paths too long: never run a cut command */
    }
    FILE *p = popen(cmd, "r");
    if (p == NULL) {
        return -1;
    }
    int n = fscanf(p, "%31s %lf %lf %lf %ld", out->status, &out->objective_s, &out->bound_s,
                   &out->time_s, &out->nodes);
    int rc = pclose(p);
    return n == 5 && rc == 0 ? 0 : -1;
}

/* HiGHS on the model file `lp`: 1 when it ran (out filled), 0 when not. */
static int highs_baseline(highs_cfg_t *h, const char *lp, highs_run_t *out)
{
    if (h->broken) {
        return 0;
    }
    if (highs_solve(h, lp, out) != 0) {
        fprintf(stderr,
                "bench_milp: HiGHS baseline SKIPPED: %s %s failed (highspy missing? "
                "scripts/setup.sh installs it)\n",
                h->python, HV_BENCH_HIGHS_SCRIPT);
        h->broken = 1;
        return 0;
    }
    return 1;
}

/* The model file of `inst` as harvest-plan --export-lp writes it (its default options):
 * with `dir`, dir/<name>.lp beside dir/<name>.csv, the instance's fruit map, both kept;
 * else a temporary file (*temp set: the caller removes it). 0 on success, else a message
 * on stderr. */
static int write_model(const char *dir, const char *name, const hv_instance_t *inst, char *lp,
                       size_t len, int *temp)
{
    *temp = dir == NULL;
    if (dir == NULL) {
        snprintf(lp, len, "/tmp/bench_milp_XXXXXX.lp");
        int fd = mkstemps(lp, 3);
        if (fd < 0) {
            fprintf(stderr, "bench_milp: cannot make a temporary model file\n");
            return -1;
        }
        close(fd);
    } else {
        char csv[1024], err[512];
        snprintf(csv, sizeof csv, "%s/%s.csv", dir, name);
        if (hv_fruitmap_save(csv, inst->fruits, inst->n_fruits, err, sizeof err) != HV_OK) {
            fprintf(stderr, "bench_milp: --export: %s\n", err);
            return -1;
        }
        snprintf(lp, len, "%s/%s.lp", dir, name);
    }
    hv_milp_options_t o;
    hv_milp_options_default(&o);
    if (hv_milp_export_lp(inst, &o, lp) != HV_OK) {
        fprintf(stderr, "bench_milp: %s: cannot write the model\n", lp);
        return -1;
    }
    return 0;
}

/* One instance's outcome, for the slowest of a model. */
typedef struct inst_time {
    double alpha, time_s, gap;
    size_t seed;
    hv_solve_status_t status;
} inst_time_t;

typedef struct bench_run {
    const char *cfg_path, *export_dir;
    double alphas[MAX_ALPHAS];
    size_t n_alpha, n_seeds, first_seed;
    int baselines, given_plan;
    hv_milp_options_t mo;
    highs_cfg_t highs;
    inst_time_t slowest[MAX_MODELS][N_SLOWEST]; /* slowest first; time_s < 0: none */
} bench_run_t;

/* Keep `t` among the N_SLOWEST slowest in list[] (slowest first). */
static void note_slowest(inst_time_t *list, const inst_time_t *t)
{
    size_t k = N_SLOWEST;
    while (k > 0 && list[k - 1].time_s < t->time_s) {
        if (k < N_SLOWEST) {
            list[k] = list[k - 1];
        }
        --k;
    }
    if (k < N_SLOWEST) {
        list[k] = *t;
    }
}

/* Every instance of model m: a row each, into st[alpha] and st[n_alpha] (all alphas).
 * Returns the number of solver failures. */
static int run_model(bench_run_t *br, const bench_model_t *m, row_stats_t *st, inst_time_t *slowest)
{
    int failures = 0;
    printf("\n# Model: %s (%s)\n", bench_model_name(m->kind),
           m->kind == BENCH_MODEL_PRODUCT
               ? "config as harvest-plan builds it: stops beyond the ends, pick cycle, tau = v/a"
               : "the paper's: N = 201 stops on the row, one-way costs, tau = stop_penalty");
    printf("%-5s %-4s %4s %5s %6s | %-9s %9s %9s %8s %7s %7s %5s | %9s %9s | %-14s %9s %7s | "
           "%9s %5s | %9s\n",
           "alpha", "seed", "nf", "stops", "pairs", "milp", "T_s", "bound_s", "gap", "time_s",
           "nodes", "used", "root_s", "heur_T_s", "highs", "highs_T_s", "highs_s", "fov_T_s",
           "stops", "serial_T");
    for (size_t ai = 0; ai < br->n_alpha; ++ai) {
        row_stats_t *r = &st[ai], *all = &st[br->n_alpha];
        size_t n_right = (size_t)lround(br->alphas[ai] * 50.0);
        for (size_t seed = 0; seed < br->n_seeds; ++seed) {
            size_t s = br->first_seed + seed;
            hv_instance_t inst;
            if (bench_instance_make(m, 50, n_right, s, &inst) != 0) {
                return failures + 1;
            }
            size_t nf = inst.n_fruits - hv_instance_unreachable_count(&inst);
            hv_assignment_t out, tmp;
            hv_assignment_alloc(&out, inst.n_fruits);
            hv_assignment_alloc(&tmp, inst.n_fruits);
            hv_milp_result_t res;
            hv_eval_t ev;
            memset(&ev, 0, sizeof ev);
            if (hv_milp_solve(&inst, &br->mo, NULL, &out, &res) != HV_OK) {
                fprintf(stderr, "bench_milp: solver error on %s alpha %g seed %zu\n",
                        bench_model_name(m->kind), br->alphas[ai], s);
                failures++;
                hv_assignment_free(&out);
                hv_assignment_free(&tmp);
                hv_instance_free(&inst);
                continue;
            }
            hv_assignment_eval(&inst, &out, &ev);
            inst_time_t it = {br->alphas[ai], res.runtime_s, res.gap, s, res.status};
            note_slowest(slowest, &it);
            for (int w = 0; w < 2; ++w) {
                row_stats_t *x = w ? all : r;
                x->t_milp[x->n++] = res.runtime_s;
                x->n_opt += res.status == HV_SOLVE_OPTIMAL;
                x->gap_max = fmax(x->gap_max, res.gap);
                x->gap_sum += res.gap;
                x->stops_milp += (double)ev.stops;
                x->thr_milp += (double)nf / res.objective_s;
                if (isfinite(res.incumbent_s)) {
                    x->heur_excess_max =
                        fmax(x->heur_excess_max, res.incumbent_s / res.objective_s - 1.0);
                }
            }
            printf("%-5g %-4zu %4zu %5zu %6zu | %-9s %9.3f %9.3f %8.2e %7.2f %7ld %5zu | %9.3f "
                   "%9.3f |",
                   br->alphas[ai], s, nf, inst.n_stops, inst.n_pairs, status_word(res.status),
                   res.objective_s, res.bound_s, res.gap, res.runtime_s, res.nodes, ev.stops,
                   res.root_bound_s, res.incumbent_s);
            /* the model file HiGHS reads, and --export's copy */
            int want_highs = seed < br->highs.seeds && !br->highs.broken, temp = 0;
            char lp[1024], name[96];
            snprintf(name, sizeof name, "%s-a%g-s%zu", bench_model_name(m->kind), br->alphas[ai],
                     s);
            int have_lp = (want_highs || br->export_dir != NULL) &&
                          write_model(br->export_dir, name, &inst, lp, sizeof lp, &temp) == 0;
            failures += br->export_dir != NULL && !have_lp;
            br->highs.broken |= want_highs && !have_lp; /* said once, not tried again */
            highs_run_t hr;
            if (want_highs && have_lp && highs_baseline(&br->highs, lp, &hr)) {
                int proven = strcmp(hr.status, "optimal") == 0;
                /* both proven: the optima agree to the ms */
                int disagree = proven && res.status == HV_SOLVE_OPTIMAL &&
                               fabs(hr.objective_s - res.objective_s) > 0.0005;
                for (int w = 0; w < 2; ++w) {
                    row_stats_t *x = w ? all : r;
                    x->t_ours[x->n_highs] = res.runtime_s;
                    x->t_highs[x->n_highs++] = hr.time_s;
                    x->n_highs_opt += proven;
                    x->n_highs_disagree += disagree;
                }
                printf(" %-14.14s %9.3f %7.2f |", hr.status, hr.objective_s, hr.time_s);
                if (disagree) {
                    fprintf(stderr,
                            "bench_milp: %s alpha %g seed %zu: HiGHS proves %.3f s, "
                            "the MILP %.3f s\n",
                            bench_model_name(m->kind), br->alphas[ai], s, hr.objective_s,
                            res.objective_s);
                }
            } else {
                printf(" %-14s %9s %7s |", "-", "-", "-");
            }
            if (temp) {
                unlink(lp);
            }
            if (br->baselines) {
                hv_eval_t fe;
                double st_serial = NAN;
                if (hv_fov_solve(&inst, HV_FOV_DEFAULT_WIDTH_M, &tmp, NULL) == HV_OK &&
                    hv_assignment_eval(&inst, &tmp, &fe) == HV_OK) {
                    for (int w = 0; w < 2; ++w) {
                        row_stats_t *x = w ? all : r;
                        x->stops_fov += (double)fe.stops;
                        x->thr_fov += (double)nf / fe.makespan_s;
                    }
                    printf(" %9.3f %5zu |", fe.makespan_s, fe.stops);
                }
                unsigned char *passes = malloc(inst.n_fruits + 1);
                hv_serial_result_t sr;
                hv_milp_options_t so;
                hv_milp_options_default(&so);
                so.time_limit_s = br->mo.time_limit_s;
                if (passes != NULL && hv_serial_solve(&inst, &so, &tmp, passes, &sr) == HV_OK) {
                    st_serial = sr.makespan_s;
                    for (int w = 0; w < 2; ++w) {
                        row_stats_t *x = w ? all : r;
                        x->thr_serial += (double)nf / sr.makespan_s;
                        x->n_serial++;
                    }
                }
                free(passes);
                printf(" %9.3f", st_serial);
            }
            printf("\n");
            if (br->given_plan && isfinite(res.objective_s)) {
                /* the same solve with its own plan as the incumbent from the start */
                hv_milp_result_t gr;
                if (hv_milp_solve(&inst, &br->mo, &out, &tmp, &gr) == HV_OK) {
                    for (int w = 0; w < 2; ++w) {
                        row_stats_t *x = w ? all : r;
                        x->t_given[x->n_given++] = gr.runtime_s;
                        x->n_given_opt += gr.status == HV_SOLVE_OPTIMAL;
                    }
                    printf("#   given its plan (%.3f s): %s %9.3f, gap %8.2e in %7.2f s, %ld "
                           "nodes\n",
                           res.objective_s, status_word(gr.status), gr.objective_s, gr.gap,
                           gr.runtime_s, gr.nodes);
                } else {
                    fprintf(stderr,
                            "bench_milp: solver error on alpha %g seed %zu, given its plan\n",
                            br->alphas[ai], s);
                    failures++;
                }
            }
            fflush(stdout);
            hv_assignment_free(&out);
            hv_assignment_free(&tmp);
            hv_instance_free(&inst);
        }
    }
    return failures;
}

/* "median max" of HiGHS and the ratio of its median to ours on the same instances into buf;
 * the ratio is a lower bound (">") when HiGHS's median instance is unproven. */
static void highs_cells(row_stats_t *r, char *buf, size_t len)
{
    if (r->n_highs == 0) {
        snprintf(buf, len, "%5s %7s %7s", "-", "-", "-");
        return;
    }
    double ours = median(r->t_ours, r->n_highs), theirs = median(r->t_highs, r->n_highs);
    int censored = 2 * (r->n_highs - r->n_highs_opt) >= r->n_highs;
    char ratio[16];
    double q = theirs / fmax(ours, 1e-3);
    snprintf(ratio, sizeof ratio, q < 10.0 ? "%s%.1fx" : "%s%.0fx", censored ? ">" : "", q);
    snprintf(buf, len, "%2zu/%-2zu %7.2f %7s", r->n_highs_opt, r->n_highs, theirs, ratio);
}

static void print_model_summary(const bench_run_t *br, const bench_model_t *m, row_stats_t *st,
                                const inst_time_t *slowest)
{
    printf("\n# Summary, %s model (times in s; throughput in fruits/s; HiGHS: proven of run, "
           "median time, its median over ours on the same instances, %.0f s limit)\n",
           bench_model_name(m->kind), br->highs.limit_s);
    printf("%-5s | %7s %7s %7s %8s %8s | %5s %8s | %5s %8s %9s | %9s %5s | %-21s\n", "alpha",
           "median", "max", "optimal", "mean_gap", "max_gap", "stops", "thr", "FOVst", "FOV_thr",
           "MILP/FOV", "serial", "dual/s", "HiGHS opt med ratio");
    for (size_t ai = 0; ai <= br->n_alpha; ++ai) {
        row_stats_t *r = &st[ai];
        double n = (double)(r->n ? r->n : 1);
        char fov[64] = "    -        -         -", serial[64] = "        -     -", highs[64];
        if (r->thr_fov > 0) {
            snprintf(fov, sizeof fov, "%5.2f %8.4f %+8.1f%%", r->stops_fov / n, r->thr_fov / n,
                     100.0 * (r->thr_milp / r->thr_fov - 1.0));
        }
        if (r->n_serial > 0) {
            snprintf(serial, sizeof serial, "%9.4f %4.2fx", r->thr_serial / (double)r->n_serial,
                     r->thr_milp / r->thr_serial);
        }
        highs_cells(r, highs, sizeof highs);
        char name[16];
        snprintf(name, sizeof name, "%g", ai < br->n_alpha ? br->alphas[ai] : 0.0);
        double tmax = max_of(r->t_milp, r->n);
        printf("%-5s | %7.3f %7.3f %3zu/%-3zu %8.2e %8.2e | %5.2f %8.4f | %s | %s | %s\n",
               ai < br->n_alpha ? name : "all", median(r->t_milp, r->n), tmax, r->n_opt, r->n,
               r->gap_sum / n, r->gap_max, r->stops_milp / n, r->thr_milp / n, fov, serial, highs);
    }
    printf("# slowest:");
    for (size_t k = 0; k < N_SLOWEST && slowest[k].time_s >= 0; ++k) {
        const inst_time_t *t = &slowest[k];
        printf("%s alpha %g seed %zu %.2f s %s", k ? ";" : "", t->alpha, t->seed, t->time_s,
               status_word(t->status));
        if (t->status != HV_SOLVE_OPTIMAL) {
            printf(" (gap %.1e)", t->gap);
        }
    }
    printf("\n");
    if (st[br->n_alpha].n_highs_disagree > 0) {
        printf("# HiGHS and the MILP proved different optima on %zu instances (stderr)\n",
               st[br->n_alpha].n_highs_disagree);
    }
    if (br->given_plan) {
        printf("\n# Given its own plan from the start (the proof alone)\n%-5s | %7s %7s %7s\n",
               "alpha", "median", "max", "optimal");
        for (size_t ai = 0; ai <= br->n_alpha; ++ai) {
            row_stats_t *r = &st[ai];
            char name[16];
            snprintf(name, sizeof name, "%g", ai < br->n_alpha ? br->alphas[ai] : 0.0);
            printf("%-5s | %7.3f %7.3f %3zu/%-3zu\n", ai < br->n_alpha ? name : "all",
                   median(r->t_given, r->n_given), max_of(r->t_given, r->n_given), r->n_given_opt,
                   r->n_given);
        }
    }
}

/* The models side by side: proven, median, max, HiGHS. */
static void print_side_by_side(const bench_run_t *br, const bench_model_t *models, size_t n_models,
                               row_stats_t (*st)[MAX_ALPHAS + 1])
{
    printf("\n# Side by side (MILP: proven, median and max time in s; HiGHS as above)\n%-5s",
           "alpha");
    for (size_t k = 0; k < n_models; ++k) {
        printf(" | %-8s %7s %7s %7s %-21s", bench_model_name(models[k].kind), "median", "max",
               "optimal", "HiGHS opt med ratio");
    }
    printf("\n");
    for (size_t ai = 0; ai <= br->n_alpha; ++ai) {
        char name[16];
        snprintf(name, sizeof name, "%g", ai < br->n_alpha ? br->alphas[ai] : 0.0);
        printf("%-5s", ai < br->n_alpha ? name : "all");
        for (size_t k = 0; k < n_models; ++k) {
            row_stats_t *r = &st[k][ai];
            char highs[64];
            highs_cells(r, highs, sizeof highs);
            double tmax = max_of(r->t_milp, r->n);
            printf(" | %-8s %7.3f %7.3f %3zu/%-3zu %s", "", median(r->t_milp, r->n), tmax, r->n_opt,
                   r->n, highs);
        }
        printf("\n");
    }
}

int main(int argc, char **argv)
{
    static bench_run_t br;
    static row_stats_t stats[MAX_MODELS][MAX_ALPHAS + 1];
    br.cfg_path = HV_BENCH_DEFAULT_CONFIG;
    const double alphas0[] = {0.25, 0.4, 1.0, 2.5, 4.0};
    memcpy(br.alphas, alphas0, sizeof alphas0);
    br.n_alpha = 5;
    br.n_seeds = 10;
    br.first_seed = 1;
    br.baselines = 1;
    br.highs = (highs_cfg_t){HV_BENCH_PYTHON, 2, 60.0, 0.0, 0};
    for (size_t k = 0; k < MAX_MODELS; ++k) {
        for (size_t i = 0; i < N_SLOWEST; ++i) {
            br.slowest[k][i].time_s = -1.0;
        }
    }
    bench_model_kind_t kinds[MAX_MODELS] = {BENCH_MODEL_PRODUCT, BENCH_MODEL_PAPER};
    size_t n_models = 2;
    hv_milp_options_default(&br.mo);
    br.mo.time_limit_s = 0.0; /* 0: the config's */
    enum {
        O_NO_BASELINES = 256,
        O_QUICK,
        O_EXPORT,
        O_GIVEN_PLAN,
        O_CONFIG,
        O_MODELS,
        O_ALPHAS,
        O_SEEDS,
        O_HIGHS_SEEDS,
        O_FIRST_SEED,
        O_TIME_LIMIT,
        O_HIGHS_LIMIT,
        O_PYTHON,
        O_SET
    };
    static const struct option longopts[] = {
        {"no-baselines", no_argument, NULL, O_NO_BASELINES},
        {"quick", no_argument, NULL, O_QUICK},
        {"export", required_argument, NULL, O_EXPORT},
        {"given-plan", no_argument, NULL, O_GIVEN_PLAN},
        {"config", required_argument, NULL, O_CONFIG},
        {"models", required_argument, NULL, O_MODELS},
        {"alphas", required_argument, NULL, O_ALPHAS},
        {"seeds", required_argument, NULL, O_SEEDS},
        {"highs-seeds", required_argument, NULL, O_HIGHS_SEEDS},
        {"first-seed", required_argument, NULL, O_FIRST_SEED},
        {"time-limit", required_argument, NULL, O_TIME_LIMIT},
        {"highs-limit", required_argument, NULL, O_HIGHS_LIMIT},
        {"python", required_argument, NULL, O_PYTHON},
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
        case 'v': br.mo.verbose = br.mo.verbose + 1; break;
        case O_NO_BASELINES: br.baselines = 0; break;
        case O_GIVEN_PLAN: br.given_plan = 1; break;
        case O_QUICK:
            br.alphas[0] = 0.25;
            br.n_alpha = 1;
            br.n_seeds = 1;
            br.highs.seeds = 1;
            br.highs.limit_s = 20.0;
            break;
        case O_EXPORT: br.export_dir = v; break;
        case O_CONFIG: br.cfg_path = v; break;
        case O_PYTHON: br.highs.python = v; break;
        case O_MODELS: {
            n_models = 0;
            char buf[64];
            snprintf(buf, sizeof buf, "%s", v);
            for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
                int paper = strcmp(tok, "paper") == 0;
                if ((!paper && strcmp(tok, "product") != 0) || n_models == MAX_MODELS) {
                    fprintf(stderr, "bench_milp: --models: product, paper or both, not '%s'\n", v);
                    return 2;
                }
                kinds[n_models++] = paper ? BENCH_MODEL_PAPER : BENCH_MODEL_PRODUCT;
            }
            break;
        }
        case O_ALPHAS: {
            br.n_alpha = 0;
            char buf[256];
            snprintf(buf, sizeof buf, "%s", v);
            for (char *tok = strtok(buf, ","); tok && br.n_alpha < MAX_ALPHAS;
                 tok = strtok(NULL, ",")) {
                char *end;
                br.alphas[br.n_alpha] = strtod(tok, &end);
                if (*end != '\0' || !(br.alphas[br.n_alpha] > 0)) {
                    fprintf(stderr, "bench_milp: --alphas: bad value '%s'\n", tok);
                    return 2;
                }
                br.n_alpha++;
            }
            break;
        }
        case O_SEEDS:
        case O_HIGHS_SEEDS: {
            long n = strtol(v, NULL, 10);
            if (n < 0 || n > MAX_SEEDS) {
                fprintf(stderr, "bench_milp: --%s: 0..%d\n", a, MAX_SEEDS);
                return 2;
            }
            *(opt == O_SEEDS ? &br.n_seeds : &br.highs.seeds) = (size_t)n;
            break;
        }
        case O_FIRST_SEED: {
            char *end;
            long n = strtol(v, &end, 10);
            if (*end != '\0' || n < 1) {
                fprintf(stderr, "bench_milp: --first-seed: a whole number >= 1, not '%s'\n", v);
                return 2;
            }
            br.first_seed = (size_t)n;
            break;
        }
        case O_TIME_LIMIT:
        case O_HIGHS_LIMIT: {
            double t = strtod(v, NULL);
            if (!(t > 0)) {
                fprintf(stderr, "bench_milp: --%s: must be > 0\n", a);
                return 2;
            }
            *(opt == O_TIME_LIMIT ? &br.mo.time_limit_s : &br.highs.limit_s) = t;
            break;
        }
        case O_SET:
            if (hv_milp_option_set(&br.mo, v) != HV_OK) {
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
    if (br.export_dir != NULL && access(br.export_dir, W_OK | X_OK) != 0) {
        fprintf(stderr, "bench_milp: --export: %s: not a folder this user can write\n",
                br.export_dir);
        return 2;
    }
    br.highs.rel_gap = br.mo.rel_gap;

    hv_config_t cfg;
    char err[256];
    if (hv_config_load(br.cfg_path, &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "bench_milp: %s\n", err);
        return 1;
    }
    int time_limit_given = br.mo.time_limit_s > 0;
    if (!time_limit_given) {
        br.mo.time_limit_s = cfg.online_limit_min_s;
    }
    static bench_model_t models[MAX_MODELS];
    for (size_t k = 0; k < n_models; ++k) {
        if (bench_model_init(&cfg, kinds[k], &models[k]) != 0) {
            return 1;
        }
    }
    const hv_milp_options_t *mo = &br.mo;
    printf("# MILP options: algorithm=%s rel_gap=%g disaggregated=%d heuristic=%d "
           "ms=%d decompose=%d limit=%.0fs; price: "
           "sr_cuts=%d/%d sr_purge=%d cover_rows=%d pseudocost=%d tree_threads=%d "
           "helper_thread=%d ascent_steps=%d auto_smoothing=%d interval_branching=%d "
           "iv_pseudocost=%d tail_off_ms=%d tail_off_open=%d binding_splits=%d "
           "balance_workers=%d warm_transfer=%d rins_every=%d region_stops=%d\n",
           mo->algorithm == HV_MILP_ALG_PRICE ? "price" : "compact", mo->rel_gap,
           mo->link_disaggregated, mo->heuristic_incumbent, mo->ms_granularity, mo->decompose,
           mo->time_limit_s, mo->sr_cuts, mo->sr_cuts_large, mo->sr_purge, mo->cover_rows,
           mo->pseudocost, mo->tree_threads, mo->helper_thread, mo->ascent_steps,
           mo->auto_smoothing, mo->interval_branching, mo->iv_pseudocost, mo->tail_off_ms,
           mo->tail_off_open, mo->binding_splits, mo->balance_workers, mo->warm_transfer,
           mo->rins_every, mo->region_stops);
    printf("# %s; MILP limit %g s per instance%s\n", br.cfg_path, mo->time_limit_s,
           time_limit_given ? "" : " (online.horizon_limit_min of the config)");
    print_load("at the start");
    printf("# HiGHS: highspy on the exported compact model, first %zu seeds per alpha, %.0f s "
           "limit, 2 threads, mip_rel_gap %g, mip_abs_gap %g s, its defaults otherwise\n",
           br.highs.seeds, br.highs.limit_s, br.highs.rel_gap, HIGHS_ABS_GAP_S);
    int failures = 0;
    for (size_t k = 0; k < n_models; ++k) {
        failures += run_model(&br, &models[k], stats[k], br.slowest[k]);
    }
    for (size_t k = 0; k < n_models; ++k) {
        print_model_summary(&br, &models[k], stats[k], br.slowest[k]);
    }
    if (n_models > 1) {
        print_side_by_side(&br, models, n_models, stats);
    }
    print_load("at the end");
    return failures ? 1 : 0;
}
