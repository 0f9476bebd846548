/* See fuzz_plan.h. */
#include "fuzz_plan.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

void hv_fuzz_plan_empty(hv_exec_plan_t *plan)
{
    const hv_exec_plan_t *src = hv_fuzz_plan(0);
    memset(plan, 0, sizeof *plan);
    plan->row_start_m = src->row_start_m;
    plan->row_length_m = src->row_length_m;
    plan->stop_margin_m = src->stop_margin_m;
    plan->planned_makespan_s = src->planned_makespan_s;
    plan->planned_pick_s = src->planned_pick_s;
}

/* Append to `plan` the picks src[first, first + n) as one stop (side from the picks) and,
 * when `gap`, a stop without picks 1 mm further; aborts when refused. */
static void append_stop(hv_exec_plan_t *plan, uint32_t index, hv_exec_real_t y_m,
                        const hv_exec_pick_t *src, unsigned n, int gap)
{
    unsigned n_left = 0;
    while (n_left < n && src[n_left].side == HV_SIDE_LEFT)
        n_left++;
    if (hv_exec_plan_append(plan, index, y_m, src, (uint16_t)n_left, (uint16_t)(n - n_left)) !=
            HV_OK ||
        (gap && hv_exec_plan_append(plan, index + 1, y_m + 0.001, NULL, 0, 0) != HV_OK)) {
        fprintf(stderr, "fuzz: plan shape: stop %u at %.4f m refused\n", (unsigned)index, y_m);
        abort();
    }
}

static void build_shape(hv_exec_plan_t *plan, hv_fuzz_shape_t shape)
{
    const hv_exec_plan_t *src = hv_fuzz_plan(0);
    hv_fuzz_plan_empty(plan);
    for (unsigned s = 0; s < src->n_stops; s++) {
        const hv_exec_stop_t *st = &src->stops[s];
        const hv_exec_pick_t *left = &src->picks[st->first[HV_SIDE_LEFT]];
        const hv_exec_pick_t *right = &src->picks[st->first[HV_SIDE_RIGHT]];
        uint32_t index = st->plan_index * 10u; /* room for the stops made in between */
        if (shape == HV_FUZZ_SHAPE_ONE_STOP && s > 0)
            break;
        if (shape == HV_FUZZ_SHAPE_ONE_ARM) {
            append_stop(plan, index, st->y_m, left, st->count[HV_SIDE_LEFT], 0);
        } else if (shape == HV_FUZZ_SHAPE_MANY) {
            /* 4 mm apart (1 mm to the empty one): each pick stays in its arm's reach */
            for (unsigned k = 0; k < st->count[HV_SIDE_LEFT]; k++, index += 2)
                append_stop(plan, index, st->y_m + 0.002 * (index % 10u), &left[k], 1, 1);
            for (unsigned k = 0; k < st->count[HV_SIDE_RIGHT]; k++, index += 2)
                append_stop(plan, index, st->y_m + 0.002 * (index % 10u), &right[k], 1, 1);
        } else {
            /* the stop's picks are contiguous, left ones first (hv_exec_plan_append) */
            append_stop(plan, index, st->y_m, left,
                        (unsigned)st->count[HV_SIDE_LEFT] + st->count[HV_SIDE_RIGHT], 0);
        }
    }
}

const hv_exec_plan_t *hv_fuzz_plan_shape(hv_fuzz_shape_t shape)
{
    static hv_exec_plan_t plan[4]; /* one per shape, built once (fuzz_support.h) */
    static int built[4];
    unsigned k = (unsigned)shape & 3u;
    if (k == HV_FUZZ_SHAPE_ROW)
        return hv_fuzz_plan(1);
    if (!built[k]) {
        build_shape(&plan[k], (hv_fuzz_shape_t)k);
        if (hv_fuzz_prepare(&plan[k]) != HV_OK)
            abort();
        built[k] = 1;
    }
    return &plan[k];
}
