/* For the executor's fuzz targets: the plan of fuzz/data/plan.json (a make-test-plan row,
 * the plan the journal seeds were written for), loaded once (see fuzz_support.h), plans of
 * other shapes made of its picks, and the preparation of a plan with the configured arms and
 * timing. */
#ifndef HV_FUZZ_PLAN_H
#define HV_FUZZ_PLAN_H

#include "hv/exec_plan.h"
#include "hv/status.h"

/* The plan as read (prepared = 0) or prepared for a run (1); aborts when it cannot be. */
const hv_exec_plan_t *hv_fuzz_plan(int prepared);

/* hv_exec_plan_prepare() with config/harvest.cfg's arms, cut, release and vehicle. */
hv_status_t hv_fuzz_prepare(hv_exec_plan_t *plan);

/* The shapes of plan the step function is fuzzed on, all of fuzz/data/plan.json's fruit. */
typedef enum hv_fuzz_shape {
    HV_FUZZ_SHAPE_ROW = 0,  /* the plan as read: 3 stops, 2 picks per arm at each */
    HV_FUZZ_SHAPE_ONE_STOP, /* its first stop alone */
    HV_FUZZ_SHAPE_MANY,     /* one stop per pick, each followed by a stop without picks */
    HV_FUZZ_SHAPE_ONE_ARM   /* its stops with the left arm's picks only: the right arm idle */
} hv_fuzz_shape_t;

/* The prepared plan of that shape, built once; aborts when it cannot be. */
const hv_exec_plan_t *hv_fuzz_plan_shape(hv_fuzz_shape_t shape);

/* The empty plan on the course of fuzz/data/plan.json (online runs grow it). */
void hv_fuzz_plan_empty(hv_exec_plan_t *plan);

#endif /* HV_FUZZ_PLAN_H */
