/* See fuzz_plan.h. */
#include "fuzz_plan.h"

#include <stdio.h>
#include <stdlib.h>

#include "fuzz_support.h"
#include "hv/exec_plan_json.h"

hv_status_t hv_fuzz_prepare(hv_exec_plan_t *plan)
{
    const hv_config_t *cfg = hv_fuzz_config();
    hv_arm_t arm[2];
    hv_config_arm(cfg, HV_SIDE_LEFT, &arm[0]);
    hv_config_arm(cfg, HV_SIDE_RIGHT, &arm[1]);
    hv_exec_timing_t tm = {cfg->cut_s, cfg->release_s, cfg->vehicle_speed_mps,
                           cfg->vehicle_accel_mps2};
    return hv_exec_plan_prepare(plan, arm, &tm);
}

const hv_exec_plan_t *hv_fuzz_plan(int prepared)
{
    static hv_exec_plan_t plan[2]; /* as read, prepared: built once (fuzz_support.h) */
    static int loaded[2];
    int k = prepared ? 1 : 0;
    if (!loaded[k]) {
        char path[1024], err[512];
        hv_fuzz_source_path("fuzz/data/plan.json", path, sizeof path);
        if (hv_exec_plan_load_json(path, &plan[k], err, sizeof err) != HV_OK) {
            fprintf(stderr, "fuzz: %s\n", err);
            abort();
        }
        if (prepared && hv_fuzz_prepare(&plan[k]) != HV_OK)
            abort();
        loaded[k] = 1;
    }
    return &plan[k];
}
