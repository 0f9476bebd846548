/* The executor's event loop (DESIGN §7) around the pure state machine, on a port
 * (hv/exec_port.h): its clock, its frames, its wait between them, its journal. Frames and
 * 10 ms timer ticks go in; the actions come out in order through hv_exec_port_carry_out
 * (a journal record durable before the next action, CAN frames sent); telemetry and the
 * progress lines are the loop's own. harvest-exec runs it on hv_exec_port_linux. */
#ifndef HV_EXEC_LOOP_H
#define HV_EXEC_LOOP_H

#include <signal.h>
#include <stdint.h>
#include <stdio.h>

#include "hv/can_bus.h"
#include "hv/exec_can.h"
#include "hv/exec_feed.h"
#include "hv/exec_journal.h"
#include "hv/exec_port.h"
#include "hv/exec_sm.h"
#include "hv/exec_telemetry.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_exec_loop_stats {
    uint64_t steps;         /* calls of hv_exec_step */
    uint64_t step_ns_total; /* time spent in hv_exec_step (the port's clock) */
    uint64_t step_ns_max;
    uint64_t frames_rx, frames_rx_malformed;
    hv_exec_port_stats_t io; /* frames_tx, send_failures, encode_errors, journal_records */
} hv_exec_loop_stats_t;

typedef struct hv_exec_loop {
    hv_exec_sm_t *sm;
    const hv_exec_port_t *port;  /* time, frames, waiting, journal records: all I/O of a step */
    hv_can_bus_t *bus;           /* the port's bus, for its counters in telemetry only
                                    (can_stats_t), or NULL */
    hv_exec_journal_t *journal;  /* the port's journal file, or NULL: the committed stops
                                    online (hv_exec_journal_stops), its path in messages */
    hv_exec_telemetry_t *tm;     /* may be NULL */
    volatile sig_atomic_t *stop; /* counted up by a signal handler: each count is one stop
                                    request (HV_EV_STOP_REQUEST: controlled, then e-stop) */
    FILE *progress;              /* phase changes and outcomes, or NULL */
    const char *clear_by;        /* the operator named in the progress line of an e-stop
                                    clear (the port journals it), or NULL */
    double tick_s;               /* timer tick (s, real), default 0.01 */
    double linger_s;             /* keep running after the end (e-stop repeats), s */
    hv_exec_feed_t *feed;        /* online: the planner's stops, or NULL */
    /* private */
    hv_exec_can_tx_t tx;
    hv_exec_arm_sample_t samples[2];
    uint64_t next_arm_pub_ns[2], next_state_pub_ns, next_stats_pub_ns;
    hv_exec_loop_stats_t st;
} hv_exec_loop_t;

/* Run until the state machine finished (ROW_DONE or SAFE) and linger_s passed. Between
 * frames and ticks it sleeps in port->wait (polls when that is NULL). HV_ERR_ARG without
 * a state machine or a port's required member; the error of port->wait, which ends it. */
hv_status_t hv_exec_loop_run(hv_exec_loop_t *L);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_LOOP_H */
