/* Status codes of the planner (range -100..-149; the MILP uses -150..-199; the plan file
 * library's, -110 and -120..-129, are in plan/ plan_file_status.h, included here).
 *
 * Planner functions return these through hv_status_t (core/include/hv/status.h);
 * hv_plan_status_name() names them, the MILP's and the plan library's (and core codes).
 */
#ifndef HV_PLAN_STATUS_H
#define HV_PLAN_STATUS_H

#include "hv/plan_file_status.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Macros of type hv_status_t (not a second enum), so returning them from functions typed
 * hv_status_t needs no cast and -Wenum-conversion stays quiet. */
/* fruit map (CSV) */
#define HV_ERR_PLAN_MAP_EMPTY  ((hv_status_t)-100) /* no fruit line after the header */
#define HV_ERR_PLAN_MAP_HEADER ((hv_status_t)-101) /* first line is not `id,side,x,y,z,yaw` */
#define HV_ERR_PLAN_MAP_SYNTAX                                                                     \
    ((hv_status_t)-102) /* wrong field count, or a number does not parse */
#define HV_ERR_PLAN_MAP_DUPLICATE ((hv_status_t)-103) /* the same fruit id twice */
#define HV_ERR_PLAN_MAP_SIDE      ((hv_status_t)-104) /* side is not L or R */
#define HV_ERR_PLAN_MAP_NAN       ((hv_status_t)-105) /* NaN or infinite coordinate */
#define HV_ERR_PLAN_MAP_RANGE                                                                      \
    ((hv_status_t)-106) /* coordinate outside the side's table grid or the row */
#define HV_ERR_PLAN_MAP_ID ((hv_status_t)-107) /* id outside the id set (hv/fruit_id.h) */

/* instance and solutions */
#define HV_ERR_PLAN_UNASSIGNED                                                                     \
    ((hv_status_t)-111) /* a reachable fruit has no stop in an assignment */
#define HV_ERR_PLAN_BAD_PAIR                                                                       \
    ((hv_status_t)-112) /* an assignment uses a (fruit, stop) pair not reachable */
#define HV_ERR_PLAN_NO_SOLUTION ((hv_status_t)-113) /* the solver returned no assignment */
#define HV_ERR_PLAN_PARAMS      ((hv_status_t)-114) /* row / step / tau parameters invalid */

/* independent checker: the plan contradicts the inputs */
#define HV_ERR_PLAN_CHECK_DUPLICATE ((hv_status_t)-130) /* a fruit picked twice or listed twice */
#define HV_ERR_PLAN_CHECK_MISSING                                                                  \
    ((hv_status_t)-131) /* a map fruit neither picked nor unreachable */
#define HV_ERR_PLAN_CHECK_UNKNOWN                                                                  \
    ((hv_status_t)-132) /* a fruit not in the map, or with other pose/side */
#define HV_ERR_PLAN_CHECK_PAIR                                                                     \
    ((hv_status_t)-133) /* a fruit picked from a stop that cannot reach it */
#define HV_ERR_PLAN_CHECK_STOP                                                                     \
    ((hv_status_t)-134) /* stop off the grid, out of order, empty or unused */
#define HV_ERR_PLAN_CHECK_COST                                                                     \
    ((hv_status_t)-135) /* a pick cost or start time differs from the table */
#define HV_ERR_PLAN_CHECK_TOTAL ((hv_status_t)-136) /* per-stop or total times / counts differ */
#define HV_ERR_PLAN_CHECK_REACHABLE                                                                \
    ((hv_status_t)-137) /* a fruit listed unreachable that a stop reaches */
#define HV_ERR_PLAN_CHECK_PARAMS                                                                   \
    ((hv_status_t)-138) /* plan parameters differ from the configuration */

#define HV_ERR_PLAN_USAGE ((hv_status_t)-140) /* bad command line */

/* Name of a planner code ("HV_ERR_PLAN_MAP_SIDE"), or of a core code. Never NULL. */
const char *hv_plan_status_name(int status);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_STATUS_H */
