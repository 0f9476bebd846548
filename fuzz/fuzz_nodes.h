/* For the executor's step-function fuzz targets: a run of the state machine on a fake
 * clock, the nodes' frames packed with the DBC's generated code, and the properties checked
 * after every step (hv_fuzz_step). The state machine's phase is the run's only state; every
 * input starts a fresh run (hv_fuzz_run_init). */
#ifndef HV_FUZZ_NODES_H
#define HV_FUZZ_NODES_H

#include <stddef.h>
#include <stdint.h>

#include "fuzz_support.h"
#include "hv/exec_sm.h"

typedef struct hv_fuzz_run {
    hv_exec_sm_t sm;
    uint64_t now; /* fake monotonic clock (ns) */
    uint8_t outcome_seen[HV_EXEC_MAX_PICKS];
    int latched_without_clear; /* a latch found at start-up, no operator clear */
    int commanded;             /* a command, setpoint, ee or move was sent in this run */
} hv_fuzz_run_t;

/* hv_exec_init on plan (prepared; it must outlive the run) with prog (NULL: fresh); picks
 * journalled done count as having their outcome. Aborts when init refuses. */
void hv_fuzz_run_init(hv_fuzz_run_t *R, const hv_exec_plan_t *plan, const hv_exec_params_t *prm,
                      const hv_exec_progress_t *prog);

/* One step with the properties: no crash or undefined behaviour; the step never overflows
 * its action list, and refuses an event out of its domain with HV_ERR_EXEC_EVENT, touching
 * nothing; every CAN action encodes; the phase is one of hv_exec_phase_t (WAIT_PLAN only
 * online) and SAFE, ROW_DONE and STOPPED are final; the current stop lies in the plan; in
 * SAFE only e-stops, heartbeats and telemetry leave the executor, and a start that finds a
 * latched e-stop without the operator's clear has commanded no node, nor does later; no
 * pick is journalled after its outcome, nor given a second outcome. */
void hv_fuzz_step(hv_fuzz_run_t *R, const hv_exec_event_t *ev);

/* A function called after every step of every run, with the step's event, status and
 * actions and the machine after it (the executor's replay traces the corpus with it,
 * tests/executor/exec_replay.c); NULL: none. */
typedef void (*hv_fuzz_step_hook_t)(void *ctx, const hv_exec_sm_t *sm, const hv_exec_event_t *ev,
                                    uint64_t now_ns, hv_status_t st, const hv_exec_actions_t *out);
void hv_fuzz_on_step(hv_fuzz_step_hook_t hook, void *ctx);

/* The nodes' operations of an input (fuzz_exec_step.c lists them): op & 7 with its argument
 * bytes from r. */
void hv_fuzz_node_op(hv_fuzz_run_t *R, int op, hv_fuzz_reader_t *r);

#endif /* HV_FUZZ_NODES_H */
