#include "hv/exec_outcome.h"

#include <string.h>

static const char *const outcome_names[HV_OUT_COUNT] = {"picked", "failed", "skipped"};
static const char *const reason_names[HV_RSN_COUNT] = {
    "ok",      "resumed",    "ik_unreachable", "setpoint_rejected", "joint_fault", "ee_fault",
    "timeout", "cut_failed", "dropped"};
static const char *const stop_reason_names[HV_STOP_COUNT] = {"none", "operator", "plan_timeout"};

static int parse(const char *const *names, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

const char *hv_exec_outcome_name(int outcome)
{
    return outcome >= 0 && outcome < HV_OUT_COUNT ? outcome_names[outcome] : "unknown";
}

const char *hv_exec_reason_name(int reason)
{
    return reason >= 0 && reason < HV_RSN_COUNT ? reason_names[reason] : "unknown";
}

int hv_exec_outcome_parse(const char *name)
{
    return parse(outcome_names, HV_OUT_COUNT, name);
}

int hv_exec_reason_parse(const char *name)
{
    return parse(reason_names, HV_RSN_COUNT, name);
}

const char *hv_exec_stop_reason_name(int reason)
{
    return reason >= 0 && reason < HV_STOP_COUNT ? stop_reason_names[reason] : "unknown";
}

int hv_exec_stop_reason_parse(const char *name)
{
    return parse(stop_reason_names, HV_STOP_COUNT, name);
}
