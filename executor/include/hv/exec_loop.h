/* The executor's event loop (DESIGN §7): CLOCK_MONOTONIC, a CAN bus, the journal and a
 * telemetry sink around the pure state machine. Frames and 10 ms timer ticks go in;
 * the actions come out in order: journal records are durable before the next action, CAN
 * frames are sent, telemetry is published. */
#ifndef HV_EXEC_LOOP_H
#define HV_EXEC_LOOP_H

#include <signal.h>
#include <stdint.h>
#include <stdio.h>

#include "hv/can_bus.h"
#include "hv/exec_can.h"
#include "hv/exec_feed.h"
#include "hv/exec_journal.h"
#include "hv/exec_sm.h"
#include "hv/exec_telemetry.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_exec_loop_stats {
    uint64_t steps;         /* calls of hv_exec_step */
    uint64_t step_ns_total; /* time spent in hv_exec_step */
    uint64_t step_ns_max;
    uint64_t frames_rx, frames_tx, frames_rx_malformed, send_failures;
    uint64_t journal_records;
    uint64_t encode_errors;
} hv_exec_loop_stats_t;

typedef struct hv_exec_loop {
    hv_exec_sm_t *sm;
    hv_can_bus_t *bus;
    hv_exec_journal_t *journal;  /* may be NULL (no journal: tests only) */
    hv_exec_telemetry_t *tm;     /* may be NULL */
    volatile sig_atomic_t *stop; /* set by a signal handler: stop safely */
    FILE *progress;              /* phase changes and outcomes, or NULL */
    const char *clear_by;        /* the operator who cleared the e-stop (E record), or
                                        NULL: an e-stop clear then fails like a journal write */
    double tick_s;               /* timer tick (s, real), default 0.01 */
    double linger_s;             /* keep running after the end (e-stop repeats), s */
    hv_exec_feed_t *feed;        /* online: the planner's stops, or NULL */
    /* private */
    hv_exec_can_tx_t tx;
    hv_exec_arm_sample_t samples[2];
    uint64_t next_arm_pub_ns[2], next_state_pub_ns, next_stats_pub_ns;
    hv_exec_loop_stats_t st;
} hv_exec_loop_t;

/* Monotonic time, ns. */
uint64_t hv_exec_now_ns(void);

/* Run until the state machine finished (ROW_DONE or SAFE) and linger_s passed. */
hv_status_t hv_exec_loop_run(hv_exec_loop_t *L);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_LOOP_H */
