/* harvest-plan-online: the online planner as its own process (DESIGN §5). It reads the
 * camera's detections from LCM, plans horizon by horizon with hv_online_* and publishes
 * the committed plan for harvest-exec --online, while the executor works what is already
 * committed. `harvest-plan-online --help`. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "harvest_lcm_exec_state_t.h"
#include "harvest_lcm_plan_commit_t.h"
#include "hv/cli.h"
#include "hv/file_io.h"
#include "hv/json_quote.h"
#include "hv/plan_build.h"
#include "hv/plan_io.h"
#include "hv/plan_paths.h"
#include "hv/plan_status.h"
#include "hv/version.h"
#include "hv/pick_model.h"
#include "plan_online.h"

static const char k_prog[] = "harvest-plan-online";
#define REPUBLISH_S 2.0 /* wall s between repeats of the committed plan and the status */

static const char k_usage[] =
    "usage: harvest-plan-online --config CFG --lcm-url URL [options]\n"
    "\n"
    "The online planner (DESIGN §5): fruit is revealed by the camera ahead of the vehicle\n"
    "(camera_frame_t on HARVEST_CAMERA, e.g. from `python -m harvest sim --fruits MAP`);\n"
    "each horizon of --window m is solved by the MILP and its first --commit m committed\n"
    "once the camera has seen all its stops can reach. The committed plan (plan_commit_t on\n"
    "HARVEST_PLAN_COMMIT) goes to `harvest-exec --online`, after each horizon and every\n"
    "2 s; committed stops never change. Each pick costs the executor's cycle (exact IK,\n"
    "plan.pick_cycle of the config, whole ms).\n"
    "\n"
    "Bad detections are refused, logged with their reason and counted, never planned:\n"
    "outside_row (y off the row or not a number), duplicate (a fruit id already known: the\n"
    "first detection stands), late (every stop that reaches it is committed), bad_id (not\n"
    "of the fruit id set).\n"
    "\n"
    "The camera's replay: as it starts (fresh or resumed) and after a lost camera frame (a\n"
    "gap in its seq), the planner asks the camera to send again every fruit it revealed\n"
    "(camera_replay_t on HARVEST_CAMERA_REPLAY, every second until it comes) and takes no\n"
    "view of the row before it: fruit revealed while the planner was down is recovered, or\n"
    "counted lost when every stop that reaches it is committed. The camera's first frame\n"
    "(seq 0) needs no replay.\n"
    "\n"
    "Status: planner_status_t on HARVEST_PLANNER_STATUS, on each change, every 2 s and as\n"
    "it ends: camera_wait (no frame yet), camera_sync (waiting for the replay), planning,\n"
    "done; or refused (bad input: config, options, journal), failed (a horizon, the\n"
    "journal's disk), ended (interrupted, the executor stopped), with the reason as\n"
    "printed; each detection refused, and the replay's counts. harvest-exec --online shows\n"
    "it, and names it when it waits for a plan.\n"
    "\n"
    "options:\n"
    "  --config CFG       harvest.cfg (row, arms, camera.lead / camera.window), required\n"
    "  --lcm-url URL      LCM URL (udpm://...?ttl=0), required\n"
    "  --window H         horizon solved per step, m (default 2)\n"
    "  --commit M         committed per step, m (default 1, at most H)\n"
    "  --time-limit S     MILP limit per horizon, s (default: half the robot time committed\n"
    "                     ahead of the executor when the horizon starts, within the\n"
    "                     config's online.horizon_limit_min and online.horizon_limit_max;\n"
    "                     robot time as at time scale 1: a faster simulated run wants a\n"
    "                     fixed --time-limit)\n"
    "  --threads N        1 or 2 (default): the MILP's second thread; 1 leaves a core to the\n"
    "                     executor and the simulator on a 2-core machine\n"
    "  --progress S       a progress line every S s of wall time (default 5; 0: per horizon\n"
    "                     only)\n"
    "  --journal FILE     what the planner saw and committed, durable before the plan is\n"
    "                     published (created, or resumed): a restart with the same file\n"
    "                     goes on from there and never commits a stop differently, so the\n"
    "                     executor's journalled stops stay valid. Without it a restart\n"
    "                     starts over from the camera's replay, and harvest-exec refuses\n"
    "                     whatever of its plan contradicts the executor's journal\n"
    "  --summary FILE     write a JSON summary at the end (detections per verdict, the\n"
    "                     camera's replays: replayed, recovered, lost)\n"
    "  --out PLAN.json    write the committed plan at the end, in the plan format\n"
    "                     (docs/PLAN_FORMAT.md, no fruit map named: the camera was the input);\n"
    "                     `harvest-plan check PLAN.json --fruits MAP.csv` verifies it\n"
    "  --quiet            no progress lines (refusals and errors are still printed)\n"
    "  --help             this text\n"
    "  --version          the version and exit\n"
    "\n"
    "It ends once the whole row is committed and the executor reports row_done, when the\n"
    "executor reports safe or stopped (HARVEST_EXEC_STATE), or on SIGINT / SIGTERM (which\n"
    "also stop a horizon's solve).\n"
    "\n" HV_EXIT_CODES_HELP ",\n"
    "4 the executor stopped in the safe state, 5 interrupted before the row was planned,\n"
    "6 the executor made a controlled stop)\n";

static atomic_int g_stop; /* set by SIGINT / SIGTERM: the only process-wide state */

static void on_signal(int sig)
{
    (void)sig;
    atomic_store(&g_stop, 1);
}

static int stop_requested(void *ctx)
{
    (void)ctx;
    return atomic_load(&g_stop);
}

static void on_exec_state(const lcm_recv_buf_t *rbuf, const char *channel,
                          const harvest_lcm_exec_state_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    po_app_t *a = user;
    a->exec_seen = 1;
    a->exec_stop = m->stop;
    a->exec_picked = m->picked;
    a->exec_vehicle_m = m->vehicle_position_m;
    snprintf(a->exec_phase, sizeof a->exec_phase, "%s", m->phase);
}

/* Robot time committed ahead of the executor: the committed stops after the one it is at
 * (that one's rest is not counted), from there; 0 before it is heard. */
static double work_ahead_s(const po_app_t *a, const hv_config_t *cfg)
{
    if (!a->exec_seen || a->exec_stop < 0 || (size_t)a->exec_stop >= a->o.n_stops) {
        return 0.0;
    }
    size_t k = (size_t)a->exec_stop;
    return hv_online_ahead_s(&a->o, k + 1, a->o.stops[k].y_m, cfg->vehicle_speed_mps);
}

/* The committed plan so far, whole (plan_commit_t.lcm says why). */
static int publish(po_app_t *a)
{
    const hv_online_t *o = &a->o;
    harvest_lcm_plan_commit_t m;
    memset(&m, 0, sizeof m);
    m.utime = po_wall_utime();
    m.row_start_m = o->params.row_start_m;
    m.row_length_m = o->params.row_length_m;
    m.stop_margin_m = o->params.stop_margin_m;
    m.commit_y_m = hv_online_commit_y(o);
    m.final = (int8_t)o->done;
    m.n_stops = (int32_t)o->n_stops;
    m.n_picks = (int32_t)o->n_order;
    size_t ns = o->n_stops ? o->n_stops : 1, np = o->n_order ? o->n_order : 1;
    m.stop_index = malloc(ns * sizeof *m.stop_index);
    m.stop_y_m = malloc(ns * sizeof *m.stop_y_m);
    m.stop_left = malloc(ns * sizeof *m.stop_left);
    m.stop_picks = malloc(ns * sizeof *m.stop_picks);
    m.picks = calloc(np, sizeof *m.picks);
    m.cost_s = malloc(np * sizeof *m.cost_s);
    char *ids = calloc(np, HV_FRUIT_ID_LEN);
    int rc = -1;
    if (m.stop_index && m.stop_y_m && m.stop_left && m.stop_picks && m.picks && m.cost_s && ids) {
        for (size_t s = 0; s < o->n_stops; ++s) {
            const hv_online_stop_t *st = &o->stops[s];
            m.stop_index[s] = (int32_t)st->index;
            m.stop_y_m[s] = st->y_m;
            m.stop_picks[s] = (int16_t)st->count;
            m.stop_left[s] = 0;
            for (size_t k = 0; k < st->count; ++k) {
                size_t i = st->first + k;
                const hv_fruit_t *f = &o->fruits[o->fruit_of[i]];
                harvest_lcm_detection_t *d = &m.picks[i];
                memcpy(ids + i * HV_FRUIT_ID_LEN, f->id, HV_FRUIT_ID_LEN);
                d->fruit_id = ids + i * HV_FRUIT_ID_LEN;
                d->side = f->side == HV_SIDE_LEFT ? 0 : 1;
                d->x_m = f->x_m;
                d->y_m = f->y_m;
                d->z_m = f->z_m;
                d->yaw_rad = f->yaw_rad;
                hv_pick_why_t why;
                double c = 0.0;
                o->model->cost(o->model->ctx, f, st->y_m, &c, &why);
                m.cost_s[i] = c;
                m.stop_left[s] = (int16_t)(m.stop_left[s] + (f->side == HV_SIDE_LEFT));
            }
        }
        rc = harvest_lcm_plan_commit_t_publish(a->lcm, "HARVEST_PLAN_COMMIT", &m);
    }
    free(m.stop_index);
    free(m.stop_y_m);
    free(m.stop_left);
    free(m.stop_picks);
    free(m.picks);
    free(m.cost_s);
    free(ids);
    return rc;
}

static const char *solve_name(hv_solve_status_t s)
{
    switch (s) {
    case HV_SOLVE_OPTIMAL: return "optimal";
    case HV_SOLVE_FEASIBLE: return "feasible";
    case HV_SOLVE_NO_SOLUTION: return "no solution";
    default: return "error";
    }
}

static void progress(const po_app_t *a, const char *what)
{
    const hv_online_t *o = &a->o;
    char exec[128] = "executor not heard yet";
    if (a->exec_seen) {
        snprintf(exec, sizeof exec,
                 "executor %s at stop %d of %zu, %d picked, vehicle at %.2f "
                 "m (%.2f m behind the commit line)",
                 a->exec_phase, a->exec_stop + 1, o->n_stops, a->exec_picked, a->exec_vehicle_m,
                 hv_online_commit_y(o) - a->exec_vehicle_m);
    }
    char camera[128] = "";
    if (!a->synced)
        snprintf(camera, sizeof camera, "; waiting for the camera's replay (asked %u times)",
                 a->replay.requests);
    else if (a->replay.replays)
        snprintf(camera, sizeof camera, "; replayed %u: %u recovered, %u lost", a->replay.replayed,
                 a->replay.recovered, a->replay.lost);
    fprintf(stderr,
            "harvest-plan-online: %s: seen to %.2f m, committed to %.2f m%s: %zu stops, "
            "%zu fruits; refused %u outside_row, %u duplicate, %u late, %u bad_id%s; %s\n",
            what, o->seen_to_m, hv_online_commit_y(o), o->done ? " (final)" : "", o->n_stops,
            o->n_order, o->counts[HV_DET_OUTSIDE_ROW], o->counts[HV_DET_DUPLICATE],
            o->counts[HV_DET_LATE], a->bad_id, camera, exec);
}

static int cmp_double(const void *x, const void *y)
{
    double p = *(const double *)x, q = *(const double *)y;
    return p < q ? -1 : p > q;
}

static void write_summary(const char *path, po_app_t *a)
{
    const hv_online_t *o = &a->o;
    const po_replay_counts_t *r = &a->replay;
    qsort(a->solve_s, a->n_solves, sizeof *a->solve_s, cmp_double);
    char buf[4096], err[256], reason[2 * PO_REASON_LEN], refusal[600];
    int n =
        snprintf(buf, sizeof buf,
                 "{\n  \"done\": %s,\n  \"state\": \"%s\",\n  \"reason\": %s,\n  \"stops\": %zu,\n"
                 "  \"fruits_committed\": %zu,\n"
                 "  \"detections\": {\"accepted\": %u, \"unreachable\": %u, \"outside_row\": %u, "
                 "\"duplicate\": %u, \"late\": %u, \"bad_id\": %u},\n  \"last_refusal\": %s,\n"
                 "  \"frames\": %u,\n  \"frames_lost\": %u,\n"
                 "  \"camera_replay\": {\"requests\": %u, \"replays\": %u, \"replayed\": %u, "
                 "\"recovered\": %u, \"lost\": %u},\n  \"horizons\": %zu,\n"
                 "  \"horizons_optimal\": %u,\n  \"horizon_s_median\": %.6f,\n  \"horizon_s_max\": "
                 "%.6f\n}\n",
                 o->done ? "true" : "false", a->end_state ? a->end_state : "ended",
                 hv_json_quote(a->reason, reason, sizeof reason), o->n_stops, o->n_order,
                 o->counts[HV_DET_ACCEPTED], o->counts[HV_DET_UNREACHABLE],
                 o->counts[HV_DET_OUTSIDE_ROW], o->counts[HV_DET_DUPLICATE], o->counts[HV_DET_LATE],
                 a->bad_id, hv_json_quote(a->last_refusal, refusal, sizeof refusal), a->frames,
                 a->frames_lost, r->requests, r->replays, r->replayed, r->recovered, r->lost,
                 a->n_solves, o->steps_optimal, a->n_solves ? a->solve_s[a->n_solves / 2] : 0.0,
                 a->n_solves ? a->solve_s[a->n_solves - 1] : 0.0);
    if (n < 0 || (size_t)n >= sizeof buf ||
        hv_file_write_atomic(path, buf, (size_t)n, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-plan-online: %s: cannot write the summary\n", path);
    }
}

/* The committed plan as a plan file (docs/PLAN_FORMAT.md). */
static int write_plan(const char *out, const char *config, const hv_config_t *cfg,
                      const po_app_t *a)
{
    const hv_online_t *o = &a->o;
    char err[512] = "", cfg_rel[HV_PLAN_PATH_LEN];
    hv_instance_t inst;
    hv_assignment_t as = {0, NULL};
    hv_plan_t plan;
    memset(&plan, 0, sizeof plan);
    hv_diag_t diag;
    hv_status_t st = hv_plan_input_relative(out, config, cfg_rel, sizeof cfg_rel, err, sizeof err);
    int built = 0;
    if (st == HV_OK) {
        st = hv_instance_build(&o->params, o->fruits, o->n_fruits, o->model, &inst, &diag);
        built = st == HV_OK;
    }
    if (st == HV_OK) {
        st = hv_assignment_alloc(&as, o->n_fruits);
    }
    if (st == HV_OK) {
        st = hv_online_assignment(o, &as);
    }
    if (st == HV_OK) {
        hv_plan_meta_t meta;
        memset(&meta, 0, sizeof meta);
        meta.method = "milp";
        meta.fruit_map = "";
        meta.cost_table_left = "";
        meta.cost_table_right = "";
        meta.config = cfg_rel;
        meta.pick_time = hv_pick_model_name(cfg);
        meta.params = o->params;
        meta.vehicle_speed_mps = cfg->vehicle_speed_mps;
        meta.solver_status = o->steps_optimal == o->steps ? "optimal" : "feasible";
        meta.gap = -1.0;
        meta.time_limit_s = o->opt.milp.time_limit_s;
        meta.horizon.used = 1;
        meta.horizon.window_m = o->opt.window_m;
        meta.horizon.commit_m = o->opt.commit_m;
        meta.horizon.windows = o->steps;
        meta.horizon.windows_optimal = o->steps_optimal;
        st = hv_plan_build(&inst, &as, NULL, &meta, &plan);
    }
    if (st == HV_OK) {
        st = hv_plan_save(out, &plan, err, sizeof err);
    }
    if (st != HV_OK) {
        fprintf(stderr, "harvest-plan-online: %s: the plan was not written: %s\n", out,
                err[0] ? err : hv_plan_status_name(st));
    }
    hv_plan_free(&plan);
    hv_assignment_free(&as);
    if (built) {
        hv_instance_free(&inst);
    }
    return st == HV_OK ? 0 : -1;
}

static int parse_pos(const char *flag, const char *text, double *out, int zero_ok)
{
    char *end = NULL;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(v) || v < 0 || (v == 0 && !zero_ok)) {
        fprintf(stderr, "harvest-plan-online: %s: expected a positive number, got \"%s\"\n", flag,
                text);
        return -1;
    }
    *out = v;
    return 0;
}

typedef struct args {
    const char *config, *url, *summary, *out, *journal;
    double progress_s, fixed_limit_s; /* fixed_limit_s 0: the limit follows the work ahead */
    int quiet;
    hv_online_options_t opt;
} args_t;

/* The command line into *g; -1 to go on, else the exit code (help, version, usage). */
static int parse_args(int argc, char **argv, args_t *g)
{
    memset(g, 0, sizeof *g);
    g->progress_s = 5.0;
    hv_online_options_default(&g->opt);
    enum {
        O_CONFIG = 256,
        O_LCM_URL,
        O_SUMMARY,
        O_OUT,
        O_JOURNAL,
        O_WINDOW,
        O_COMMIT,
        O_TIME_LIMIT,
        O_PROGRESS,
        O_THREADS,
        O_QUIET
    };
    static const struct option longopts[] = {
        {"config", required_argument, NULL, O_CONFIG},
        {"lcm-url", required_argument, NULL, O_LCM_URL},
        {"summary", required_argument, NULL, O_SUMMARY},
        {"out", required_argument, NULL, O_OUT},
        {"journal", required_argument, NULL, O_JOURNAL},
        {"window", required_argument, NULL, O_WINDOW},
        {"commit", required_argument, NULL, O_COMMIT},
        {"time-limit", required_argument, NULL, O_TIME_LIMIT},
        {"progress", required_argument, NULL, O_PROGRESS},
        {"threads", required_argument, NULL, O_THREADS},
        {"quiet", no_argument, NULL, O_QUIET},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    opterr = 0;
    int o, idx = 0;
    while ((o = getopt_long(argc, argv, ":h", longopts, &idx)) != -1) {
        const char *v = optarg;
        char f[32]; /* the option's name for messages, also when written --name=value */
        snprintf(f, sizeof f, "--%s", o >= O_CONFIG ? longopts[idx].name : "");
        int bad = 0;
        switch (o) {
        case 'h': fputs(k_usage, stdout); return 0;
        case 'V': printf("harvest-plan-online %s\n", HV_VERSION); return 0;
        case O_QUIET: g->quiet = 1; break;
        case O_CONFIG: g->config = v; break;
        case O_LCM_URL: g->url = v; break;
        case O_SUMMARY: g->summary = v; break;
        case O_OUT: g->out = v; break;
        case O_JOURNAL: g->journal = v; break;
        case O_WINDOW: bad = parse_pos(f, v, &g->opt.window_m, 0); break;
        case O_COMMIT: bad = parse_pos(f, v, &g->opt.commit_m, 0); break;
        case O_TIME_LIMIT: bad = parse_pos(f, v, &g->fixed_limit_s, 0); break;
        case O_PROGRESS: bad = parse_pos(f, v, &g->progress_s, 1); break;
        case O_THREADS:
            bad = strcmp(v, "1") != 0 && strcmp(v, "2") != 0;
            if (bad) {
                fprintf(stderr, "harvest-plan-online: --threads: expected 1 or 2, got \"%s\"\n", v);
            } else if (v[0] == '1') {
                g->opt.milp.helper_thread = 0;
                g->opt.milp.tree_threads = 1;
            }
            break;
        default: hv_cli_option_error(k_prog, o, optopt, argv[optind - 1]); return HV_EXIT_USAGE;
        }
        if (bad) {
            return HV_EXIT_USAGE;
        }
    }
    if (optind < argc) {
        hv_cli_usage_error(k_prog, argv[optind], "unexpected argument");
        return HV_EXIT_USAGE;
    }
    if (g->config == NULL || g->url == NULL) {
        hv_cli_usage_error(k_prog, g->config == NULL ? "--config" : "--lcm-url", "required");
        return HV_EXIT_USAGE;
    }
    if (g->opt.commit_m > g->opt.window_m) {
        hv_cli_usage_error(k_prog, "--commit", "must not exceed --window");
        return HV_EXIT_USAGE;
    }
    return -1;
}

/* What must outlive the online module: the config and its pick model. */
typedef struct world {
    hv_config_t cfg;
    hv_ik_model_t ik;
    hv_pick_model_t model;
    hv_online_journal_t journal;
} world_t;

/* The config, the online module and the journal (resumed); the exit code on a refusal (it is
 * published: the LCM is open), else HV_EXIT_OK. */
static int setup(po_app_t *a, args_t *g, world_t *w)
{
    char err[512];
    if (hv_config_load(g->config, &w->cfg, err, sizeof err) != HV_OK) {
        return po_refuse(a, HV_EXIT_USAGE, "%s", err);
    }
    if (w->cfg.pick_cost_flat) { /* its costs are laid out over the config's whole row */
        return po_refuse(a, HV_EXIT_USAGE,
                         "%s: plan.pick_cost_flat = 1 is the experiments' offline cost "
                         "variant, not the robot's times",
                         g->config);
    }
    if (hv_pick_model_ik(&w->cfg, &w->ik, &w->model) != HV_OK) {
        return po_refuse(a, HV_EXIT_USAGE, "%s: an arm reaches none of its fruit area", g->config);
    }
    hv_instance_params_t par;
    hv_instance_params_from_config(&w->cfg, &w->model, &par);
    g->opt.milp.stop = stop_requested;
    g->opt.limit_min_s = w->cfg.online_limit_min_s;
    g->opt.limit_max_s = w->cfg.online_limit_max_s;
    /* the plan records the longest a horizon may take */
    g->opt.milp.time_limit_s = g->fixed_limit_s > 0.0 ? g->fixed_limit_s : g->opt.limit_max_s;
    hv_status_t ist = hv_online_init(&a->o, &par, &w->model, &g->opt);
    if (ist != HV_OK) {
        return po_refuse(a, HV_EXIT_USAGE, "%s: cannot plan with this config and these options: %s",
                         g->config, hv_plan_status_name(ist));
    }
    if (g->journal == NULL) {
        return HV_EXIT_OK;
    }
    hv_status_t jst = hv_online_journal_open(&w->journal, g->journal, &a->o, err, sizeof err);
    if (jst != HV_OK) {
        /* a journal that cannot be opened or written is a failure; one of another row, bad
         * input */
        return po_refuse(a,
                         jst == HV_ERR_IO || jst == HV_ERR_NOMEM ? HV_EXIT_FAILURE : HV_EXIT_USAGE,
                         "%s", err);
    }
    a->journal = &w->journal;
    if (w->journal.detections > 0 && !g->quiet) {
        fprintf(stderr,
                "harvest-plan-online: resumed from %s: %u detections, %u horizons "
                "(%zu stops, committed to %.2f m%s) as they were%s\n",
                g->journal, w->journal.detections, w->journal.horizons, a->o.n_stops,
                hv_online_commit_y(&a->o), a->o.done ? ", final" : "",
                w->journal.torn_bytes ? "; a torn end was cut off" : "");
    }
    return HV_EXIT_OK;
}

/* Solve every horizon that can be committed now; the exit code when one fails. */
static int plan_horizons(po_app_t *a, const args_t *g, const world_t *w, double *last_pub)
{
    while (hv_online_ready(&a->o) && !atomic_load(&g_stop)) {
        double t0 = po_now_s();
        hv_online_step_result_t r;
        size_t pos = a->o.pos;
        hv_status_t sst = g->fixed_limit_s > 0.0
                              ? hv_online_step(&a->o, &r)
                              : hv_online_step_ahead(&a->o, work_ahead_s(a, &w->cfg), &r);
        if (sst != HV_OK) {
            return po_refuse(a, HV_EXIT_FAILURE, "horizon %zu at %.2f m: failed to plan: %s",
                             a->n_solves + 1, hv_online_commit_y(&a->o), hv_plan_status_name(sst));
        }
        /* durable before anyone may act on it */
        if (a->journal != NULL && a->o.pos != pos &&
            hv_online_journal_horizon(a->journal, &a->o, r.stops_from) != HV_OK) {
            return po_refuse(a, HV_EXIT_FAILURE, "%s: journal write failed: %s", a->journal->path,
                             strerror(errno));
        }
        double dt = po_now_s() - t0;
        if (a->n_solves < PO_MAX_HORIZONS) {
            a->solve_s[a->n_solves++] = dt;
        }
        publish(a);
        po_status_publish(a);
        *last_pub = po_now_s();
        if (!g->quiet) {
            char what[160];
            snprintf(what, sizeof what,
                     "horizon %zu (%zu fruits, %s%s, %.2f s of %.1f s) committed "
                     "%zu stops",
                     a->n_solves, r.window_fruits, solve_name(r.status),
                     r.kept_heuristic ? ", kept the FOV plan" : "", dt, r.limit_s,
                     r.stops_to - r.stops_from);
            progress(a, what);
        }
        /* what arrived meanwhile is taken before the next horizon */
        while (lcm_handle_timeout(a->lcm, 0) > 0)
            ;
        if (a->fatal_rc) {
            return a->fatal_rc;
        }
    }
    return HV_EXIT_OK;
}

/* Until the row is committed and the executor reports row_done, it stops, or a signal. */
static int run(po_app_t *a, const args_t *g, const world_t *w)
{
    double last_pub = 0.0, last_progress = po_now_s();
    while (!atomic_load(&g_stop)) {
        lcm_handle_timeout(a->lcm, 20);
        while (lcm_handle_timeout(a->lcm, 0) > 0)
            ;
        if (a->fatal_rc) {
            return a->fatal_rc;
        }
        po_camera_poll(a);
        int rc = plan_horizons(a, g, w, &last_pub);
        if (rc != HV_EXIT_OK) {
            return rc;
        }
        double t = po_now_s();
        if (t - last_pub >= REPUBLISH_S) {
            publish(a);
            po_status_publish(a);
            last_pub = t;
        } else if (a->status_changed) {
            po_status_publish(a);
        }
        if (!g->quiet && g->progress_s > 0 && t - last_progress >= g->progress_s) {
            progress(a, "progress");
            last_progress = t;
        }
        if (a->exec_seen && strcmp(a->exec_phase, "safe") == 0) {
            snprintf(a->reason, sizeof a->reason,
                     "harvest-plan-online: the executor stopped in the safe state");
            fprintf(stderr, "%s\n", a->reason);
            return HV_EXIT_ONLINE_EXEC_SAFE;
        }
        if (a->exec_seen && strcmp(a->exec_phase, "stopped") == 0) {
            snprintf(a->reason, sizeof a->reason,
                     "harvest-plan-online: the executor made a controlled stop");
            fprintf(stderr, "%s\n", a->reason);
            return HV_EXIT_ONLINE_EXEC_STOPPED;
        }
        if (a->o.done && a->exec_seen && strcmp(a->exec_phase, "row_done") == 0) {
            return HV_EXIT_OK;
        }
    }
    if (a->o.done) {
        return HV_EXIT_OK;
    }
    snprintf(a->reason, sizeof a->reason,
             "harvest-plan-online: interrupted before the row was planned");
    return HV_EXIT_ONLINE_INTERRUPTED;
}

int main(int argc, char **argv)
{
    args_t g;
    int rc = parse_args(argc, argv, &g);
    if (rc >= 0) {
        return rc;
    }
    po_app_t *a = calloc(1, sizeof *a);
    world_t *w = calloc(1, sizeof *w);
    if (a == NULL || w == NULL) {
        fprintf(stderr, "harvest-plan-online: out of memory\n");
        free(a);
        free(w);
        return HV_EXIT_FAILURE;
    }
    a->quiet = g.quiet;
    /* before the journal is made: a stop asked for while it is written is a stop, not death */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    /* first, so that a refusal of what follows reaches the executor */
    a->lcm = lcm_create(g.url);
    if (a->lcm == NULL) {
        fprintf(stderr, "harvest-plan-online: --lcm-url %s: LCM could not be opened\n", g.url);
        free(a);
        free(w);
        return HV_EXIT_FAILURE;
    }
    rc = setup(a, &g, w);
    if (rc != HV_EXIT_OK) {
        /* nothing was planned: no summary, no plan */
        hv_online_journal_close(a->journal);
        hv_online_free(&a->o);
        lcm_destroy(a->lcm);
        free(a);
        free(w);
        return rc;
    }
    harvest_lcm_exec_state_t_subscription_t *exec_sub =
        harvest_lcm_exec_state_t_subscribe(a->lcm, "HARVEST_EXEC_STATE", on_exec_state, a);
    po_camera_open(a);
    char limit_text[128];
    if (g.fixed_limit_s > 0.0) {
        snprintf(limit_text, sizeof limit_text, "%.1f s per horizon", g.fixed_limit_s);
    } else {
        snprintf(limit_text, sizeof limit_text,
                 "a horizon takes half the robot time committed ahead, %.1f to %.1f s",
                 g.opt.limit_min_s, g.opt.limit_max_s);
    }
    if (!g.quiet) {
        fprintf(stderr,
                "harvest-plan-online: row %.2f m, camera %.2f m from %.2f m ahead, "
                "horizon %.2f m, commit %.2f m, %s; waiting for the camera\n",
                w->cfg.row_length_m, w->cfg.camera_window_m, w->cfg.camera_lead_m, g.opt.window_m,
                g.opt.commit_m, limit_text);
    }
    rc = run(a, &g, w);
    if (a->end_state == NULL) { /* not refused nor failed: done, or ended for a reason */
        a->end_state = rc == HV_EXIT_OK ? "done" : "ended";
    }
    po_status_publish(a);
    if (!g.quiet) {
        progress(a, "end");
    }
    if (g.summary != NULL) {
        write_summary(g.summary, a);
    }
    if (g.out != NULL && a->o.done && write_plan(g.out, g.config, &w->cfg, a) != 0 &&
        rc == HV_EXIT_OK) {
        rc = HV_EXIT_FAILURE;
    }
    po_camera_close(a);
    harvest_lcm_exec_state_t_unsubscribe(a->lcm, exec_sub);
    lcm_destroy(a->lcm);
    hv_online_journal_close(a->journal);
    hv_online_free(&a->o);
    free(a);
    free(w);
    return rc;
}
