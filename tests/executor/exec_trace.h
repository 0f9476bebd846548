/* The executor's steps as text, for the recorded-run replay (exec_replay.c): what went in
 * (the event and the time), what came out (every action: frames, journal records,
 * telemetry) and the state the step left, one block per step that acted, failed or
 * changed that state; then a closing summary of the run (progress of every pick, counts,
 * times). Two builds of the state machine that write the same trace for the same inputs
 * behave the same. Reals are written with as many digits as their type round-trips. */
#ifndef HV_EXEC_TRACE_H
#define HV_EXEC_TRACE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hv/exec_sm.h"

typedef struct exec_trace {
    FILE *f;
    uint64_t steps;         /* steps seen, the quiet ones too (a block names its step number) */
    uint64_t t0_ns;         /* time of the first step: blocks give the time from it */
    char state[256];        /* the state line of the last block written */
    const hv_exec_sm_t *sm; /* the machine of the last step, for the summary */
    uint64_t now_ns;        /* and its time */
} exec_trace_t;

/* Start a trace into f with a comment line naming what runs. */
void exec_trace_begin(exec_trace_t *t, FILE *f, const char *title);

/* One step: the event, the status of hv_exec_step, the actions it appended (out) and the
 * machine after it. */
void exec_trace_step(exec_trace_t *t, const hv_exec_sm_t *sm, const hv_exec_event_t *ev,
                     uint64_t now_ns, hv_status_t st, const hv_exec_actions_t *out);

/* exec_trace_step with the trace (an exec_trace_t) as ctx: the step hook of exec_fixture.h
 * (on_step) and of the fuzz targets (hv_fuzz_on_step). */
void exec_trace_hook(void *ctx, const hv_exec_sm_t *sm, const hv_exec_event_t *ev, uint64_t now_ns,
                     hv_status_t st, const hv_exec_actions_t *out);

/* The closing summary, of the machine of the last step (nothing when there was none). */
void exec_trace_end(exec_trace_t *t);

/* The trace `text` (len bytes) against the file dir/name: 1 the same, 0 not (the first line
 * that differs is printed, and the trace written to ./name.actual for a diff), -1 when the
 * file cannot be read (printed). With `write`, the file is written instead (1, or -1). */
int exec_trace_golden(const char *dir, const char *name, const char *text, size_t len, int write);

#endif /* HV_EXEC_TRACE_H */
