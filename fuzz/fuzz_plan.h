/* For the executor's fuzz targets: the plan of fuzz/data/plan.json (a make-test-plan row,
 * the plan the journal seeds were written for), loaded once (see fuzz_support.h), and the
 * preparation of a plan with the configured arms and timing. */
#ifndef HV_FUZZ_PLAN_H
#define HV_FUZZ_PLAN_H

#include "hv/exec_plan.h"
#include "hv/status.h"

/* The plan as read (prepared = 0) or prepared for a run (1); aborts when it cannot be. */
const hv_exec_plan_t *hv_fuzz_plan(int prepared);

/* hv_exec_plan_prepare() with config/harvest.cfg's arms, cut, release and vehicle. */
hv_status_t hv_fuzz_prepare(hv_exec_plan_t *plan);

#endif /* HV_FUZZ_PLAN_H */
