/* harvest-fw: the executor's state machine as firmware on mps2-an386 (executor/README.md,
 * "The firmware port"). One loop, no interrupts: read the clock, take what the UART
 * brings (SLCAN lines: commands and frames from the bus), step the state machine on each
 * frame it reads and every 10 ms, send the frames of its actions back as SLCAN lines.
 * Text lines for people (banner, status once a second) start with "harvest-fw:" and end
 * with CR like SLCAN lines; python-can's slcan reader skips them. */
#include <stdint.h>
#include <string.h>

#include "fw_board.h"
#include "fw_status.h"
#include "hv/exec_can.h"
#include "hv/exec_sm.h"
#include "hv/exec_status.h"
#include "fw_upload.h"
#include "slcan.h"

#define TICK_NS 10000000u    /* the state machine's timer tick, like harvest-exec's */
#define REPORT_NS 1000000000u /* status line period */

typedef struct hv_fw {
    hv_fw_clock_t clock;
    hv_exec_plan_t plan;
    hv_exec_params_t prm;
    hv_fw_upload_t upload;
    hv_exec_sm_t sm;
    hv_exec_actions_t out;
    hv_exec_can_tx_t tx;
    hv_exec_arm_sample_t samples[2];
    hv_slcan_rx_t rx;
    int open;        /* SLCAN channel opened by the host (O) */
    int running;     /* a plan is loaded and the state machine runs */
    uint64_t next_tick_ns, next_report_ns, next_upload_status_ns;
    uint64_t steps, step_cycles_max;
    uint32_t frames_rx, frames_tx, bad_lines, overruns;
} hv_fw_t;

/* decimal digits of v into buf (no stdio in the firmware) */
static size_t fmt_u64(char *buf, uint64_t v)
{
    char tmp[20];
    size_t n = 0, k = 0;
    do {
        tmp[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v);
    while (n)
        buf[k++] = tmp[--n];
    return k;
}

static void put_field(const char *name, uint64_t v)
{
    char num[21];
    hv_fw_uart_puts(name);
    hv_fw_uart_write(num, fmt_u64(num, v));
}

static void report(hv_fw_t *fw, uint64_t now)
{
    hv_fw_uart_puts("harvest-fw: status");
    put_field(" up_ms=", now / 1000000u);
    put_field(" steps=", fw->steps);
    put_field(" worst_step_cycles=", fw->step_cycles_max);
    put_field(" rx=", fw->frames_rx);
    put_field(" tx=", fw->frames_tx);
    put_field(" bad_lines=", fw->bad_lines);
    put_field(" overruns=", fw->overruns);
    hv_fw_uart_puts(" phase=");
    hv_fw_uart_puts(fw->running ? hv_exec_phase_name(fw->sm.phase) : "NO_PLAN");
    hv_fw_uart_puts("\r");
}

/* A named error on the UART: Lawicel's BELL, then a text line naming it. */
static void report_error(int status)
{
    hv_fw_uart_puts("\aharvest-fw: error ");
    hv_fw_uart_puts(hv_fw_status_name(status));
    hv_fw_uart_puts("\r");
}

static void send_frame(hv_fw_t *fw, const hv_can_frame_t *f)
{
    char line[HV_SLCAN_LINE_MAX + 1];
    size_t n = hv_slcan_format(f, line, sizeof line);
    if (!fw->open || n == 0)
        return; /* a closed channel carries no frames (Lawicel) */
    hv_fw_uart_write(line, n);
    fw->frames_tx++;
}

static void carry_out(hv_fw_t *fw)
{
    for (unsigned i = 0; i < fw->out.n; i++) {
        hv_can_frame_t f;
        int has = 0;
        if (hv_exec_can_encode(&fw->out.a[i], &fw->tx, &f, &has) == HV_OK && has)
            send_frame(fw, &f);
    }
    fw->out.n = 0;
}

static void step(hv_fw_t *fw, const hv_exec_event_t *ev, uint64_t now)
{
    uint64_t c0 = hv_fw_clock_cycles(&fw->clock);
    hv_status_t st = hv_exec_step(&fw->sm, ev, now, &fw->out);
    uint64_t dc = hv_fw_clock_cycles(&fw->clock) - c0;
    fw->steps++;
    if (dc > fw->step_cycles_max)
        fw->step_cycles_max = dc;
    if (st != HV_OK && st != HV_ERR_EXEC_ACTIONS_FULL)
        fw->out.n = 0; /* an event out of its domain: ignored */
    carry_out(fw);
}

static void send_upload_status(hv_fw_t *fw, uint64_t now)
{
    hv_can_frame_t f;
    hv_fw_upload_status(&fw->upload, &f);
    send_frame(fw, &f);
    fw->next_upload_status_ns = now + REPORT_NS;
}

/* A whole plan arrived: run it, or refuse it when the state machine does (parameters). */
static void start_plan(hv_fw_t *fw, uint64_t now)
{
    hv_status_t st = hv_exec_init(&fw->sm, &fw->plan, &fw->prm, NULL);
    if (st != HV_OK) {
        fw->upload.state = HV_UPLOAD_REFUSED;
        fw->upload.error = st;
        return;
    }
    fw->upload.state = HV_UPLOAD_RUNNING;
    fw->running = 1;
    fw->next_tick_ns = now;
}

static void on_frame(hv_fw_t *fw, const hv_can_frame_t *f, uint64_t now)
{
    hv_exec_event_t ev;
    int answer = 0;
    fw->frames_rx++;
    if (hv_fw_upload_frame(&fw->upload, f, &fw->plan, &fw->prm, &answer)) {
        if (fw->upload.state == HV_UPLOAD_ACCEPTED)
            start_plan(fw, now);
        if (answer) {
            if (fw->upload.error != HV_OK)
                report_error(fw->upload.error);
            send_upload_status(fw, now);
        }
        return;
    }
    if (fw->running && hv_exec_can_decode(f, &ev, fw->samples) == HV_RX_EVENT)
        step(fw, &ev, now);
}

static void on_line(hv_fw_t *fw, uint64_t now)
{
    hv_slcan_cmd_t cmd;
    hv_can_frame_t f;
    hv_status_t st = hv_slcan_parse(fw->rx.line, fw->rx.done, &cmd, &f);
    if (st == HV_OK && cmd == HV_SLCAN_FRAME && !fw->open)
        st = HV_ERR_SLCAN_CLOSED;
    if (st != HV_OK) {
        fw->bad_lines++;
        report_error(st);
        return;
    }
    switch (cmd) {
    case HV_SLCAN_OPEN: fw->open = 1; break;
    case HV_SLCAN_CLOSE: fw->open = 0; break;
    case HV_SLCAN_VERSION: hv_fw_uart_puts("V0101"); break;
    case HV_SLCAN_SERIAL: hv_fw_uart_puts("NHVFW"); break;
    case HV_SLCAN_FLAGS: hv_fw_uart_puts("F00"); break;
    case HV_SLCAN_FRAME:
        /* the reply first: frames the step sends must start lines of their own */
        hv_fw_uart_puts((f.flags & HV_CAN_FLAG_EXT) ? "Z\r" : "z\r");
        on_frame(fw, &f, now);
        return;
    default: break;
    }
    hv_fw_uart_puts("\r");
}

/* Returns the number of bytes taken. */
static int poll_uart(hv_fw_t *fw, uint64_t now)
{
    int k;
    for (k = 0; k < 64; k++) {
        uint8_t b;
        int r = hv_fw_uart_getc(&b);
        if (r == 1)
            break;
        if (r == HV_ERR_FW_UART_OVERRUN) {
            /* the line under way lost a byte: drop it whole, never act on half a line */
            fw->overruns++;
            report_error(r);
            hv_slcan_reset(&fw->rx);
            continue;
        }
        r = hv_slcan_feed(&fw->rx, b);
        if (r == 1) {
            on_line(fw, now);
        } else if (r < 0) {
            fw->bad_lines++;
            report_error(r);
        }
    }
    return k;
}

void hv_fw_main(void)
{
    /* the firmware's one instance: static storage (RAM the linker accounts for), reached
     * from here only */
    static hv_fw_t fw;
    hv_fw_uart_init();
    hv_fw_clock_init(&fw.clock);
    hv_fw_wake_init();
    hv_fw_uart_puts("harvest-fw: mps2-an386 cortex-m4f, SLCAN on UART0, waiting for a plan\r");
    for (;;) {
        uint64_t now = hv_fw_clock_ns(&fw.clock);
        int busy = poll_uart(&fw, now);
        if (fw.running && now >= fw.next_tick_ns) {
            hv_exec_event_t tick;
            memset(&tick, 0, sizeof tick);
            tick.kind = HV_EV_TICK;
            step(&fw, &tick, now);
            fw.next_tick_ns = now + TICK_NS;
        }
        if (!fw.running && fw.open && now >= fw.next_upload_status_ns)
            send_upload_status(&fw, now);
        if (now >= fw.next_report_ns) {
            report(&fw, now);
            fw.next_report_ns = now + REPORT_NS;
        }
        if (!busy)
            hv_fw_idle();
    }
}
