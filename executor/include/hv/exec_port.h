/* The port: what a board gives the executor, as one small struct of function pointers (a
 * driver interface). The state machine (hv/exec_sm.h) stays pure; a loop around it (Linux:
 * hv/exec_loop.h, the firmware: firmware/fw_main.c) asks the port for the time and the
 * frames, sleeps in it (poll(), WFI), and carries out each step's actions through it
 * (hv_exec_port_carry_out). Two implementations:
 *   - Linux (exec_port_linux.c, hv_exec_port_linux): CLOCK_MONOTONIC, an hv_can_bus_t
 *     (SocketCAN or udp), the journal file (hv/exec_journal.h);
 *   - the firmware (firmware/fw_port.c): the SysTick, SLCAN on the UART, the journal as
 *     fixed-size binary records on the board's storage (firmware/fw_journal.h; in QEMU a
 *     host file through semihosting), replayed at boot like the Linux journal
 *     (hv/exec_progress.h).
 */
#ifndef HV_EXEC_PORT_H
#define HV_EXEC_PORT_H

#include <stdint.h>

#include "hv/can_bus.h"
#include "hv/exec_can.h"
#include "hv/exec_sm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every member but wait is required. None is called from an interrupt or another thread:
 * the loop is the port's only caller. */
typedef struct hv_exec_port {
    void *ctx; /* the implementation's state, passed to every call */
    /* monotonic time, ns; never goes back */
    uint64_t (*now_ns)(void *ctx);
    /* queue one frame for the bus, waiting for room a bounded while at most (Linux: 10 ms);
     * HV_OK or the transport's error (the frame is lost: the state machine resends what
     * must arrive) */
    hv_status_t (*can_send)(void *ctx, const hv_can_frame_t *f);
    /* the next received frame without waiting; HV_CAN_ERR_TIMEOUT when none waits */
    hv_status_t (*can_recv)(void *ctx, hv_can_frame_t *f);
    /* optional, NULL when the board cannot sleep (the loop then polls can_recv): block
     * until a frame may be waiting or now_ns() reaches until_ns (ns, now_ns's clock),
     * whichever is first; return at once when until_ns has passed. It may return early
     * (a signal, another wake-up source of the board, a frame can_recv then drops): the
     * caller reads the clock and can_recv after every return. HV_OK, or the platform's
     * error, on which the caller stops */
    hv_status_t (*wait)(void *ctx, uint64_t until_ns);
    /* store one journal record (an HV_ACT_JOURNAL action; t_s: the run's plan time)
     * durably before returning: the next action must not happen without it */
    hv_status_t (*journal_append)(void *ctx, const hv_exec_action_t *record, hv_exec_real_t t_s);
} hv_exec_port_t;

typedef struct hv_exec_port_stats {
    uint64_t frames_tx, send_failures, encode_errors, journal_records;
} hv_exec_port_stats_t;

/* Carry out a step's actions in order: frames encoded (hv_exec_can) and sent, journal
 * records appended; telemetry actions (fruit events, phases) are the caller's and skipped
 * here. Stops at a journal record that could not be stored and returns its status (the
 * caller then steps HV_EV_JOURNAL_FAILED); HV_OK otherwise. *done (may be NULL): the
 * actions carried out. */
hv_status_t hv_exec_port_carry_out(const hv_exec_port_t *port, hv_exec_can_tx_t *tx,
                                   const hv_exec_actions_t *out, hv_exec_real_t t_s,
                                   hv_exec_port_stats_t *st, unsigned *done);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_PORT_H */
