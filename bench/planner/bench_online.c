/* bench_online: online planning of 50 m rows (DESIGN §5, §10) against the offline plan of
 * the same fruits, and whether the vehicle ever waits for the planner.
 * Run `bench_online --help`.
 *
 * The vehicle is simulated in virtual time at time scale 1, in the robot's time of the
 * plan model (plan.pick_cycle = 1: a stop takes its slower arm's pick cycles plus what
 * the drive loses stopping; the vehicle drives at vehicle.speed between stops). The
 * camera sees [y + camera.lead, y + camera.lead + camera.window] from the vehicle's
 * position y, which changes at each arrival. The planner (hv_online_step_ahead, really run,
 * its limit from the robot time committed ahead when it starts) takes
 * the wall time it measures per horizon; its committed stops are available to the vehicle
 * that long after it started, which is when it was free and the vehicle's last arrival
 * had shown it what it planned with. A vehicle with no committed stop to go to waits.
 */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_instances.h"
#include "hv/file_io.h"
#include "hv/milp.h"
#include "hv/online.h"
#include "hv/plan_eval.h"

#ifndef HV_BENCH_DEFAULT_CONFIG
#define HV_BENCH_DEFAULT_CONFIG "config/harvest.cfg"
#endif

#define MAX_ALPHAS 16

static void usage(FILE *f)
{
    fprintf(f,
            "usage: bench_online [options]\n"
            "Online planning of long rows (fruit revealed by the camera of the config) against\n"
            "the offline MILP plan of the whole row on the same fruits, in the robot's time\n"
            "(plan.pick_cycle = 1). Per row: makespans, the vehicle's wait for the planner\n"
            "(virtual time at time scale 1 from the planner's measured wall time per horizon),\n"
            "planner time per horizon (median, max).\n"
            "  --config PATH      harvest config (default %s)\n"
            "  --length M         row length, m (default 50)\n"
            "  --alphas A,B,..    right/left density ratios, one row each (default\n"
            "                     0.25,1,2.5);\n"
            "                     the left side has the paper's 25 fruits per m\n"
            "  --seed N           fruit seed (default 1)\n"
            "  --window H         horizon solved per step, m (default 2)\n"
            "  --commit M         committed per step, m (default 1)\n"
            "  --window-limit S   MILP limit per horizon, s (default: half the robot time\n"
            "                     committed ahead when the horizon starts, within the config's\n"
            "                     online.horizon_limit_min and online.horizon_limit_max)\n"
            "  --time-limit S     limit of the offline whole-row solve, s (default 120)\n"
            "  --help             this text\n",
            HV_BENCH_DEFAULT_CONFIG);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int by_y(const void *a, const void *b)
{
    const hv_fruit_t *p = a, *q = b;
    return p->y_m < q->y_m ? -1 : p->y_m > q->y_m;
}

typedef struct online_run {
    double makespan_s;   /* virtual: course start to course end, waits included */
    double wait_start_s; /* waiting for the first committed stop */
    double wait_row_s;   /* waiting after that */
    unsigned waits;      /* times the vehicle waited after the first stop */
    double min_slack_s;  /* least robot time left ahead of the vehicle when a step came */
    double *step_s;      /* wall time per horizon */
    double *limit_s;     /* its time limit */
    size_t n_steps;
    unsigned empty_advances; /* drives to the commit line with no stop ahead */
} online_run_t;

/* Reveal what the camera at vehicle position vy sees. */
static int reveal(hv_online_t *o, const hv_config_t *cfg, const hv_fruit_t *fr, size_t n,
                  size_t *next, double vy)
{
    double seen = vy + cfg->camera_lead_m + cfg->camera_window_m;
    while (*next < n && fr[*next].y_m <= seen) {
        hv_online_verdict_t v;
        if (hv_online_detect(o, &fr[(*next)++], &v) != HV_OK) {
            return -1;
        }
    }
    hv_online_seen(o, seen);
    return 0;
}

static int run_online(hv_online_t *o, const hv_config_t *cfg, const hv_fruit_t *fr, size_t n,
                      int fixed_limit, online_run_t *run)
{
    memset(run, 0, sizeof *run);
    run->min_slack_s = INFINITY;
    size_t cap = 256, next = 0, k = 0;
    double *avail = malloc(cap * sizeof *avail); /* per committed stop */
    run->step_s = malloc(1024 * sizeof *run->step_s);
    run->limit_s = malloc(1024 * sizeof *run->limit_s);
    if (avail == NULL || run->step_s == NULL || run->limit_s == NULL) {
        free(avail);
        return -1;
    }
    const double speed = cfg->vehicle_speed_mps;
    double t = 0.0, vy = hv_online_commit_y(o), t_seen = 0.0, tp = 0.0;
    double commit_y = vy, commit_y_at = 0.0;
    double course_end = o->params.row_start_m + o->params.row_length_m + o->params.stop_margin_m;
    if (reveal(o, cfg, fr, n, &next, vy) != 0) {
        return -1;
    }
    for (;;) {
        while (hv_online_ready(o)) {
            /* the robot time committed ahead when the step starts (at fmax(tp, t_seen)):
             * the rest of the stop the vehicle is at (it is done at t) and the stops after */
            double ahead = fmax(0.0, t + hv_online_ahead_s(o, k, vy, speed) - fmax(tp, t_seen));
            double w0 = now_s();
            hv_online_step_result_t r;
            hv_status_t sst =
                fixed_limit ? hv_online_step(o, &r) : hv_online_step_ahead(o, ahead, &r);
            if (sst != HV_OK) {
                fprintf(stderr, "bench_online: a step failed\n");
                free(avail);
                return -1;
            }
            double w = now_s() - w0;
            if (run->n_steps < 1024) {
                run->limit_s[run->n_steps] = r.limit_s;
                run->step_s[run->n_steps++] = w;
            }
            tp = fmax(tp, t_seen) + w;
            if (o->n_stops > cap) {
                cap = 2 * o->n_stops;
                double *a = realloc(avail, cap * sizeof *a);
                if (a == NULL) {
                    free(avail);
                    return -1;
                }
                avail = a;
            }
            for (size_t s = r.stops_from; s < r.stops_to; ++s) {
                avail[s] = tp;
            }
            commit_y = hv_online_commit_y(o);
            commit_y_at = tp;
            /* robot time of the committed stops still ahead when this step came */
            if (k > 0) {
                double ahead = 0.0, y = vy;
                for (size_t s = k; s < r.stops_from; ++s) {
                    ahead += fabs(o->stops[s].y_m - y) / speed + hv_online_stop_work_s(o, s);
                    y = o->stops[s].y_m;
                }
                double slack = (t + ahead) - tp; /* t: when the vehicle finished stop k-1 */
                run->min_slack_s = fmin(run->min_slack_s, slack);
            }
        }
        if (k < o->n_stops) {
            if (avail[k] > t) {
                if (k == 0) {
                    run->wait_start_s += avail[k] - t;
                } else {
                    run->wait_row_s += avail[k] - t;
                    run->waits++;
                }
                t = avail[k];
            }
            t += fabs(o->stops[k].y_m - vy) / speed;
            vy = o->stops[k].y_m;
            t_seen = t;
            if (reveal(o, cfg, fr, n, &next, vy) != 0) {
                return -1;
            }
            t += hv_online_stop_work_s(o, k);
            k++;
        } else if (o->done) {
            t += fabs(course_end - vy) / speed;
            break;
        } else if (commit_y > vy + 1e-9) {
            /* no fruit in the committed stretch: drive on to its end to see further */
            if (commit_y_at > t) {
                run->wait_row_s += commit_y_at - t;
                run->waits++;
                t = commit_y_at;
            }
            t += (commit_y - vy) / speed;
            vy = commit_y;
            t_seen = t;
            run->empty_advances++;
            if (reveal(o, cfg, fr, n, &next, vy) != 0) {
                return -1;
            }
        } else {
            fprintf(stderr, "bench_online: the planner cannot commit and the vehicle cannot "
                            "advance: camera.lead + camera.window too short\n");
            free(avail);
            return -1;
        }
    }
    run->makespan_s = t;
    free(avail);
    return 0;
}

static int parse_alphas(const char *text, double *out, int *n)
{
    *n = 0;
    const char *p = text;
    while (*p && *n < MAX_ALPHAS) {
        char *end;
        double v = strtod(p, &end);
        if (end == p || !(v > 0)) {
            return -1;
        }
        out[(*n)++] = v;
        p = *end == ',' ? end + 1 : end;
        if (*end != ',' && *end != '\0') {
            return -1;
        }
    }
    return *n > 0 ? 0 : -1;
}

static int bench_row(const hv_config_t *cfg, double alpha, uint64_t seed,
                     const hv_online_options_t *oo, int fixed_limit, double time_limit)
{
    hv_ik_model_t ik;
    hv_pick_model_t model;
    if (hv_pick_model_ik(cfg, &ik, &model) != HV_OK) {
        fprintf(stderr, "bench_online: pick model failed\n");
        return -1;
    }
    size_t n_left = (size_t)floor(25.0 * cfg->row_length_m + 0.5);
    size_t n_right = (size_t)floor(alpha * (double)n_left + 0.5);
    size_t n = n_left + n_right;
    hv_fruit_t *fr = bench_fruits_make(cfg, n_left, n_right, seed);
    if (fr == NULL) {
        return -1;
    }
    qsort(fr, n, sizeof *fr, by_y); /* the order the camera meets them */
    hv_instance_params_t par;
    hv_instance_params_from_config(cfg, &model, &par);
    hv_online_t o;
    online_run_t run;
    memset(&run, 0, sizeof run);
    int rc = hv_online_init(&o, &par, &model, oo) == HV_OK ? 0 : -1;
    if (rc == 0) {
        rc = run_online(&o, cfg, fr, n, fixed_limit, &run);
    }
    /* the same fruits planned offline, whole row, and the online plan's makespan on them */
    hv_instance_t inst;
    memset(&inst, 0, sizeof inst);
    hv_assignment_t on = {0, NULL}, off = {0, NULL}, warm = {0, NULL};
    hv_milp_result_t mr;
    memset(&mr, 0, sizeof mr);
    double t_on = 0.0, t_off = 0.0;
    hv_diag_t diag;
    if (rc == 0) {
        rc = hv_instance_build(&par, o.fruits, o.n_fruits, &model, &inst, &diag) == HV_OK &&
                     hv_assignment_alloc(&on, o.n_fruits) == HV_OK &&
                     hv_assignment_alloc(&off, o.n_fruits) == HV_OK &&
                     hv_assignment_alloc(&warm, o.n_fruits) == HV_OK &&
                     hv_online_assignment(&o, &on) == HV_OK &&
                     hv_assignment_makespan(&inst, &on, &t_on) == HV_OK
                 ? 0
                 : -1;
    }
    double t0 = now_s();
    if (rc == 0) {
        hv_milp_options_t mo;
        hv_milp_options_default(&mo);
        mo.time_limit_s = time_limit;
        rc = hv_heuristic_solve(&inst, &warm) == HV_OK &&
                     hv_milp_solve(&inst, &mo, &warm, &off, &mr) == HV_OK
                 ? 0
                 : -1;
    }
    double off_wall = now_s() - t0;
    if (rc == 0) {
        int have = mr.status == HV_SOLVE_OPTIMAL || mr.status == HV_SOLVE_FEASIBLE;
        if (have) {
            hv_assignment_makespan(&inst, &off, &t_off);
        }
        qsort(run.step_s, run.n_steps, sizeof *run.step_s, cmp_double);
        qsort(run.limit_s, run.n_steps, sizeof *run.limit_s, cmp_double);
        double med = run.n_steps ? run.step_s[run.n_steps / 2] : 0.0;
        double mx = run.n_steps ? run.step_s[run.n_steps - 1] : 0.0;
        double lmin = run.n_steps ? run.limit_s[0] : 0.0;
        double lmed = run.n_steps ? run.limit_s[run.n_steps / 2] : 0.0;
        printf("row %.0f m, alpha %.2f, seed %llu: %zu fruits (%u unreachable), %zu stops "
               "committed in %zu horizons (%u optimal)\n",
               cfg->row_length_m, alpha, (unsigned long long)seed, n, o.counts[HV_DET_UNREACHABLE],
               o.n_stops, run.n_steps, o.steps_optimal);
        printf("  offline whole row: %s after %.1f s: makespan %s%.1f s, bound %.1f s\n",
               mr.status == HV_SOLVE_OPTIMAL ? "optimal"
               : have                        ? "feasible"
                                             : "no solution",
               off_wall, have ? "" : "n/a ", have ? t_off : 0.0, mr.bound_s);
        printf("  online plan: makespan %.1f s: %+.2f %% vs offline%s, %+.2f %% vs its bound\n",
               t_on, have ? 100.0 * (t_on - t_off) / t_off : NAN, have ? "" : " (none)",
               100.0 * (t_on - mr.bound_s) / mr.bound_s);
        printf("  online run (virtual time, time scale 1): %.1f s, vehicle waited %.2f s for the "
               "first horizon and %.2f s after it (%u times); least robot time committed ahead "
               "when a horizon came: %.1f s; %u drives through a stretch with no fruit\n",
               run.makespan_s, run.wait_start_s, run.wait_row_s, run.waits, run.min_slack_s,
               run.empty_advances);
        printf("  planner wall time per horizon: median %.3f s, max %.3f s; its limit: least "
               "%.1f s, median %.1f s\n",
               med, mx, lmin, lmed);
    }
    hv_assignment_free(&on);
    hv_assignment_free(&off);
    hv_assignment_free(&warm);
    hv_instance_free(&inst);
    hv_online_free(&o);
    free(run.step_s);
    free(run.limit_s);
    free(fr);
    return rc;
}

int main(int argc, char **argv)
{
    const char *cfg_path = HV_BENCH_DEFAULT_CONFIG;
    double length = 50.0, time_limit = 120.0;
    double alphas[MAX_ALPHAS] = {0.25, 1.0, 2.5};
    int n_alphas = 3;
    int fixed_limit = 0;
    unsigned long long seed = 1;
    hv_online_options_t oo;
    hv_online_options_default(&oo);
    enum {
        O_CONFIG = 256,
        O_ALPHAS,
        O_LENGTH,
        O_SEED,
        O_WINDOW,
        O_COMMIT,
        O_WINDOW_LIMIT,
        O_TIME_LIMIT
    };
    static const struct option longopts[] = {
        {"config", required_argument, NULL, O_CONFIG},
        {"alphas", required_argument, NULL, O_ALPHAS},
        {"length", required_argument, NULL, O_LENGTH},
        {"seed", required_argument, NULL, O_SEED},
        {"window", required_argument, NULL, O_WINDOW},
        {"commit", required_argument, NULL, O_COMMIT},
        {"window-limit", required_argument, NULL, O_WINDOW_LIMIT},
        {"time-limit", required_argument, NULL, O_TIME_LIMIT},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    opterr = 0;
    int opt, idx = 0;
    while ((opt = getopt_long(argc, argv, ":h", longopts, &idx)) != -1) {
        const char *v = optarg;
        if (opt == 'h') {
            usage(stdout);
            return 0;
        }
        if (opt == ':' || opt == '?') {
            fprintf(stderr, "bench_online: %s %s (see --help)\n",
                    opt == ':' ? "a value is needed for" : "unknown option", argv[optind - 1]);
            return 2;
        }
        if (opt == O_CONFIG) {
            cfg_path = v;
            continue;
        }
        if (opt == O_ALPHAS) {
            if (parse_alphas(v, alphas, &n_alphas) != 0) {
                fprintf(stderr, "bench_online: --alphas: bad list \"%s\"\n", v);
                return 2;
            }
            continue;
        }
        char *end = NULL;
        double x = strtod(v, &end);
        if (end == v || *end != '\0' || !isfinite(x) || x <= 0) {
            fprintf(stderr, "bench_online: --%s: expected a positive number, got \"%s\"\n",
                    longopts[idx].name, v);
            return 2;
        }
        switch (opt) {
        case O_LENGTH: length = x; break;
        case O_SEED: seed = (unsigned long long)x; break;
        case O_WINDOW: oo.window_m = x; break;
        case O_COMMIT: oo.commit_m = x; break;
        case O_WINDOW_LIMIT:
            oo.milp.time_limit_s = x;
            fixed_limit = 1;
            break;
        default: time_limit = x; break; /* O_TIME_LIMIT */
        }
    }
    if (optind < argc) {
        fprintf(stderr, "bench_online: unexpected argument %s (see --help)\n", argv[optind]);
        return 2;
    }
    if (oo.commit_m > oo.window_m) {
        fprintf(stderr, "bench_online: --commit must not exceed --window\n");
        return 2;
    }
    hv_config_t cfg;
    char err[512];
    if (hv_config_load(cfg_path, &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "bench_online: %s\n", err);
        return 1;
    }
    cfg.row_length_m = length;
    cfg.pick_cycle = 1; /* the robot's time: what the vehicle really spends */
    oo.limit_min_s = cfg.online_limit_min_s;
    oo.limit_max_s = cfg.online_limit_max_s;
    char limit[96];
    snprintf(limit, sizeof limit,
             fixed_limit ? "%.0f s per horizon" : "half the work ahead per horizon, %.0f to %.0f s",
             fixed_limit ? oo.milp.time_limit_s : oo.limit_min_s, oo.limit_max_s);
    printf("bench_online: %s; camera lead %.2f m, window %.2f m; horizon %.2f m, commit %.2f m, "
           "%s; offline limit %.0f s\n",
           cfg_path, cfg.camera_lead_m, cfg.camera_window_m, oo.window_m, oo.commit_m, limit,
           time_limit);
    int rc = 0;
    for (int i = 0; i < n_alphas && rc == 0; ++i) {
        rc = bench_row(&cfg, alphas[i], seed, &oo, fixed_limit, time_limit);
    }
    return rc == 0 ? 0 : 1;
}
