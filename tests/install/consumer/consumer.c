/* An out-of-tree program built against an installed harvest stack (tests/install): one
 * call into each installed layer (core, planner, executor, CAN; with CONSUMER_TELEMETRY
 * the LCM telemetry sink on memq://, linked with the consumer's own LCM), so a missing
 * library, header or link dependency fails the build or the run. With CONSUMER_CORE_ONLY
 * it uses the component core alone (hv_core_io, hv_core), which needs no jansson,
 * msgpack-c or GLPK. Usage: consumer CONFIG */
#include <stdio.h>

#include "hv/file_io.h"
#include "hv/pick.h"
#ifdef CONSUMER_CORE_ONLY
#include "hv/status.h"
#include "hv/version.h"
#else
#include "harvest_can.h"
#include "hv/exec_status.h"
#include "hv/exec_telemetry.h"
#include "hv/pick_model.h"
#endif

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: consumer CONFIG\n");
        return 2;
    }
    static hv_config_t cfg;
    char err[256];
    if (hv_config_load(argv[1], &cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "consumer: %s\n", err);
        return 1;
    }
    double margin_m = 0.0;
    if (hv_pick_stop_margin(&cfg, &margin_m) != HV_OK)
        return 1;
#ifdef CONSUMER_CORE_ONLY
    printf("stop_margin_m %.3f status %s version %s\n", margin_m, hv_status_name(HV_OK),
           HV_VERSION);
    return 0;
#else
    struct harvest_can_estop_t estop = {.estop_active = 1};
    uint8_t frame[8];
    int len = harvest_can_estop_pack(frame, &estop, sizeof frame);
    unsigned published = 0;
#ifdef CONSUMER_TELEMETRY
    hv_exec_telemetry_t tm;
    if (hv_exec_telemetry_lcm_open(&tm, "memq://", err, sizeof err) != HV_OK) {
        fprintf(stderr, "consumer: %s\n", err);
        return 1;
    }
    hv_exec_bus_stats_t stats = {.bus = "consumer"};
    hv_exec_tm_can_stats(&tm, &stats, 0);
    published = tm.failed ? 0u : tm.published;
    hv_exec_telemetry_close(&tm);
#endif
    printf("stop_margin_m %.3f pick_model %s estop_frame_bytes %d status %s telemetry %u\n",
           margin_m, hv_pick_model_name(&cfg), len, hv_exec_status_name(HV_OK), published);
    return len > 0 ? 0 : 1;
#endif
}
