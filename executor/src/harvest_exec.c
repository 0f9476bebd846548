/* harvest-exec: run a plan on the CAN bus (DESIGN §7). See --help. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "hv/cli.h"
#include "hv/config.h"
#include "hv/exec_can.h"
#include "hv/exec_journal.h"
#include "hv/exec_loop.h"
#include "hv/exec_plan_json.h"
#include "hv/exec_port_linux.h"
#include "hv/exec_status.h"
#include "hv/exec_telemetry.h"
#include "hv/file_io.h"
#include "hv/json_quote.h"
#include "hv/pick.h"

#include "harvest_exec_args.h"

/* The only mutable global: a signal handler can reach nothing else. */
static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    if (stop_requested < 2)
        stop_requested++; /* the first: a controlled stop; the second: e-stop */
}

/* Everything the run needs, allocated once at start-up. */
typedef struct world {
    hv_exec_plan_t plan;
    hv_exec_sm_t sm;
    hv_exec_progress_t prog;
    hv_exec_journal_t journal;
    hv_can_bus_t bus;
    hv_exec_telemetry_t tm;
    hv_exec_port_linux_t linux_port;
    hv_exec_port_t port; /* the loop's I/O: clock, bus, journal */
    hv_exec_loop_t loop;
    hv_exec_feed_t feed; /* online */
    hv_exec_feed_stats_t feed_stats;
    char planner_note[HV_EXEC_PLANNER_REASON_LEN + 96]; /* the feed's last line on the planner */
    int journal_open, bus_open, tm_open;                /* what close_world closes */
} world_t;

/* Online: what the planner said of itself as last heard, and the feed's line on it (in a
 * wait, why no plan came), for the summary. */
static int planner_summary(const world_t *w, char *buf, size_t n)
{
    const hv_exec_planner_heard_t *h = &w->feed_stats.planner;
    char note[2 * sizeof w->planner_note], state[2 * sizeof h->state], reason[2 * sizeof h->reason],
        refusal[2 * sizeof h->last_refusal];
    return snprintf(buf, n,
                    "  \"planner\": %s,\n  \"planner_state\": %s,\n  \"planner_reason\": %s,\n"
                    "  \"planner_last_refusal\": %s,\n  \"planner_refused\": %u,\n"
                    "  \"camera_replays\": %u,\n  \"camera_replayed\": %u,\n"
                    "  \"camera_recovered\": %u,\n  \"camera_lost\": %u\n",
                    hv_json_quote(w->planner_note, note, sizeof note),
                    hv_json_quote(h->state, state, sizeof state),
                    hv_json_quote(h->reason, reason, sizeof reason),
                    hv_json_quote(h->last_refusal, refusal, sizeof refusal), h->refused, h->replays,
                    h->replayed, h->recovered, h->lost);
}

static void write_summary(const exec_args_t *o, const world_t *w, double wall_s, double cpu_s,
                          long peak_rss_kb)
{
    const hv_exec_sm_t *sm = &w->sm;
    const hv_exec_loop_stats_t *st = &w->loop.st;
    char buf[8192], latched[64];
    double wait_first = 0.0, wait_row = 0.0;
    uint64_t now = w->port.now_ns(w->port.ctx);
    hv_exec_plan_wait_s(sm, now, &wait_first, &wait_row);
    hv_exec_node_list(sm->latched, latched, sizeof latched);
    unsigned outcome[HV_OUT_COUNT] = {0, 0, 0};
    /* what the transport dropped (datagrams that do not parse, CAN FD), beside the DBC
     * frames of a wrong length the loop dropped (frames_rx_malformed) */
    hv_can_stats_t cs;
    memset(&cs, 0, sizeof cs);
    hv_can_get_stats(&w->bus, &cs);
    for (uint16_t i = 0; i < w->plan.n_picks; i++)
        if (sm->prog.pick[i] == HV_PROG_DONE)
            outcome[sm->prog.outcome[i]]++;
    int n = snprintf(
        buf, sizeof buf,
        "{\n  \"phase\": \"%s\",\n  \"safe_reason\": \"%s\",\n  \"safe_node\": %d,\n"
        "  \"stop_reason\": \"%s\",\n"
        "  \"fruits_planned\": %u,\n  \"picked\": %u,\n  \"failed\": %u,\n  \"skipped\": %u,\n"
        "  \"remaining\": %u,\n  \"picked_this_run\": %u,\n  \"failed_this_run\": %u,\n"
        "  \"skipped_this_run\": %u,\n  \"faults\": %u,\n"
        "  \"planned_makespan_s\": %.6f,\n  \"expected_makespan_s\": %.6f,\n"
        "  \"executed_makespan_s\": %.6f,\n  \"time_scale\": %.6f,\n"
        "  \"wall_s\": %.6f,\n  \"cpu_s\": %.6f,\n  \"peak_rss_kb\": %ld,\n"
        "  \"steps\": %llu,\n  \"step_ns_mean\": %.1f,\n  \"step_ns_max\": %llu,\n"
        "  \"frames_rx\": %llu,\n  \"frames_tx\": %llu,\n  \"send_failures\": %llu,\n"
        "  \"frames_rx_malformed\": %llu,\n  \"bus_rx_malformed\": %llu,\n"
        "  \"bus_rx_unsupported\": %llu,\n"
        "  \"journal_records\": %llu,\n  \"journal\": \"%s\",\n  \"bus\": \"%s\",\n"
        "  \"estop_latched\": \"%s\",\n  \"estop_cleared\": %s,\n"
        "  \"safe_node_name\": \"%s\",\n  \"online\": %s,\n  \"plan_stops\": %u,\n"
        "  \"plan_final\": %s,\n  \"plan_wait_first_s\": %.6f,\n  \"plan_wait_row_s\": %.6f,\n"
        "  \"plan_waits\": %u,\n  \"plan_messages\": %u,\n  \"plan_refused\": %u,\n",
        hv_exec_phase_name(sm->phase), hv_exec_safe_reason_name(sm->safe_reason), sm->safe_node,
        hv_exec_stop_reason_name(sm->stop_reason), (unsigned)w->plan.n_picks,
        outcome[HV_OUT_PICKED], outcome[HV_OUT_FAILED], outcome[HV_OUT_SKIPPED],
        hv_exec_remaining(sm), sm->picked, sm->failed, sm->skipped, sm->faults,
        w->plan.planned_makespan_s, w->plan.expected_makespan_s, hv_exec_executed_s(sm, now),
        sm->time_scale, wall_s, cpu_s, peak_rss_kb, (unsigned long long)st->steps,
        st->steps ? (double)st->step_ns_total / (double)st->steps : 0.0,
        (unsigned long long)st->step_ns_max, (unsigned long long)st->frames_rx,
        (unsigned long long)st->io.frames_tx, (unsigned long long)st->io.send_failures,
        (unsigned long long)st->frames_rx_malformed, (unsigned long long)cs.rx_malformed,
        (unsigned long long)cs.rx_unsupported, (unsigned long long)st->io.journal_records,
        o->journal, hv_can_name(&w->bus), latched,
        sm->latched && sm->prm.clear_estop ? "true" : "false", hv_exec_node_name(sm->safe_node),
        o->online ? "true" : "false", (unsigned)w->plan.n_stops, sm->plan_final ? "true" : "false",
        wait_first, wait_row, sm->waits, w->feed_stats.messages, w->feed_stats.refused);
    if (n > 0 && (size_t)n < sizeof buf) {
        int k = planner_summary(w, buf + n, sizeof buf - (size_t)n);
        n = k < 0 ? k : n + k;
    }
    if (n > 0 && (size_t)n + 2 < sizeof buf)
        n += snprintf(buf + n, sizeof buf - (size_t)n, "}\n");
    else
        n = -1;
    char err[256];
    if (n < 0 || (size_t)n >= sizeof buf ||
        hv_file_write_atomic(o->summary, buf, (size_t)n, err, sizeof err) != HV_OK)
        fprintf(stderr, "harvest-exec: %s: cannot write the summary\n", o->summary);
}

/* Peak resident memory of this program (kB): VmHWM, which execve resets; ru_maxrss is not
 * used because Linux carries it over from the parent that forked us. -1 when unknown. */
static long peak_rss_kb(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "VmHWM: %ld kB", &kb) == 1)
            break;
    if (f)
        fclose(f);
    return kb;
}

/* What start-up takes from the config: the arms, how far beyond the row's ends they
 * reach, the timing the plan is prepared with and the state machine's parameters. */
typedef struct setup {
    hv_config_t cfg;
    hv_arm_t arms[2];
    double margin_m;
    hv_exec_timing_t timing;
    hv_exec_params_t prm;
} setup_t;

/* main's steps return an exit code, or GO_ON when the run goes on. */
#define GO_ON (-1)

/* The config, the arms, the cost tables (checked, not used: the IK decides every pick,
 * hv/pick.h) and the stop margin the arms reach. */
static int load_config(const exec_args_t *o, setup_t *s)
{
    char err[512];
    if (hv_config_load(o->config, &s->cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        return HV_EXIT_USAGE;
    }
    for (int side = 0; side < 2; side++) {
        hv_config_arm(&s->cfg, (hv_side_t)side, &s->arms[side]);
        if (o->table[side] && hv_costtab_check_for(o->table[side], &s->cfg, (hv_side_t)side, err,
                                                   sizeof err) != HV_OK) {
            fprintf(stderr, "harvest-exec: %s\n", err);
            return HV_EXIT_USAGE;
        }
    }
    s->margin_m = 0.0;
    if (hv_pick_stop_margin(&s->cfg, &s->margin_m) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s: an arm reaches none of its fruit area\n", o->config);
        return HV_EXIT_USAGE;
    }
    s->timing = (hv_exec_timing_t){s->cfg.cut_s, s->cfg.release_s, s->cfg.vehicle_speed_mps,
                                   s->cfg.vehicle_accel_mps2};
    return GO_ON;
}

/* The plan file, prepared for these arms (online: the plan starts empty and grows from
 * the planner's messages); a line for each pick the IK refuses. */
static int load_plan(const exec_args_t *o, const setup_t *s, world_t *w)
{
    char err[512];
    hv_status_t st = o->online ? HV_OK : hv_exec_plan_load_json(o->plan, &w->plan, err, sizeof err);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        return HV_EXIT_USAGE;
    }
    if (w->plan.stop_margin_m > s->margin_m + 1e-9) {
        fprintf(stderr,
                "harvest-exec: %s: params.stop_margin_m: %g m beyond the row's ends, "
                "but from there no arm of %s reaches the row (at most %g m) (%s)\n",
                o->plan, w->plan.stop_margin_m, o->config, s->margin_m,
                hv_exec_status_name(HV_ERR_EXEC_PLAN_RANGE));
        return HV_EXIT_USAGE;
    }
    if ((st = hv_exec_plan_prepare(&w->plan, s->arms, &s->timing)) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s: cannot prepare the plan: %s\n", o->plan,
                hv_exec_status_name(st));
        return HV_EXIT_USAGE;
    }
    for (uint16_t i = 0; i < w->plan.n_picks; i++)
        if (!w->plan.picks[i].reachable)
            fprintf(stderr,
                    "harvest-exec: %s: fruit %s (%c): the IK finds no pose within the "
                    "joint limits (%s): it will be skipped\n",
                    o->plan, w->plan.picks[i].id, w->plan.picks[i].side == HV_SIDE_LEFT ? 'L' : 'R',
                    hv_status_name(w->plan.picks[i].ik_status));
    if (o->check_only) {
        printf("harvest-exec: %s: %u stops, %u picks, %u refused by the IK; expected makespan "
               "%.3f s (plan's objective %.3f s)\n",
               o->plan, (unsigned)w->plan.n_stops, (unsigned)w->plan.n_picks, w->plan.n_unreachable,
               w->plan.expected_makespan_s, w->plan.planned_makespan_s);
        return w->plan.n_unreachable ? HV_EXIT_EXEC_REFUSED : HV_EXIT_OK;
    }
    return GO_ON;
}

/* The journal, created or resumed (online: with the committed stops it holds, checked and
 * prepared as the planner's messages are); nothing to do when it says the row is done. */
static int open_journal(const exec_args_t *o, const setup_t *s, world_t *w)
{
    char err[512];
    hv_status_t st = o->online ? hv_exec_journal_open_online(&w->journal, o->journal, &w->plan,
                                                             &w->prog, err, sizeof err)
                               : hv_exec_journal_open(&w->journal, o->journal, &w->plan, &w->prog,
                                                      err, sizeof err);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        /* a journal that cannot be opened or written is a failure; one that does not
         * belong to this plan, bad input */
        return st == HV_ERR_EXEC_JOURNAL_IO || st == HV_ERR_NOMEM ? HV_EXIT_FAILURE : HV_EXIT_USAGE;
    }
    w->journal_open = 1;
    if (o->online && w->plan.n_stops &&
        (w->plan.stop_margin_m > s->margin_m + 1e-9 ||
         hv_exec_plan_prepare(&w->plan, s->arms, &s->timing) != HV_OK)) {
        fprintf(stderr,
                "harvest-exec: %s: the committed stops it holds cannot be run with %s "
                "(a stop margin beyond the arms' reach, or a stop off the course)\n",
                o->journal, o->config);
        return HV_EXIT_USAGE;
    }
    unsigned done = 0;
    for (uint16_t i = 0; i < w->plan.n_picks; i++)
        done += w->prog.pick[i] == HV_PROG_DONE;
    if (w->prog.row_done) {
        printf("harvest-exec: %s: the journal says this row is done (%u/%u fruits have an "
               "outcome): nothing to do\n",
               o->journal, done, (unsigned)w->plan.n_picks);
        return HV_EXIT_OK;
    }
    if (done || w->journal.records > 1)
        fprintf(stderr,
                "harvest-exec: resuming from %s: %u of %u fruits already have an "
                "outcome%s%s\n",
                o->journal, done, (unsigned)w->plan.n_picks,
                o->online ? "; the committed stops rebuilt from it" : "",
                w->journal.torn_bytes ? " (a torn last record was cut off)" : "");
    return GO_ON;
}

/* The state machine's parameters: the options' timeouts and margins, the config's timing,
 * the slower arm's homing. */
static void exec_params(const exec_args_t *o, setup_t *s)
{
    hv_exec_params_t *prm = &s->prm;
    hv_exec_params_default(prm);
    prm->time_scale = o->time_scale;
    prm->margin = o->margin;
    prm->slack_s = o->slack_s;
    prm->startup_timeout_s = o->startup_s;
    prm->heartbeat_timeout_s = o->hb_timeout_s;
    prm->latency_s = o->latency_s;
    prm->cut_s = s->cfg.cut_s;
    prm->release_s = s->cfg.release_s;
    prm->vehicle_speed_mps = s->cfg.vehicle_speed_mps;
    prm->vehicle_accel_mps2 = s->cfg.vehicle_accel_mps2;
    prm->max_retries = (unsigned)o->max_retries;
    prm->clear_estop = o->clear_by != NULL;
    prm->online = o->online;
    prm->wait_plan_timeout_s = s->cfg.online_wait_plan_timeout_s;
    double h0 = hv_exec_home_max_s(&s->arms[0]), h1 = hv_exec_home_max_s(&s->arms[1]);
    prm->home_max_s = h0 > h1 ? h0 : h1;
}

/* The bus, the telemetry sink and (online) the planner's feed. */
static int open_io(const exec_args_t *o, const setup_t *s, world_t *w)
{
    char err[512];
    hv_status_t st = strcmp(o->transport, "udp") == 0
                         ? hv_can_udp_open(&w->bus, o->channel, (uint16_t)o->port, NULL, NULL, 0)
                         : hv_can_socketcan_open(&w->bus, o->channel, NULL, 0);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s bus '%s': cannot open: %s (%s)\n", o->transport,
                o->channel, hv_can_status_name(st), strerror(hv_can_last_errno(&w->bus)));
        return HV_EXIT_FAILURE;
    }
    w->bus_open = 1;
    if (!o->lcm_url) {
        hv_exec_telemetry_null(&w->tm);
    } else if (hv_exec_telemetry_lcm_open(&w->tm, o->lcm_url, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        return HV_EXIT_FAILURE;
    }
    w->tm_open = 1;
    if (!o->online)
        return GO_ON;
#ifdef HV_WITH_LCM
    w->feed.log = o->quiet ? NULL : stderr;
    st = hv_exec_feed_lcm_open(&w->feed, o->lcm_url, &w->plan, s->arms, &s->timing, s->margin_m,
                               err, sizeof err);
#else
    (void)s;
    snprintf(err, sizeof err, "--online needs LCM: this build has none (HV_WITH_LCM=OFF)");
    st = HV_ERR_ARG;
#endif
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        return HV_EXIT_FAILURE;
    }
    w->loop.feed = &w->feed;
    return GO_ON;
}

/* Close what start-up opened (the feed is closed once the run has ended), and free. */
static void close_world(world_t *w)
{
    if (w->tm_open)
        hv_exec_telemetry_close(&w->tm);
    if (w->bus_open)
        hv_can_close(&w->bus);
    if (w->journal_open)
        hv_exec_journal_close(&w->journal);
    free(w);
}

/* Signals, the plan's telemetry and a first line, then the loop on the Linux port until
 * the row ends or the run stops: its status, and the clock at its start and end. */
static hv_status_t run_loop(const exec_args_t *o, const setup_t *s, world_t *w, uint64_t *t0,
                            uint64_t *t_end)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    hv_exec_tm_plan(&w->tm, &w->plan, o->plan ? o->plan : "(online)", &s->prm, o->time_scale,
                    (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000);
    if (!o->quiet && o->online)
        fprintf(stderr,
                "harvest-exec: online on %s: the plan grows from the planner's "
                "committed stops (HARVEST_PLAN_COMMIT on %s); waiting for the nodes\n",
                hv_can_name(&w->bus), o->lcm_url);
    else if (!o->quiet)
        fprintf(stderr,
                "harvest-exec: %u stops, %u fruits on %s; expected makespan %.1f s "
                "(plan's objective %.1f s); waiting for the nodes\n",
                (unsigned)w->plan.n_stops, (unsigned)w->plan.n_picks, hv_can_name(&w->bus),
                w->plan.expected_makespan_s, w->plan.planned_makespan_s);

    w->linux_port.bus = &w->bus;
    w->linux_port.journal = &w->journal;
    w->linux_port.clear_by = o->clear_by;
    w->linux_port.send_timeout_ms = 10;
    w->linux_port.wake_fd = o->online ? w->feed.fd : -1;
    hv_exec_port_linux(&w->port, &w->linux_port);
    w->loop.sm = &w->sm;
    w->loop.port = &w->port;
    w->loop.bus = &w->bus;
    w->loop.journal = &w->journal;
    w->loop.tm = &w->tm;
    w->loop.stop = &stop_requested;
    w->loop.progress = o->quiet ? NULL : stderr;
    w->loop.clear_by = o->clear_by;
    w->loop.tick_s = 0.01;
    w->loop.linger_s = 0.5; /* e-stops repeat meanwhile when safe */
    *t0 = w->port.now_ns(w->port.ctx);
    hv_status_t st = hv_exec_loop_run(&w->loop);
    *t_end = w->port.now_ns(w->port.ctx);
    return st;
}

/* The run's outcome: its exit code and the lines that say it (and how to go on); online,
 * the feed's refusals, and the feed closed. */
static int report(const exec_args_t *o, world_t *w, hv_status_t st, uint64_t t_end)
{
    const hv_exec_sm_t *sm = &w->sm;
    int rc = st != HV_OK                                ? HV_EXIT_FAILURE
             : sm->phase == HV_PH_ROW_DONE              ? HV_EXIT_OK
             : sm->phase == HV_PH_STOPPED               ? HV_EXIT_EXEC_STOPPED
             : sm->safe_reason == HV_SAFE_ESTOP_LATCHED ? HV_EXIT_EXEC_ESTOP_LATCHED
                                                        : HV_EXIT_EXEC_SAFE;
    /* an online plan has no objective of its own: the planner's horizons each had one */
    char objective[96];
    if (o->online)
        snprintf(objective, sizeof objective, "online, %u stops committed%s",
                 (unsigned)w->plan.n_stops, sm->plan_final ? ", final" : "");
    else
        snprintf(objective, sizeof objective, "plan's objective %.2f s",
                 w->plan.planned_makespan_s);
    int safe = sm->phase == HV_PH_SAFE, halted = sm->phase == HV_PH_STOPPED;
    printf("harvest-exec: %s%s%s: picked %u, failed %u, skipped %u this run (%u remaining), "
           "faults %u; executed %.2f s vs expected %.2f s (%s)\n",
           hv_exec_phase_name(sm->phase), safe || halted ? " " : "",
           safe     ? hv_exec_safe_reason_name(sm->safe_reason)
           : halted ? hv_exec_stop_reason_name(sm->stop_reason)
                    : "",
           sm->picked, sm->failed, sm->skipped, hv_exec_remaining(sm), sm->faults,
           hv_exec_executed_s(sm, t_end), w->plan.expected_makespan_s, objective);
    if (rc == HV_EXIT_EXEC_ESTOP_LATCHED) {
        char latched[64];
        hv_exec_node_list(sm->latched, latched, sizeof latched);
        printf("harvest-exec: latched e-stop on %s: not started, nothing enabled. Once its "
               "cause is dealt with, an operator clears it by restarting with "
               "--clear-estop NAME\n",
               latched);
    } else if (rc == HV_EXIT_EXEC_SAFE)
        printf("harvest-exec: the nodes hold the e-stop (%s, %s): a restart needs "
               "--clear-estop NAME\n",
               hv_exec_safe_reason_name(sm->safe_reason), hv_exec_node_name(sm->safe_node));
#ifdef HV_WITH_LCM
    if (o->online) {
        w->feed_stats = *hv_exec_feed_lcm_stats(&w->feed);
        snprintf(w->planner_note, sizeof w->planner_note, "%s", w->feed.planner(w->feed.ctx));
        if (halted && sm->stop_reason == HV_STOP_PLAN_TIMEOUT)
            printf("harvest-exec: no plan for %.0f s (online.wait_plan_timeout): %s\n",
                   (double)sm->prm.wait_plan_timeout_s, w->planner_note);
        if (w->feed_stats.refused)
            fprintf(stderr,
                    "harvest-exec: %u of the planner's %u messages refused, the last "
                    "for %s\n",
                    w->feed_stats.refused, w->feed_stats.messages, w->feed_stats.last_refusal);
        hv_exec_feed_lcm_close(&w->feed);
    }
#endif
    return rc;
}

/* Start-up up to the loop: GO_ON, or the exit code it ends with. */
static int start(const exec_args_t *o, setup_t *s, world_t *w)
{
    int rc = load_plan(o, s, w);
    if (rc == GO_ON)
        rc = open_journal(o, s, w);
    if (rc != GO_ON)
        return rc;
    exec_params(o, s);
    hv_status_t st = hv_exec_init(&w->sm, &w->plan, &s->prm, &w->prog);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s: parameters refused: %s\n", o->config,
                hv_exec_status_name(st));
        return HV_EXIT_USAGE;
    }
    return open_io(o, s, w);
}

int main(int argc, char **argv)
{
    exec_args_t o;
    if (exec_args_parse(argc, argv, &o) != 0)
        return HV_EXIT_USAGE;
    setup_t s;
    int rc = load_config(&o, &s);
    if (rc != GO_ON)
        return rc;
    world_t *w = calloc(1, sizeof *w);
    if (!w) {
        fprintf(stderr, "harvest-exec: out of memory\n");
        return HV_EXIT_FAILURE;
    }
    rc = start(&o, &s, w);
    if (rc != GO_ON) {
        close_world(w);
        return rc;
    }
    uint64_t t0 = 0, t_end = 0;
    hv_status_t st = run_loop(&o, &s, w, &t0, &t_end);
    double wall_s = (double)(t_end - t0) * 1e-9;
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    double cpu_s = (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 +
                   (double)ru.ru_stime.tv_sec + (double)ru.ru_stime.tv_usec * 1e-6;
    rc = report(&o, w, st, t_end);
    if (o.summary)
        write_summary(&o, w, wall_s, cpu_s, peak_rss_kb());
    close_world(w);
    return rc;
}
