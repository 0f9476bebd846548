#include "hv/status.h"

const char *hv_status_name(int status)
{
    switch (status) {
    case HV_OK: return "HV_OK";
    case HV_ERR_ARG: return "HV_ERR_ARG";
    case HV_ERR_NAN: return "HV_ERR_NAN";
    case HV_ERR_NOMEM: return "HV_ERR_NOMEM";
    case HV_ERR_IO: return "HV_ERR_IO";
    case HV_ERR_FRUIT_ID: return "HV_ERR_FRUIT_ID";
    case HV_ERR_UNREACHABLE: return "HV_ERR_UNREACHABLE";
    case HV_ERR_JOINT_LIMIT: return "HV_ERR_JOINT_LIMIT";
    case HV_ERR_TAB_TRUNCATED: return "HV_ERR_TAB_TRUNCATED";
    case HV_ERR_TAB_MAGIC: return "HV_ERR_TAB_MAGIC";
    case HV_ERR_TAB_VERSION: return "HV_ERR_TAB_VERSION";
    case HV_ERR_TAB_HEADER: return "HV_ERR_TAB_HEADER";
    case HV_ERR_TAB_GRID: return "HV_ERR_TAB_GRID";
    case HV_ERR_TAB_CRC: return "HV_ERR_TAB_CRC";
    case HV_ERR_TAB_MISMATCH: return "HV_ERR_TAB_MISMATCH";
    case HV_ERR_OUT_OF_GRID: return "HV_ERR_OUT_OF_GRID";
    case HV_ERR_CFG_SYNTAX: return "HV_ERR_CFG_SYNTAX";
    case HV_ERR_CFG_UNKNOWN: return "HV_ERR_CFG_UNKNOWN";
    case HV_ERR_CFG_MISSING: return "HV_ERR_CFG_MISSING";
    case HV_ERR_CFG_RANGE: return "HV_ERR_CFG_RANGE";
    case HV_ERR_CFG_DUPLICATE: return "HV_ERR_CFG_DUPLICATE";
    default: return "HV_ERR_UNKNOWN_CODE";
    }
}
