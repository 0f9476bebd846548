/* Reading a plan file (docs/PLAN_FORMAT.md) into the executor's plan tables.
 *
 * The JSON goes through the strict plan reader of plan/ (library hv_plan, no GLPK), which
 * also checks fruit ids against the id set and stops for driving order; this maps it onto
 * the executor's fixed tables and checks what the executor needs beyond the format: its
 * capacity, one pick per fruit and side, stops on the plan's course, totals that agree
 * with the stops. Errors are one line naming the file and the field, e.g.
 * "plan.json: stops[2].left[0].cost_s: expected a number >= 0".
 */
#ifndef HV_EXEC_PLAN_JSON_H
#define HV_EXEC_PLAN_JSON_H

#include <stddef.h>

#include "hv/exec_plan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parse plan text (len bytes). `name` prefixes error messages (the file name).
 * Codes: HV_ERR_EXEC_PLAN_SYNTAX, _FIELD, _RANGE, _CAPACITY, _ID (a fruit id outside the
 * set of hv/fruit_id.h), _ORDER (stops not by pass, then increasing y_m), HV_ERR_NOMEM. */
hv_status_t hv_exec_plan_parse_json(const char *name, const char *text, size_t len,
                                    hv_exec_plan_t *plan, char *err, size_t errlen);

/* Read and parse a plan file; HV_ERR_IO when it cannot be read. */
hv_status_t hv_exec_plan_load_json(const char *path, hv_exec_plan_t *plan, char *err,
                                   size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_PLAN_JSON_H */
