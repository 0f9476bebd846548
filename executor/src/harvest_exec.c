/* harvest-exec: run a plan on the CAN bus (DESIGN §7). See --help. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
#include "hv/version.h"

static const char k_prog[] = "harvest-exec";

/* The only mutable global: a signal handler can reach nothing else. */
static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    if (stop_requested < 2)
        stop_requested++; /* the first: a controlled stop; the second: e-stop */
}

static void usage(FILE *out)
{
    fprintf(
        out,
        "usage: harvest-exec --plan PLAN.json --config harvest.cfg --journal FILE [options]\n"
        "       harvest-exec --check-plan --plan PLAN.json --config harvest.cfg [tables]\n"
        "       harvest-exec --online --lcm-url URL --config harvest.cfg --journal FILE [options]\n"
        "\n"
        "Run a harvest plan on the CAN bus: wait for the vehicle drive and both arms, enable and\n"
        "home them, drive to each stop, run both arms' pick cycles, and stop safely (e-stop) on\n"
        "any fault. Every outcome is journalled before the next action; restarting with the same\n"
        "plan and journal resumes without picking a fruit twice.\n"
        "\n"
        "SIGTERM or SIGINT is a controlled stop: no new pick or drive starts, the picks under way\n"
        "finish, the vehicle arrives, every node is disabled (exit 6); a plain restart resumes.\n"
        "A second signal before that, a fault or a node's e-stop is a stop in the safe state: "
        "every\n"
        "node holds an e-stop. Only an operator releases it: a restart finds it latched and stays\n"
        "safe (exit 4) until it is given --clear-estop.\n"
        "\n"
        "input:\n"
        "  --plan FILE             plan file (docs/PLAN_FORMAT.md), required\n"
        "  --config FILE           harvest.cfg: arm, mount, vehicle speed/accel, required\n"
        "  --cost-table-left FILE  optional: refused unless built for the config's left arm\n"
        "  --cost-table-right FILE   (mount, joint limits, home pose, grid); same for the right.\n"
        "                          Picks come from the exact IK either way.\n"
        "  --check-plan            only load the plan and solve every pick's IK as a run would:\n"
        "                          print the picks the IK refuses and the expected makespan, open\n"
        "                          no bus and no journal; exit 0 when every pick is accepted\n"
        "  --online                instead of --plan: the plan grows while the row runs, from the\n"
        "                          online planner's committed stops (harvest-plan-online, LCM\n"
        "                          channel HARVEST_PLAN_COMMIT on --lcm-url); with no committed "
        "stop\n"
        "                          ahead the vehicle waits (or drives on to the commit line); the\n"
        "                          row ends once the planner's plan is final. Progress lines show\n"
        "                          stops done of those known, fruits picked, the robot time\n"
        "                          committed ahead and the waits. The committed stops go into the\n"
        "                          journal before any is acted on: a restart with the same "
        "journal\n"
        "                          rebuilds them and resumes; a planner's message that "
        "contradicts\n"
        "                          them is refused (HV_ERR_EXEC_PLAN_CONFLICT). The planner's\n"
        "                          status (HARVEST_PLANNER_STATUS) is said as it comes: its\n"
        "                          refusal and why, the detections it refused, the camera's\n"
        "                          replays; a wait names the reason no plan comes (also in\n"
        "                          telemetry, exec_state_t.planner, and the summary). With no\n"
        "                          stop for online.wait_plan_timeout of the config it makes a\n"
        "                          controlled stop (plan_timeout, exit 6) naming that reason\n"
        "bus:\n"
        "  --transport T           socketcan | udp (default udp)\n"
        "  --channel C             socketcan: interface (vcan0); udp: multicast group\n"
        "                          (default 239.74.163.2, python-can udp_multicast's)\n"
        "  --port N                udp port (default 43113)\n"
        "timing:\n"
        "  --time-scale K          expected node time scale; 0 = take the nodes' (default 0)\n"
        "  --margin M              timeout = planned * (1 + M) + slack (default 0.5)\n"
        "  --slack S               simulated s added to every timeout (default 1.0)\n"
        "  --max-retries N         further attempts of a fruit after a recoverable fault (2)\n"
        "  --startup-timeout S     wall s to see every node (default 10)\n"
        "  --heartbeat-timeout S   wall s without a node's heartbeat = lost (default 0.5, the "
        "DBC's)\n"
        "  --latency S             wall s added to every motion timeout for the bus (default 0.3)\n"
        "safety:\n"
        "  --clear-estop NAME      operator NAME has dealt with what caused the e-stop and clears "
        "it\n"
        "                          for this start-up: the nodes reporting a latched e-stop get\n"
        "                          CLEAR_ESTOP once the clear is in the journal (\"E NAME "
        "nodes=...\"),\n"
        "                          and nothing is enabled before every node's heartbeat and "
        "status,\n"
        "                          received after the clear, show no e-stop. NAME: 1-32 of\n"
        "                          A-Z a-z 0-9 . _ -. Without it a latched e-stop is never "
        "cleared.\n"
        "                          An e-stop during the run still ends it (exit 3)\n"
        "record and telemetry:\n"
        "  --journal FILE          harvest journal (created, or resumed), required\n"
        "  --lcm-url URL           publish LCM telemetry here (memq://, udpm://...?ttl=0);\n"
        "                          default: no telemetry\n"
        "  --summary FILE          write a JSON summary of the run here\n"
        "  --quiet                 no progress lines on stderr\n"
        "  -h, --help              this text\n"
        "  --version               the version and exit\n"
        "\n"
        "Expected makespan (compared with the executed one): per stop the slower arm's sum of\n"
        "pick cycles (2 x IK move time home->fruit + pick.cut_time + pick.release_time of the\n"
        "config) plus trapezoid vehicle moves\n"
        "between stops, from the course's start to its end (the row and the plan's stop margin\n"
        "beyond each end; the vehicle is expected at the course's start).\n"
        "\n" HV_EXIT_CODES_HELP ",\n"
        "3 stopped in the safe state, 4 not started: a latched e-stop, 5 --check-plan: a pick\n"
        "refused by the IK, 6 stopped on request)\n");
}

typedef struct opts {
    const char *plan, *config, *table[2], *transport, *channel, *journal, *lcm_url, *summary;
    const char *clear_by; /* --clear-estop, or NULL */
    int port, quiet, check_only, online;
    double time_scale, margin, slack_s, startup_s, hb_timeout_s, latency_s;
    long max_retries;
} opts_t;

static int parse_double(const char *name, const char *s, double min, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || *end || end == s || !isfinite(v) || v < min) {
        fprintf(stderr, "harvest-exec: --%s: expected a number >= %g, got '%s'\n", name, min, s);
        return -1;
    }
    *out = v;
    return 0;
}

static int parse_args(int argc, char **argv, opts_t *o)
{
    static const struct option lo[] = {{"plan", required_argument, 0, 'p'},
                                       {"config", required_argument, 0, 'c'},
                                       {"cost-table-left", required_argument, 0, 'L'},
                                       {"cost-table-right", required_argument, 0, 'R'},
                                       {"transport", required_argument, 0, 't'},
                                       {"channel", required_argument, 0, 'C'},
                                       {"port", required_argument, 0, 'P'},
                                       {"time-scale", required_argument, 0, 'k'},
                                       {"margin", required_argument, 0, 'm'},
                                       {"slack", required_argument, 0, 's'},
                                       {"max-retries", required_argument, 0, 'n'},
                                       {"startup-timeout", required_argument, 0, 'w'},
                                       {"heartbeat-timeout", required_argument, 0, 'H'},
                                       {"latency", required_argument, 0, 'a'},
                                       {"journal", required_argument, 0, 'j'},
                                       {"lcm-url", required_argument, 0, 'l'},
                                       {"summary", required_argument, 0, 'S'},
                                       {"quiet", no_argument, 0, 'q'},
                                       {"check-plan", no_argument, 0, 'K'},
                                       {"online", no_argument, 0, 'O'},
                                       {"clear-estop", required_argument, 0, 'E'},
                                       {"help", no_argument, 0, 'h'},
                                       {"version", no_argument, 0, 'V'},
                                       {0, 0, 0, 0}};
    memset(o, 0, sizeof *o);
    o->transport = "udp";
    o->port = HV_CAN_UDP_DEFAULT_PORT;
    o->margin = 0.5;
    o->slack_s = 1.0;
    o->startup_s = 10.0;
    o->hb_timeout_s = 0.5;
    o->latency_s = 0.3;
    o->max_retries = 2;
    int c;
    double v;
    opterr = 0; /* hv_cli_option_error's message instead of getopt's */
    while ((c = getopt_long(argc, argv, ":h", lo, NULL)) != -1) {
        switch (c) {
        case 'p': o->plan = optarg; break;
        case 'c': o->config = optarg; break;
        case 'L': o->table[0] = optarg; break;
        case 'R': o->table[1] = optarg; break;
        case 't': o->transport = optarg; break;
        case 'C': o->channel = optarg; break;
        case 'P':
            if (parse_double("port", optarg, 1, &v) || v > 65535 || v != floor(v))
                return -1;
            o->port = (int)v;
            break;
        case 'k':
            if (parse_double("time-scale", optarg, 0, &o->time_scale))
                return -1;
            break;
        case 'm':
            if (parse_double("margin", optarg, 0, &o->margin))
                return -1;
            break;
        case 's':
            if (parse_double("slack", optarg, 0, &o->slack_s))
                return -1;
            break;
        case 'w':
            if (parse_double("startup-timeout", optarg, 0.1, &o->startup_s))
                return -1;
            break;
        case 'H':
            if (parse_double("heartbeat-timeout", optarg, 0.05, &o->hb_timeout_s))
                return -1;
            break;
        case 'a':
            if (parse_double("latency", optarg, 0, &o->latency_s))
                return -1;
            break;
        case 'n':
            if (parse_double("max-retries", optarg, 0, &v) || v > 20 || v != floor(v))
                return -1;
            o->max_retries = (long)v;
            break;
        case 'j': o->journal = optarg; break;
        case 'l': o->lcm_url = optarg; break;
        case 'S': o->summary = optarg; break;
        case 'q': o->quiet = 1; break;
        case 'K': o->check_only = 1; break;
        case 'O': o->online = 1; break;
        case 'E':
            if (!hv_exec_journal_operator_ok(optarg)) {
                fprintf(stderr,
                        "harvest-exec: --clear-estop: expected the operator's name, 1-32 "
                        "of A-Z a-z 0-9 . _ -, got '%s'\n",
                        optarg);
                return -1;
            }
            o->clear_by = optarg;
            break;
        case 'h': usage(stdout); exit(0);
        case 'V': printf("harvest-exec %s\n", HV_VERSION); exit(0);
        default: hv_cli_option_error(k_prog, c, optopt, argv[optind - 1]); return -1;
        }
    }
    if (optind < argc) {
        hv_cli_usage_error(k_prog, argv[optind], "unexpected argument");
        return -1;
    }
    if (o->online && (o->plan || o->check_only || !o->lcm_url)) {
        hv_cli_usage_error(k_prog, "--online",
                           "takes no --plan nor --check-plan, and needs --lcm-url");
        return -1;
    }
    const char *missing = !o->plan && !o->online          ? "--plan"
                          : !o->config                    ? "--config"
                          : !o->journal && !o->check_only ? "--journal"
                                                          : NULL;
    if (missing) {
        hv_cli_usage_error(k_prog, missing, "required");
        return -1;
    }
    if (strcmp(o->transport, "udp") != 0 && strcmp(o->transport, "socketcan") != 0) {
        fprintf(stderr, "harvest-exec: --transport: expected socketcan or udp, got '%s'\n",
                o->transport);
        return -1;
    }
    if (!o->channel)
        o->channel = strcmp(o->transport, "udp") == 0 ? HV_CAN_UDP_DEFAULT_GROUP : "vcan0";
    return 0;
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

static void write_summary(const opts_t *o, const world_t *w, double wall_s, double cpu_s,
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

#include <sys/resource.h>
#include <time.h>

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

int main(int argc, char **argv)
{
    opts_t o;
    if (parse_args(argc, argv, &o) != 0)
        return HV_EXIT_USAGE;
    char err[512];
    hv_config_t cfg;
    if (hv_config_load(o.config, &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        return HV_EXIT_USAGE;
    }
    /* a table is checked, not used: the IK decides every pick (hv/pick.h) */
    hv_arm_t arms[2];
    for (int s = 0; s < 2; s++) {
        hv_config_arm(&cfg, (hv_side_t)s, &arms[s]);
        if (o.table[s] &&
            hv_costtab_check_for(o.table[s], &cfg, (hv_side_t)s, err, sizeof err) != HV_OK) {
            fprintf(stderr, "harvest-exec: %s\n", err);
            return HV_EXIT_USAGE;
        }
    }
    double margin_m = 0.0;
    if (hv_pick_stop_margin(&cfg, &margin_m) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s: an arm reaches none of its fruit area\n", o.config);
        return HV_EXIT_USAGE;
    }

    world_t *w = calloc(1, sizeof *w);
    if (!w) {
        fprintf(stderr, "harvest-exec: out of memory\n");
        return HV_EXIT_FAILURE;
    }
    /* online: the plan starts empty and grows from the planner's messages */
    hv_status_t st = o.online ? HV_OK : hv_exec_plan_load_json(o.plan, &w->plan, err, sizeof err);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        free(w);
        return HV_EXIT_USAGE;
    }
    if (w->plan.stop_margin_m > margin_m + 1e-9) {
        fprintf(stderr,
                "harvest-exec: %s: params.stop_margin_m: %g m beyond the row's ends, "
                "but from there no arm of %s reaches the row (at most %g m) (%s)\n",
                o.plan, w->plan.stop_margin_m, o.config, margin_m,
                hv_exec_status_name(HV_ERR_EXEC_PLAN_RANGE));
        free(w);
        return HV_EXIT_USAGE;
    }
    hv_exec_timing_t timing = {cfg.cut_s, cfg.release_s, cfg.vehicle_speed_mps,
                               cfg.vehicle_accel_mps2};
    if ((st = hv_exec_plan_prepare(&w->plan, arms, &timing)) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s: cannot prepare the plan: %s\n", o.plan,
                hv_exec_status_name(st));
        free(w);
        return HV_EXIT_USAGE;
    }
    for (uint16_t i = 0; i < w->plan.n_picks; i++)
        if (!w->plan.picks[i].reachable)
            fprintf(stderr,
                    "harvest-exec: %s: fruit %s (%c): the IK finds no pose within the "
                    "joint limits (%s): it will be skipped\n",
                    o.plan, w->plan.picks[i].id, w->plan.picks[i].side == HV_SIDE_LEFT ? 'L' : 'R',
                    hv_status_name(w->plan.picks[i].ik_status));
    if (o.check_only) {
        printf("harvest-exec: %s: %u stops, %u picks, %u refused by the IK; expected makespan "
               "%.3f s (plan's objective %.3f s)\n",
               o.plan, (unsigned)w->plan.n_stops, (unsigned)w->plan.n_picks, w->plan.n_unreachable,
               w->plan.expected_makespan_s, w->plan.planned_makespan_s);
        int rc = w->plan.n_unreachable ? HV_EXIT_EXEC_REFUSED : HV_EXIT_OK;
        free(w);
        return rc;
    }

    st = o.online
             ? hv_exec_journal_open_online(&w->journal, o.journal, &w->plan, &w->prog, err,
                                           sizeof err)
             : hv_exec_journal_open(&w->journal, o.journal, &w->plan, &w->prog, err, sizeof err);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s\n", err);
        free(w);
        /* a journal that cannot be opened or written is a failure; one that does not
         * belong to this plan, bad input */
        return st == HV_ERR_EXEC_JOURNAL_IO || st == HV_ERR_NOMEM ? HV_EXIT_FAILURE : HV_EXIT_USAGE;
    }
    /* online: the stops committed before a restart, rebuilt from the journal, are checked
     * and prepared as the planner's messages are */
    if (o.online && w->plan.n_stops &&
        (w->plan.stop_margin_m > margin_m + 1e-9 ||
         (st = hv_exec_plan_prepare(&w->plan, arms, &timing)) != HV_OK)) {
        fprintf(stderr,
                "harvest-exec: %s: the committed stops it holds cannot be run with %s "
                "(a stop margin beyond the arms' reach, or a stop off the course)\n",
                o.journal, o.config);
        hv_exec_journal_close(&w->journal);
        free(w);
        return HV_EXIT_USAGE;
    }
    unsigned done = 0;
    for (uint16_t i = 0; i < w->plan.n_picks; i++)
        done += w->prog.pick[i] == HV_PROG_DONE;
    if (w->prog.row_done) {
        printf("harvest-exec: %s: the journal says this row is done (%u/%u fruits have an "
               "outcome): nothing to do\n",
               o.journal, done, (unsigned)w->plan.n_picks);
        hv_exec_journal_close(&w->journal);
        free(w);
        return HV_EXIT_OK;
    }
    if (done || w->journal.records > 1)
        fprintf(stderr,
                "harvest-exec: resuming from %s: %u of %u fruits already have an "
                "outcome%s%s\n",
                o.journal, done, (unsigned)w->plan.n_picks,
                o.online ? "; the committed stops rebuilt from it" : "",
                w->journal.torn_bytes ? " (a torn last record was cut off)" : "");

    hv_exec_params_t prm;
    hv_exec_params_default(&prm);
    prm.time_scale = o.time_scale;
    prm.margin = o.margin;
    prm.slack_s = o.slack_s;
    prm.startup_timeout_s = o.startup_s;
    prm.heartbeat_timeout_s = o.hb_timeout_s;
    prm.latency_s = o.latency_s;
    prm.cut_s = cfg.cut_s;
    prm.release_s = cfg.release_s;
    prm.vehicle_speed_mps = cfg.vehicle_speed_mps;
    prm.vehicle_accel_mps2 = cfg.vehicle_accel_mps2;
    prm.max_retries = (unsigned)o.max_retries;
    prm.clear_estop = o.clear_by != NULL;
    prm.online = o.online;
    prm.wait_plan_timeout_s = cfg.online_wait_plan_timeout_s;
    double h0 = hv_exec_home_max_s(&arms[0]), h1 = hv_exec_home_max_s(&arms[1]);
    prm.home_max_s = h0 > h1 ? h0 : h1;
    if ((st = hv_exec_init(&w->sm, &w->plan, &prm, &w->prog)) != HV_OK) {
        fprintf(stderr, "harvest-exec: %s: parameters refused: %s\n", o.config,
                hv_exec_status_name(st));
        hv_exec_journal_close(&w->journal);
        free(w);
        return HV_EXIT_USAGE;
    }

    if (strcmp(o.transport, "udp") == 0)
        st = hv_can_udp_open(&w->bus, o.channel, (uint16_t)o.port, NULL, NULL, 0);
    else
        st = hv_can_socketcan_open(&w->bus, o.channel, NULL, 0);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-exec: %s bus '%s': cannot open: %s (%s)\n", o.transport, o.channel,
                hv_can_status_name(st), strerror(hv_can_last_errno(&w->bus)));
        hv_exec_journal_close(&w->journal);
        free(w);
        return HV_EXIT_FAILURE;
    }
    if (o.lcm_url) {
        if (hv_exec_telemetry_lcm_open(&w->tm, o.lcm_url, err, sizeof err) != HV_OK) {
            fprintf(stderr, "harvest-exec: %s\n", err);
            hv_can_close(&w->bus);
            hv_exec_journal_close(&w->journal);
            free(w);
            return HV_EXIT_FAILURE;
        }
    } else {
        hv_exec_telemetry_null(&w->tm);
    }
    if (o.online) {
#ifdef HV_WITH_LCM
        w->feed.log = o.quiet ? NULL : stderr;
        st = hv_exec_feed_lcm_open(&w->feed, o.lcm_url, &w->plan, arms, &timing, margin_m, err,
                                   sizeof err);
#else
        snprintf(err, sizeof err, "--online needs LCM: this build has none (HV_WITH_LCM=OFF)");
        st = HV_ERR_ARG;
#endif
        if (st != HV_OK) {
            fprintf(stderr, "harvest-exec: %s\n", err);
            hv_exec_telemetry_close(&w->tm);
            hv_can_close(&w->bus);
            hv_exec_journal_close(&w->journal);
            free(w);
            return HV_EXIT_FAILURE;
        }
        w->loop.feed = &w->feed;
    }

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    hv_exec_tm_plan(&w->tm, &w->plan, o.plan ? o.plan : "(online)", &prm, o.time_scale,
                    (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000);
    if (!o.quiet && o.online)
        fprintf(stderr,
                "harvest-exec: online on %s: the plan grows from the planner's "
                "committed stops (HARVEST_PLAN_COMMIT on %s); waiting for the nodes\n",
                hv_can_name(&w->bus), o.lcm_url);
    else if (!o.quiet)
        fprintf(stderr,
                "harvest-exec: %u stops, %u fruits on %s; expected makespan %.1f s "
                "(plan's objective %.1f s); waiting for the nodes\n",
                (unsigned)w->plan.n_stops, (unsigned)w->plan.n_picks, hv_can_name(&w->bus),
                w->plan.expected_makespan_s, w->plan.planned_makespan_s);

    w->linux_port.bus = &w->bus;
    w->linux_port.journal = &w->journal;
    w->linux_port.clear_by = o.clear_by;
    w->linux_port.send_timeout_ms = 10;
    w->linux_port.wake_fd = o.online ? w->feed.fd : -1;
    hv_exec_port_linux(&w->port, &w->linux_port);
    w->loop.sm = &w->sm;
    w->loop.port = &w->port;
    w->loop.bus = &w->bus;
    w->loop.journal = &w->journal;
    w->loop.tm = &w->tm;
    w->loop.stop = &stop_requested;
    w->loop.progress = o.quiet ? NULL : stderr;
    w->loop.clear_by = o.clear_by;
    w->loop.tick_s = 0.01;
    w->loop.linger_s = 0.5; /* e-stops repeat meanwhile when safe */
    uint64_t t0 = w->port.now_ns(w->port.ctx);
    st = hv_exec_loop_run(&w->loop);
    uint64_t t_end = w->port.now_ns(w->port.ctx);
    double wall_s = (double)(t_end - t0) * 1e-9;
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    double cpu_s = (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 +
                   (double)ru.ru_stime.tv_sec + (double)ru.ru_stime.tv_usec * 1e-6;

    int rc = st != HV_OK                                  ? HV_EXIT_FAILURE
             : w->sm.phase == HV_PH_ROW_DONE              ? HV_EXIT_OK
             : w->sm.phase == HV_PH_STOPPED               ? HV_EXIT_EXEC_STOPPED
             : w->sm.safe_reason == HV_SAFE_ESTOP_LATCHED ? HV_EXIT_EXEC_ESTOP_LATCHED
                                                          : HV_EXIT_EXEC_SAFE;
    /* an online plan has no objective of its own: the planner's horizons each had one */
    char objective[96];
    if (o.online)
        snprintf(objective, sizeof objective, "online, %u stops committed%s",
                 (unsigned)w->plan.n_stops, w->sm.plan_final ? ", final" : "");
    else
        snprintf(objective, sizeof objective, "plan's objective %.2f s",
                 w->plan.planned_makespan_s);
    int safe = w->sm.phase == HV_PH_SAFE, halted = w->sm.phase == HV_PH_STOPPED;
    printf("harvest-exec: %s%s%s: picked %u, failed %u, skipped %u this run (%u remaining), "
           "faults %u; executed %.2f s vs expected %.2f s (%s)\n",
           hv_exec_phase_name(w->sm.phase), safe || halted ? " " : "",
           safe     ? hv_exec_safe_reason_name(w->sm.safe_reason)
           : halted ? hv_exec_stop_reason_name(w->sm.stop_reason)
                    : "",
           w->sm.picked, w->sm.failed, w->sm.skipped, hv_exec_remaining(&w->sm), w->sm.faults,
           hv_exec_executed_s(&w->sm, t_end), w->plan.expected_makespan_s, objective);
    if (rc == HV_EXIT_EXEC_ESTOP_LATCHED) {
        char latched[64];
        hv_exec_node_list(w->sm.latched, latched, sizeof latched);
        printf("harvest-exec: latched e-stop on %s: not started, nothing enabled. Once its "
               "cause is dealt with, an operator clears it by restarting with "
               "--clear-estop NAME\n",
               latched);
    } else if (rc == HV_EXIT_EXEC_SAFE)
        printf("harvest-exec: the nodes hold the e-stop (%s, %s): a restart needs "
               "--clear-estop NAME\n",
               hv_exec_safe_reason_name(w->sm.safe_reason), hv_exec_node_name(w->sm.safe_node));
#ifdef HV_WITH_LCM
    if (o.online) {
        w->feed_stats = *hv_exec_feed_lcm_stats(&w->feed);
        snprintf(w->planner_note, sizeof w->planner_note, "%s", w->feed.planner(w->feed.ctx));
        if (halted && w->sm.stop_reason == HV_STOP_PLAN_TIMEOUT)
            printf("harvest-exec: no plan for %.0f s (online.wait_plan_timeout): %s\n",
                   (double)w->sm.prm.wait_plan_timeout_s, w->planner_note);
        if (w->feed_stats.refused)
            fprintf(stderr,
                    "harvest-exec: %u of the planner's %u messages refused, the last "
                    "for %s\n",
                    w->feed_stats.refused, w->feed_stats.messages, w->feed_stats.last_refusal);
        hv_exec_feed_lcm_close(&w->feed);
    }
#endif
    if (o.summary)
        write_summary(&o, w, wall_s, cpu_s, peak_rss_kb());
    hv_exec_telemetry_close(&w->tm);
    hv_can_close(&w->bus);
    hv_exec_journal_close(&w->journal);
    free(w);
    return rc;
}
