/* The firmware's port (see fw_port.h). can_recv reads what the UART holds, answers SLCAN
 * commands as a Lawicel adapter does, and returns the next frame the host transmits. */
#include "fw_port.h"

#include <string.h>

#include "fw_status.h"

void hv_fw_port_report_error(int status)
{
    hv_fw_uart_puts("\aharvest-fw: error ");
    hv_fw_uart_puts(hv_fw_status_name(status));
    hv_fw_uart_puts("\r");
}

static uint64_t fw_now_ns(void *ctx)
{
    hv_fw_port_t *P = ctx;
    return hv_fw_clock_ns(&P->clock);
}

static hv_status_t fw_send(void *ctx, const hv_can_frame_t *f)
{
    hv_fw_port_t *P = ctx;
    char line[HV_SLCAN_LINE_MAX + 1];
    size_t n = hv_slcan_format(f, line, sizeof line);
    if (!P->open)
        return HV_ERR_SLCAN_CLOSED; /* a closed channel carries no frames (Lawicel) */
    if (n == 0)
        return HV_ERR_ARG;
    hv_fw_uart_write(line, n);
    P->frames_tx++;
    return HV_OK;
}

/* A complete line: a command answered here, or a frame for the caller (returns 1). */
static int on_line(hv_fw_port_t *P, hv_can_frame_t *f)
{
    hv_slcan_cmd_t cmd;
    hv_status_t st = hv_slcan_parse(P->rx.line, P->rx.done, &cmd, f);
    if (st == HV_OK && cmd == HV_SLCAN_FRAME && !P->open)
        st = HV_ERR_SLCAN_CLOSED;
    if (st != HV_OK) {
        P->bad_lines++;
        hv_fw_port_report_error(st);
        return 0;
    }
    switch (cmd) {
    case HV_SLCAN_OPEN: P->open = 1; break;
    case HV_SLCAN_CLOSE: P->open = 0; break;
    case HV_SLCAN_VERSION: hv_fw_uart_puts("V0101"); break;
    case HV_SLCAN_SERIAL: hv_fw_uart_puts("NHVFW"); break;
    case HV_SLCAN_FLAGS: hv_fw_uart_puts("F00"); break;
    case HV_SLCAN_FRAME:
        /* the reply first: frames the caller's step sends must start lines of their own */
        hv_fw_uart_puts((f->flags & HV_CAN_FLAG_EXT) ? "Z\r" : "z\r");
        P->frames_rx++;
        return 1;
    default: break;
    }
    hv_fw_uart_puts("\r");
    return 0;
}

static hv_status_t fw_recv(void *ctx, hv_can_frame_t *f)
{
    hv_fw_port_t *P = ctx;
    for (;;) {
        uint8_t b;
        int r = hv_fw_uart_getc(&b);
        if (r == 1)
            return HV_CAN_ERR_TIMEOUT;
        if (r == HV_ERR_FW_UART_OVERRUN) {
            /* the line under way lost a byte: drop it whole up to its CR, never act on what
             * is left of it; b came after the loss (fw_board.h) and may be that CR */
            P->overruns++;
            hv_fw_port_report_error(r);
            hv_slcan_lost(&P->rx);
        }
        r = hv_slcan_feed(&P->rx, b);
        if (r == 1 && on_line(P, f))
            return HV_OK;
        if (r < 0) {
            P->bad_lines++;
            hv_fw_port_report_error(r);
        }
    }
}

/* WFI until the UART's RX interrupt or timer 0 (1 kHz): back within 1 ms, early as the
 * port's contract allows */
static hv_status_t fw_wait(void *ctx, uint64_t until_ns)
{
    hv_fw_port_t *P = ctx;
    if (hv_fw_clock_ns(&P->clock) < until_ns)
        hv_fw_idle();
    return HV_OK;
}

static hv_status_t fw_journal(void *ctx, const hv_exec_action_t *record, hv_exec_real_t t_s)
{
    hv_fw_port_t *P = ctx;
    hv_status_t st = hv_fw_journal_append(&P->journal, record, t_s);
    if (st == HV_OK)
        P->journal_records++;
    return st;
}

void hv_fw_port_init(hv_exec_port_t *port, hv_fw_port_t *ctx)
{
    memset(ctx, 0, sizeof *ctx);
    hv_fw_uart_init();
    hv_fw_clock_init(&ctx->clock);
    hv_fw_wake_init();
    ctx->store_status = hv_fw_semihost_open(&ctx->storage, &ctx->store);
    port->ctx = ctx;
    port->now_ns = fw_now_ns;
    port->can_send = fw_send;
    port->can_recv = fw_recv;
    port->wait = fw_wait;
    port->journal_append = fw_journal;
}
