/* Names of the plan library's status codes (plan_file_status.h). */
#include "hv/plan_file_status.h"

const char *hv_plan_file_status_name(int status)
{
    switch (status) {
    case HV_ERR_PLAN_NOMEM: return "HV_ERR_PLAN_NOMEM";
    case HV_ERR_PLAN_JSON: return "HV_ERR_PLAN_JSON";
    case HV_ERR_PLAN_FORMAT: return "HV_ERR_PLAN_FORMAT";
    case HV_ERR_PLAN_ID: return "HV_ERR_PLAN_ID";
    case HV_ERR_PLAN_ORDER: return "HV_ERR_PLAN_ORDER";
    default: return hv_status_name(status);
    }
}
