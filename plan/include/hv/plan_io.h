/* Plan files (JSON, docs/PLAN_FORMAT.md): writer and strict reader (library hv_plan, the
 * contract between planner and executor; it knows no solver).
 *
 * The reader is jansson's strict JSON parser (RFC 8259: no comments, no trailing commas,
 * no duplicate keys) followed by a schema check: every field of the format must be
 * present with its type, unknown fields are rejected, so a plan is either read whole or
 * refused with a one-line message naming the file and the field.
 */
#ifndef HV_PLAN_IO_H
#define HV_PLAN_IO_H

#include <stddef.h>

#include "hv/plan.h"
#include "hv/plan_file_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Serialise to JSON text: *text is malloc'd (NUL-terminated), *len its length. */
hv_status_t hv_plan_to_json(const hv_plan_t *plan, char **text, size_t *len);

/* Serialise and write atomically (hv_file_write_atomic): never a half-written file. */
hv_status_t hv_plan_save(const char *path, const hv_plan_t *plan, char *err, size_t errlen);

/* Parse JSON text (len bytes) into *plan. `name` is used in messages (the file path).
 * HV_ERR_PLAN_JSON (syntax; message names line and column), HV_ERR_PLAN_FORMAT (message
 * names the field, e.g. "stops[2].left[0].cost_s: expected a number"), HV_ERR_PLAN_ID (a
 * fruit id outside the id set of hv/fruit_id.h, "stops[0].right[1].id: ...") or
 * HV_ERR_PLAN_ORDER (stops not by pass, then increasing y_m: "stops[3].y_m: ..."). On
 * error *plan is left empty (nothing allocated). */
hv_status_t hv_plan_parse(const char *text, size_t len, const char *name, hv_plan_t *plan,
                          char *err, size_t errlen);

/* Read and parse a plan file. */
hv_status_t hv_plan_load(const char *path, hv_plan_t *plan, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_IO_H */
