#include "hv/exec_outcome.h"

#include <string.h>

static const char *const outcome_names[HV_OUT_COUNT] = {"picked", "failed", "skipped"};
static const char *const reason_names[HV_RSN_COUNT] = {
    "ok",      "resumed",    "ik_unreachable", "setpoint_rejected", "joint_fault", "ee_fault",
    "timeout", "cut_failed", "dropped"};

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
    for (int i = 0; i < HV_OUT_COUNT; i++)
        if (strcmp(name, outcome_names[i]) == 0)
            return i;
    return -1;
}

int hv_exec_reason_parse(const char *name)
{
    for (int i = 0; i < HV_RSN_COUNT; i++)
        if (strcmp(name, reason_names[i]) == 0)
            return i;
    return -1;
}
