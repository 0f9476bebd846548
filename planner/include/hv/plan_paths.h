/* The paths of a plan's inputs (its `inputs` object, docs/PLAN_FORMAT.md).
 *
 * In a plan file an input path is absolute or relative to the plan file's folder, never
 * to the current directory, so a plan is read the same from anywhere and a folder holding
 * a plan with its inputs can move as a whole.
 */
#ifndef HV_PLAN_PATHS_H
#define HV_PLAN_PATHS_H

#include <stddef.h>

#include "hv/plan_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The path to open for `input` as written in the plan file at `plan_path`: `input` itself
 * when absolute, else the plan's folder joined with it. Pure string work (nothing is
 * looked up). HV_ERR_NOMEM when it does not fit out[cap], HV_ERR_ARG for NULL or empty. */
hv_status_t hv_plan_input_resolve(const char *plan_path, const char *input, char *out, size_t cap);

/* What to write in the plan file at `plan_path` for an input the user named `input`
 * (absolute, or relative to the current directory): an absolute path as it is; a relative
 * one rewritten relative to the plan's folder, through the real paths of both folders
 * (symbolic links in them resolved, the file name kept). Both folders must exist.
 * HV_ERR_IO with `err` ("<path>: cannot resolve its folder: <reason>"), HV_ERR_NOMEM when
 * it does not fit out[cap]. */
hv_status_t hv_plan_input_relative(const char *plan_path, const char *input, char *out, size_t cap,
                                   char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* HV_PLAN_PATHS_H */
