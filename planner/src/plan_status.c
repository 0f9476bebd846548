/* Names of the planner's status codes (plan_status.h) and the MILP's (milp_status.h). */
#include "hv/milp_status.h"
#include "hv/plan_status.h"

const char *hv_plan_status_name(int status)
{
    switch (status) {
    case HV_ERR_PLAN_MAP_EMPTY: return "HV_ERR_PLAN_MAP_EMPTY";
    case HV_ERR_PLAN_MAP_HEADER: return "HV_ERR_PLAN_MAP_HEADER";
    case HV_ERR_PLAN_MAP_SYNTAX: return "HV_ERR_PLAN_MAP_SYNTAX";
    case HV_ERR_PLAN_MAP_DUPLICATE: return "HV_ERR_PLAN_MAP_DUPLICATE";
    case HV_ERR_PLAN_MAP_SIDE: return "HV_ERR_PLAN_MAP_SIDE";
    case HV_ERR_PLAN_MAP_NAN: return "HV_ERR_PLAN_MAP_NAN";
    case HV_ERR_PLAN_MAP_RANGE: return "HV_ERR_PLAN_MAP_RANGE";
    case HV_ERR_PLAN_MAP_ID: return "HV_ERR_PLAN_MAP_ID";
    case HV_ERR_PLAN_UNASSIGNED: return "HV_ERR_PLAN_UNASSIGNED";
    case HV_ERR_PLAN_BAD_PAIR: return "HV_ERR_PLAN_BAD_PAIR";
    case HV_ERR_PLAN_NO_SOLUTION: return "HV_ERR_PLAN_NO_SOLUTION";
    case HV_ERR_PLAN_PARAMS: return "HV_ERR_PLAN_PARAMS";
    case HV_ERR_PLAN_CHECK_DUPLICATE: return "HV_ERR_PLAN_CHECK_DUPLICATE";
    case HV_ERR_PLAN_CHECK_MISSING: return "HV_ERR_PLAN_CHECK_MISSING";
    case HV_ERR_PLAN_CHECK_UNKNOWN: return "HV_ERR_PLAN_CHECK_UNKNOWN";
    case HV_ERR_PLAN_CHECK_PAIR: return "HV_ERR_PLAN_CHECK_PAIR";
    case HV_ERR_PLAN_CHECK_STOP: return "HV_ERR_PLAN_CHECK_STOP";
    case HV_ERR_PLAN_CHECK_COST: return "HV_ERR_PLAN_CHECK_COST";
    case HV_ERR_PLAN_CHECK_TOTAL: return "HV_ERR_PLAN_CHECK_TOTAL";
    case HV_ERR_PLAN_CHECK_REACHABLE: return "HV_ERR_PLAN_CHECK_REACHABLE";
    case HV_ERR_PLAN_CHECK_PARAMS: return "HV_ERR_PLAN_CHECK_PARAMS";
    case HV_ERR_PLAN_USAGE: return "HV_ERR_PLAN_USAGE";
    case HV_ERR_MILP_GLPK: return "HV_ERR_MILP_GLPK";
    case HV_ERR_MILP_EXPORT: return "HV_ERR_MILP_EXPORT";
    case HV_ERR_MILP_INCUMBENT: return "HV_ERR_MILP_INCUMBENT";
    case HV_ERR_MILP_DEADLINE: return "HV_ERR_MILP_DEADLINE";
    default: return hv_plan_file_status_name(status);
    }
}
