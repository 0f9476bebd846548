/* The telemetry interface's wrappers and the null sink. */
#include "hv/exec_telemetry.h"

#include <stdio.h>

#include "hv/exec_status.h"

static const hv_exec_telemetry_ops_t null_ops = {NULL, NULL, NULL, NULL, NULL, NULL};

void hv_exec_telemetry_null(hv_exec_telemetry_t *t)
{
    t->ops = &null_ops;
    t->impl = NULL;
    t->published = t->failed = 0;
}

#ifndef HV_WITH_LCM
hv_status_t hv_exec_telemetry_lcm_open(hv_exec_telemetry_t *t, const char *url, char *err,
                                       size_t errlen)
{
    (void)url;
    hv_exec_telemetry_null(t);
    snprintf(err, errlen, "LCM telemetry was not built in (HV_WITH_LCM=OFF)");
    return HV_ERR_EXEC_TELEMETRY;
}
#endif

static void count(hv_exec_telemetry_t *t, int rc)
{
    if (rc == 0)
        t->published++;
    else
        t->failed++;
}

void hv_exec_tm_plan(hv_exec_telemetry_t *t, const hv_exec_plan_t *plan, const char *path,
                     const hv_exec_params_t *prm, double time_scale, int64_t utime)
{
    if (t && t->ops && t->ops->plan)
        count(t, t->ops->plan(t, plan, path, prm, time_scale, utime));
}

void hv_exec_tm_state(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const char *planner,
                      uint64_t now_ns, int64_t utime)
{
    if (t && t->ops && t->ops->state)
        count(t, t->ops->state(t, sm, planner, now_ns, utime));
}

void hv_exec_tm_fruit(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_action_t *fe,
                      uint64_t now_ns, int64_t utime)
{
    if (t && t->ops && t->ops->fruit)
        count(t, t->ops->fruit(t, sm, fe, now_ns, utime));
}

void hv_exec_tm_arm(hv_exec_telemetry_t *t, const hv_exec_sm_t *sm, const hv_exec_arm_sample_t *s,
                    int64_t utime)
{
    if (t && t->ops && t->ops->arm)
        count(t, t->ops->arm(t, sm, s, utime));
}

void hv_exec_tm_can_stats(hv_exec_telemetry_t *t, const hv_exec_bus_stats_t *s, int64_t utime)
{
    if (t && t->ops && t->ops->can_stats)
        count(t, t->ops->can_stats(t, s, utime));
}

void hv_exec_telemetry_close(hv_exec_telemetry_t *t)
{
    if (t && t->ops && t->ops->close)
        t->ops->close(t);
    if (t)
        t->ops = &null_ops;
}

unsigned hv_exec_remaining(const hv_exec_sm_t *sm)
{
    unsigned n = 0;
    for (uint16_t i = 0; i < sm->plan->n_picks; i++)
        n += sm->prog.pick[i] != HV_PROG_DONE;
    return n;
}
