/* Reading a plan file (docs/PLAN_FORMAT.md, version 1) into the executor's plan tables.
 *
 * Strict: the format and version must match; every field the executor uses must be there
 * with the right type and a sane value; a fruit may appear once per side; fruit ids are in
 * the id set and stops in driving order (both checked by the planner's reader). Errors are one
 * line naming the file and the field, e.g. "plan.json: stops[2].left[0].cost_s: expected
 * a number >= 0". The executor's own reader because the planner's lives with GLPK.
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
