/* harvest-fw-plan: the plan image the firmware receives over the bus (firmware/
 * plan_image.h), from a plan file and the config, prepared exactly as harvest-exec
 * prepares it (IK of every pick, expected times). See --help. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fw_status.h"
#include "hv/cli.h"
#include "hv/cost_table.h"
#include "hv/exec_plan_json.h"
#include "hv/exec_status.h"
#include "hv/file_io.h"
#include "hv/pick.h"
#include "hv/version.h"
#include "plan_image.h"

static const char k_prog[] = "harvest-fw-plan";

static void usage(FILE *out)
{
    fprintf(
        out,
        "usage: harvest-fw-plan --plan PLAN.json --config harvest.cfg --out IMAGE [options]\n"
        "\n"
        "Write the plan image harvest-fw.elf takes over the bus (ExecutorPlanBegin/Data): the "
        "plan\n"
        "prepared as harvest-exec prepares it (IK of every pick with the config's arms, expected\n"
        "times) and the executor's parameters. Prints the image's size, CRC-32 and the expected\n"
        "makespan. Refuses a plan larger than the firmware's tables (%u stops, %u picks).\n"
        "\n"
        "  --plan FILE             plan file (docs/PLAN_FORMAT.md), required\n"
        "  --config FILE           harvest.cfg, required\n"
        "  --out FILE              the image, required\n"
        "  --time-scale K          expected node time scale; 0 = take the nodes' (default 0)\n"
        "  --heartbeat-timeout S   wall s without a node's heartbeat = lost (default 0.5)\n"
        "  --startup-timeout S     wall s to see every node (default 10)\n"
        "  -h, --help              this text\n"
        "  --version               the version and exit\n"
        "\n" HV_EXIT_CODES_HELP ")\n",
        (unsigned)HV_FW_MAX_STOPS, (unsigned)HV_FW_MAX_PICKS);
}

static int number(const char *name, const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || *end || end == s || !isfinite(v) || v < 0.0) {
        fprintf(stderr, "harvest-fw-plan: --%s: expected a number >= 0, got '%s'\n", name, s);
        return -1;
    }
    *out = v;
    return 0;
}

int main(int argc, char **argv)
{
    const char *plan_path = NULL, *config = NULL, *out = NULL;
    hv_exec_params_t prm;
    hv_exec_params_default(&prm);
    static const struct option opts[] = {{"plan", required_argument, 0, 'p'},
                                         {"config", required_argument, 0, 'c'},
                                         {"out", required_argument, 0, 'o'},
                                         {"time-scale", required_argument, 0, 't'},
                                         {"heartbeat-timeout", required_argument, 0, 'b'},
                                         {"startup-timeout", required_argument, 0, 's'},
                                         {"help", no_argument, 0, 'h'},
                                         {"version", no_argument, 0, 'V'},
                                         {0, 0, 0, 0}};
    int c;
    opterr = 0; /* hv_cli_option_error's message instead of getopt's */
    while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
        int bad = 0;
        switch (c) {
        case 'p': plan_path = optarg; break;
        case 'c': config = optarg; break;
        case 'o': out = optarg; break;
        case 't': bad = number("time-scale", optarg, &prm.time_scale); break;
        case 'b': bad = number("heartbeat-timeout", optarg, &prm.heartbeat_timeout_s); break;
        case 's': bad = number("startup-timeout", optarg, &prm.startup_timeout_s); break;
        case 'h': usage(stdout); return 0;
        case 'V': printf("harvest-fw-plan %s\n", HV_VERSION); return 0;
        default: hv_cli_option_error(k_prog, c, optopt, argv[optind - 1]); return HV_EXIT_USAGE;
        }
        if (bad)
            return HV_EXIT_USAGE;
    }
    if (optind != argc) {
        hv_cli_usage_error(k_prog, argv[optind], "unexpected argument");
        return HV_EXIT_USAGE;
    }
    const char *missing = !plan_path ? "--plan" : !config ? "--config" : !out ? "--out" : NULL;
    if (missing) {
        hv_cli_usage_error(k_prog, missing, "required");
        return HV_EXIT_USAGE;
    }
    char err[512];
    hv_config_t cfg;
    if (hv_config_load(config, &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-fw-plan: %s\n", err);
        return HV_EXIT_USAGE;
    }
    hv_arm_t arms[2];
    for (int s = 0; s < 2; s++)
        hv_config_arm(&cfg, (hv_side_t)s, &arms[s]);
    hv_exec_plan_t *plan = calloc(1, sizeof *plan);
    if (!plan) {
        fprintf(stderr, "harvest-fw-plan: out of memory\n");
        return HV_EXIT_FAILURE;
    }
    if (hv_exec_plan_load_json(plan_path, plan, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-fw-plan: %s\n", err);
        free(plan);
        return HV_EXIT_USAGE;
    }
    double margin_m = 0.0;
    if (hv_pick_stop_margin(&cfg, &margin_m) != HV_OK || plan->stop_margin_m > margin_m + 1e-9) {
        fprintf(stderr,
                "harvest-fw-plan: %s: params.stop_margin_m: %g m, the arms of %s reach "
                "the row from at most %g m beyond its ends (%s)\n",
                plan_path, plan->stop_margin_m, config, margin_m,
                hv_exec_status_name(HV_ERR_EXEC_PLAN_RANGE));
        free(plan);
        return HV_EXIT_USAGE;
    }
    if (plan->n_stops > HV_FW_MAX_STOPS || plan->n_picks > HV_FW_MAX_PICKS) {
        fprintf(stderr,
                "harvest-fw-plan: %s: %u stops and %u picks, the firmware holds %u and "
                "%u (%s)\n",
                plan_path, (unsigned)plan->n_stops, (unsigned)plan->n_picks,
                (unsigned)HV_FW_MAX_STOPS, (unsigned)HV_FW_MAX_PICKS,
                hv_exec_status_name(HV_ERR_EXEC_PLAN_CAPACITY));
        free(plan);
        return HV_EXIT_USAGE;
    }
    hv_exec_timing_t timing = {cfg.cut_s, cfg.release_s, cfg.vehicle_speed_mps,
                               cfg.vehicle_accel_mps2};
    hv_status_t st = hv_exec_plan_prepare(plan, arms, &timing);
    if (st != HV_OK) {
        fprintf(stderr, "harvest-fw-plan: %s: cannot prepare the plan: %s\n", plan_path,
                hv_exec_status_name(st));
        free(plan);
        return HV_EXIT_USAGE;
    }
    prm.cut_s = cfg.cut_s;
    prm.release_s = cfg.release_s;
    prm.vehicle_speed_mps = cfg.vehicle_speed_mps;
    prm.vehicle_accel_mps2 = cfg.vehicle_accel_mps2;
    double h0 = hv_exec_home_max_s(&arms[0]), h1 = hv_exec_home_max_s(&arms[1]);
    prm.home_max_s = h0 > h1 ? h0 : h1;
    size_t size = hv_fw_image_size(plan->n_stops, plan->n_picks);
    uint8_t *buf = malloc(size);
    snprintf(err, sizeof err, "%s: out of memory", out);
    if (!buf || hv_fw_image_write(plan, &prm, buf, size) != size ||
        hv_file_write_atomic(out, buf, size, err, sizeof err) != HV_OK) {
        fprintf(stderr, "harvest-fw-plan: %s\n", err);
        free(buf);
        free(plan);
        return HV_EXIT_FAILURE;
    }
    printf("harvest-fw-plan: %s: %zu bytes, crc32 %08lx, %u stops, %u picks (%u refused by the "
           "IK), expected makespan %.3f s\n",
           out, size, (unsigned long)hv_crc32(0, buf, size), (unsigned)plan->n_stops,
           (unsigned)plan->n_picks, plan->n_unreachable, plan->expected_makespan_s);
    free(buf);
    free(plan);
    return HV_EXIT_OK;
}
