/* Status codes of the MILP solver (range -150..-199, see plan_status.h). */
#ifndef HV_MILP_STATUS_H
#define HV_MILP_STATUS_H

#include "hv/plan_status.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    HV_ERR_MILP_GLPK = -150,      /* GLPK failed (LP relaxation or branch-and-bound error) */
    HV_ERR_MILP_EXPORT = -151,    /* the LP file could not be written */
    HV_ERR_MILP_INCUMBENT = -152  /* the incumbent handed in is not a feasible assignment */
};

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_STATUS_H */
