#include "hv/exec_status.h"

const char *hv_exec_status_name(int status)
{
    switch (status) {
    case HV_ERR_EXEC_PLAN_SYNTAX: return "HV_ERR_EXEC_PLAN_SYNTAX";
    case HV_ERR_EXEC_PLAN_FIELD: return "HV_ERR_EXEC_PLAN_FIELD";
    case HV_ERR_EXEC_PLAN_RANGE: return "HV_ERR_EXEC_PLAN_RANGE";
    case HV_ERR_EXEC_PLAN_CAPACITY: return "HV_ERR_EXEC_PLAN_CAPACITY";
    case HV_ERR_EXEC_PLAN_ID: return "HV_ERR_EXEC_PLAN_ID";
    case HV_ERR_EXEC_PLAN_ORDER: return "HV_ERR_EXEC_PLAN_ORDER";
    case HV_ERR_EXEC_PLAN_CONFLICT: return "HV_ERR_EXEC_PLAN_CONFLICT";
    case HV_ERR_EXEC_JOURNAL_IO: return "HV_ERR_EXEC_JOURNAL_IO";
    case HV_ERR_EXEC_JOURNAL_FORMAT: return "HV_ERR_EXEC_JOURNAL_FORMAT";
    case HV_ERR_EXEC_JOURNAL_PLAN: return "HV_ERR_EXEC_JOURNAL_PLAN";
    case HV_ERR_EXEC_JOURNAL_UNKNOWN: return "HV_ERR_EXEC_JOURNAL_UNKNOWN";
    case HV_ERR_EXEC_JOURNAL_ID: return "HV_ERR_EXEC_JOURNAL_ID";
    case HV_ERR_EXEC_ACTIONS_FULL: return "HV_ERR_EXEC_ACTIONS_FULL";
    case HV_ERR_EXEC_EVENT: return "HV_ERR_EXEC_EVENT";
    case HV_ERR_EXEC_PARAMS: return "HV_ERR_EXEC_PARAMS";
    case HV_ERR_EXEC_TELEMETRY: return "HV_ERR_EXEC_TELEMETRY";
    case HV_ERR_EXEC_CAN_FRAME: return "HV_ERR_EXEC_CAN_FRAME";
    default: return hv_status_name(status);
    }
}
