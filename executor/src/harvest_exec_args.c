/* harvest-exec's command line (harvest_exec_args.h). */
#define _POSIX_C_SOURCE 200809L
#include "harvest_exec_args.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/cli.h"
#include "hv/can_bus.h"
#include "hv/exec_journal.h"
#include "hv/version.h"

static const char k_prog[] = "harvest-exec";

static const char k_usage[] =
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
    "refused by the IK, 6 stopped on request)\n";

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

static const struct option k_longopts[] = {{"plan", required_argument, 0, 'p'},
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

/* An option that sets a member of exec_args_t (getopt's value, offsetof the member). */
typedef struct opt_member {
    int c;
    size_t at;
} opt_member_t;

/* The options whose text is kept as given (const char *), and the flags (int, set to 1). */
static const opt_member_t k_text_opts[] = {
    {'p', offsetof(exec_args_t, plan)},      {'c', offsetof(exec_args_t, config)},
    {'L', offsetof(exec_args_t, table[0])},  {'R', offsetof(exec_args_t, table[1])},
    {'t', offsetof(exec_args_t, transport)}, {'C', offsetof(exec_args_t, channel)},
    {'j', offsetof(exec_args_t, journal)},   {'l', offsetof(exec_args_t, lcm_url)},
    {'S', offsetof(exec_args_t, summary)},
};
static const opt_member_t k_flag_opts[] = {
    {'q', offsetof(exec_args_t, quiet)},
    {'K', offsetof(exec_args_t, check_only)},
    {'O', offsetof(exec_args_t, online)},
};

/* The options that take a number >= min: a double, or a whole number up to max in an int
 * ('i') or a long ('l'). */
typedef struct num_opt {
    int c;
    const char *name;
    double min, max;
    char type; /* 'd', 'i', 'l' */
    size_t at;
} num_opt_t;

static const num_opt_t k_num_opts[] = {
    {'P', "port", 1, 65535, 'i', offsetof(exec_args_t, port)},
    {'k', "time-scale", 0, 0, 'd', offsetof(exec_args_t, time_scale)},
    {'m', "margin", 0, 0, 'd', offsetof(exec_args_t, margin)},
    {'s', "slack", 0, 0, 'd', offsetof(exec_args_t, slack_s)},
    {'w', "startup-timeout", 0.1, 0, 'd', offsetof(exec_args_t, startup_s)},
    {'H', "heartbeat-timeout", 0.05, 0, 'd', offsetof(exec_args_t, hb_timeout_s)},
    {'a', "latency", 0, 0, 'd', offsetof(exec_args_t, latency_s)},
    {'n', "max-retries", 0, 20, 'l', offsetof(exec_args_t, max_retries)},
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static const opt_member_t *find_member(const opt_member_t *t, size_t n, int c)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].c == c)
            return &t[i];
    return NULL;
}

/* A number option's argument into its member: 0, or -1 when refused. */
static int parse_num(const num_opt_t *n, const char *s, exec_args_t *o)
{
    char *m = (char *)o + n->at;
    double v;
    if (parse_double(n->name, s, n->min, &v))
        return -1;
    if (n->type == 'd') {
        *(double *)m = v;
        return 0;
    }
    if (v > n->max || v != floor(v))
        return -1;
    if (n->type == 'i')
        *(int *)m = (int)v;
    else
        *(long *)m = (long)v;
    return 0;
}

/* One option `c` (its argument in optarg): 0, or -1 when refused; --help and --version
 * print and exit. */
static int parse_option(int c, char **argv, exec_args_t *o)
{
    const opt_member_t *text = find_member(k_text_opts, COUNT(k_text_opts), c);
    const opt_member_t *flag = find_member(k_flag_opts, COUNT(k_flag_opts), c);
    if (text) {
        *(const char **)((char *)o + text->at) = optarg;
        return 0;
    }
    if (flag) {
        *(int *)((char *)o + flag->at) = 1;
        return 0;
    }
    for (size_t i = 0; i < COUNT(k_num_opts); i++)
        if (k_num_opts[i].c == c)
            return parse_num(&k_num_opts[i], optarg, o);
    switch (c) {
    case 'E':
        if (!hv_exec_journal_operator_ok(optarg)) {
            fprintf(stderr,
                    "harvest-exec: --clear-estop: expected the operator's name, 1-32 "
                    "of A-Z a-z 0-9 . _ -, got '%s'\n",
                    optarg);
            return -1;
        }
        o->clear_by = optarg;
        return 0;
    case 'h': fputs(k_usage, stdout); exit(0);
    case 'V': printf("harvest-exec %s\n", HV_VERSION); exit(0);
    default: hv_cli_option_error(k_prog, c, optopt, argv[optind - 1]); return -1;
    }
}

/* The options together: what is required, and the transport; the channel's default. */
static int check_opts(exec_args_t *o)
{
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

int exec_args_parse(int argc, char **argv, exec_args_t *o)
{
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
    opterr = 0; /* hv_cli_option_error's message instead of getopt's */
    while ((c = getopt_long(argc, argv, ":h", k_longopts, NULL)) != -1)
        if (parse_option(c, argv, o) != 0)
            return -1;
    if (optind < argc) {
        hv_cli_usage_error(k_prog, argv[optind], "unexpected argument");
        return -1;
    }
    return check_opts(o);
}
