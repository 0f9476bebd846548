/* A step's actions through a port (see hv/exec_port.h). */
#include "hv/exec_port.h"

hv_status_t hv_exec_port_carry_out(const hv_exec_port_t *port, hv_exec_can_tx_t *tx,
                                   const hv_exec_actions_t *out, hv_exec_real_t t_s,
                                   hv_exec_port_stats_t *st, unsigned *done)
{
    unsigned i;
    hv_status_t rc = HV_OK;
    for (i = 0; i < out->n; i++) {
        const hv_exec_action_t *a = &out->a[i];
        if (a->kind == HV_ACT_JOURNAL) {
            rc = port->journal_append(port->ctx, a, t_s);
            if (rc != HV_OK)
                break;
            st->journal_records++;
            continue;
        }
        hv_can_frame_t f;
        int has = 0;
        if (hv_exec_can_encode(a, tx, &f, &has) != HV_OK) {
            st->encode_errors++;
            continue;
        }
        if (!has)
            continue; /* telemetry: the caller's */
        if (port->can_send(port->ctx, &f) == HV_OK)
            st->frames_tx++;
        else
            st->send_failures++;
    }
    if (done)
        *done = i;
    return rc;
}
