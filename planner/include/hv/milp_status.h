/* Status codes of the MILP solver (range -150..-199, see plan_status.h). */
#ifndef HV_MILP_STATUS_H
#define HV_MILP_STATUS_H

#include "hv/status.h"

/* Defined as hv_status_t values, like plan_status.h's, so they compare and return without
 * casts. */
#define HV_ERR_MILP_GLPK                                                                           \
    ((hv_status_t)-150) /* GLPK failed (LP relaxation or branch-and-bound error) */
#define HV_ERR_MILP_EXPORT ((hv_status_t)-151) /* the LP file could not be written */
#define HV_ERR_MILP_INCUMBENT                                                                      \
    ((hv_status_t)-152) /* the incumbent handed in is not a feasible assignment */
#define HV_ERR_MILP_DEADLINE                                                                       \
    ((hv_status_t)-153) /* a pricing call stopped at the solve's deadline
                                                     (internal: the solve then reports its time
                                                     limit reached) */

#endif /* HV_MILP_STATUS_H */
