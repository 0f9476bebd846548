/* The executor's port on Linux (see hv/exec_port.h): CLOCK_MONOTONIC, an hv_can_bus_t, the
 * journal file, and poll() on the bus (and one more descriptor) to wait. */
#ifndef HV_EXEC_PORT_LINUX_H
#define HV_EXEC_PORT_LINUX_H

#include "hv/can_bus.h"
#include "hv/exec_journal.h"
#include "hv/exec_port.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_exec_port_linux {
    hv_can_bus_t *bus;
    hv_exec_journal_t *journal; /* NULL: records are dropped (tests only) */
    const char *clear_by;       /* the operator named in an e-stop clear record, or NULL:
                                   such a record then fails like a write */
    int send_timeout_ms;        /* how long hv_can_send may wait for room (10) */
    int wake_fd;                /* input on it ends a wait too (harvest-exec --online: the
                                   planner feed's socket), or -1 */
} hv_exec_port_linux_t;

/* Fill `port` with the Linux functions on `ctx` (which must outlive it; every field set,
 * wake_fd to -1 when there is none). */
void hv_exec_port_linux(hv_exec_port_t *port, hv_exec_port_linux_t *ctx);

/* One journal record (an HV_ACT_JOURNAL action) into the journal file, synced:
 * hv/exec_journal.h's writers by kind. HV_ERR_ARG for an e-stop clear without clear_by. */
hv_status_t hv_exec_journal_action(hv_exec_journal_t *j, const hv_exec_action_t *a,
                                   const char *clear_by, double t_s);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_PORT_LINUX_H */
