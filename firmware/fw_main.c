/* harvest-fw: the executor's state machine as firmware on mps2-an386 (firmware/README.md).
 * One loop around the port (fw_port.h): take the frames the UART brings, the plan upload
 * first (fw_upload.h), then step the state machine on each frame and every 10 ms and
 * carry out its actions through the port; sleep in its wait (WFI) when nothing came. Text
 * lines for people (banner, status once a second) start with "harvest-fw:" and end with CR
 * like SLCAN lines; python-can's slcan reader skips them. */
#include <stdint.h>
#include <string.h>

#include "fw_port.h"
#include "fw_status.h"
#include "fw_upload.h"
#include "hv/exec_can.h"
#include "hv/exec_port.h"
#include "hv/exec_sm.h"
#include "hv/exec_status.h"

#define TICK_NS          10000000u   /* the state machine's timer tick, like harvest-exec's */
#define REPORT_NS        1000000000u /* status line period */
/* PlanStatus repeated while waiting for a plan: the DBC's cycle */
#define UPLOAD_STATUS_NS ((uint64_t)HV_CAN_PLAN_STATUS_CYCLE_MS * 1000000u)

typedef struct hv_fw {
    hv_exec_port_t port;
    hv_fw_port_t board;
    hv_exec_plan_t plan;
    hv_exec_params_t prm;
    hv_exec_progress_t progress; /* replayed from the journal when the plan arrives */
    hv_fw_upload_t upload;
    hv_exec_sm_t sm;
    hv_exec_actions_t out;
    hv_exec_can_tx_t tx;
    hv_exec_port_stats_t st;
    hv_exec_arm_sample_t samples[2];
    int running; /* a plan is loaded and the state machine runs */
    uint64_t next_tick_ns, next_report_ns, next_upload_status_ns;
    uint64_t steps, step_cycles_max;
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

static void report(const hv_fw_t *fw, uint64_t now)
{
    hv_fw_uart_puts("harvest-fw: status");
    put_field(" up_ms=", now / 1000000u);
    put_field(" steps=", fw->steps);
    put_field(" worst_step_cycles=", fw->step_cycles_max);
    put_field(" rx=", fw->board.frames_rx);
    put_field(" tx=", fw->board.frames_tx);
    put_field(" bad_lines=", fw->board.bad_lines);
    put_field(" overruns=", fw->board.overruns);
    put_field(" journal=", fw->board.journal_records);
    hv_fw_uart_puts(" phase=");
    hv_fw_uart_puts(fw->running ? hv_exec_phase_name(fw->sm.phase) : "NO_PLAN");
    if (fw->running && fw->sm.phase == HV_PH_SAFE) {
        hv_fw_uart_puts(" safe_reason=");
        hv_fw_uart_puts(hv_exec_safe_reason_name(fw->sm.safe_reason));
        hv_fw_uart_puts(" safe_node=");
        hv_fw_uart_puts(hv_exec_node_name(fw->sm.safe_node));
    }
    hv_fw_uart_puts("\r");
}

static void step(hv_fw_t *fw, const hv_exec_event_t *ev, uint64_t now)
{
    uint64_t c0 = hv_fw_clock_cycles(&fw->board.clock);
    hv_status_t st = hv_exec_step(&fw->sm, ev, now, &fw->out);
    uint64_t dc = hv_fw_clock_cycles(&fw->board.clock) - c0;
    fw->steps++;
    if (dc > fw->step_cycles_max)
        fw->step_cycles_max = dc;
    hv_status_t rc = HV_OK;
    if (st == HV_OK || st == HV_ERR_EXEC_ACTIONS_FULL) /* else: out of its domain, ignored */
        rc = hv_exec_port_carry_out(&fw->port, &fw->tx, &fw->out, hv_exec_executed_s(&fw->sm, now),
                                    &fw->st, NULL);
    fw->out.n = 0;
    if (rc != HV_OK) {
        hv_exec_event_t jf;
        memset(&jf, 0, sizeof jf);
        jf.kind = HV_EV_JOURNAL_FAILED;
        step(fw, &jf, now);
    }
}

static void send_upload_status(hv_fw_t *fw, uint64_t now)
{
    hv_can_frame_t f;
    hv_fw_upload_status(&fw->upload, &f);
    fw->port.can_send(fw->port.ctx, &f);
    fw->next_upload_status_ns = now + UPLOAD_STATUS_NS;
}

/* What the journal brought back: records held, torn bytes ignored, fruits with an outcome. */
static void report_journal(const hv_fw_t *fw)
{
    unsigned done = 0;
    for (unsigned i = 0; i < fw->plan.n_picks; i++)
        done += fw->progress.pick[i] == HV_PROG_DONE;
    hv_fw_uart_puts("harvest-fw: journal");
    put_field(" records=", fw->board.journal.records);
    put_field(" torn_bytes=", fw->board.journal.torn_bytes);
    put_field(" outcomes=", done);
    put_field(" row_done=", (uint64_t)fw->progress.row_done);
    hv_fw_uart_puts("\r");
}

/* A whole plan arrived: replay its journal and run it from there, or refuse it when the
 * state machine (parameters) or the journal (storage, another plan's, damage) does. The
 * parameters are checked first: a refused plan leaves a fresh journal without a header,
 * so the corrected plan is not taken for another plan's. */
static void start_plan(hv_fw_t *fw, uint64_t now)
{
    hv_status_t st = hv_exec_init(&fw->sm, &fw->plan, &fw->prm, NULL);
    if (st == HV_OK)
        st = fw->board.store_status;
    if (st == HV_OK)
        st = hv_fw_journal_open(&fw->board.journal, &fw->board.store, &fw->plan, fw->upload.rd.crc,
                                &fw->progress);
    if (st == HV_OK)
        st = hv_exec_init(&fw->sm, &fw->plan, &fw->prm, &fw->progress);
    if (st != HV_OK) {
        fw->upload.state = HV_UPLOAD_REFUSED;
        fw->upload.error = st;
        return;
    }
    report_journal(fw);
    fw->upload.state = HV_UPLOAD_RUNNING;
    fw->running = 1;
    fw->next_tick_ns = now;
}

static void on_frame(hv_fw_t *fw, const hv_can_frame_t *f, uint64_t now)
{
    hv_exec_event_t ev;
    int answer = 0;
    if (hv_fw_upload_frame(&fw->upload, f, &fw->plan, &fw->prm, &answer)) {
        if (fw->upload.state == HV_UPLOAD_ACCEPTED)
            start_plan(fw, now);
        if (answer) {
            if (fw->upload.error != HV_OK)
                hv_fw_port_report_error(fw->upload.error);
            send_upload_status(fw, now);
        }
        return;
    }
    if (fw->running && hv_exec_can_decode(f, &ev, fw->samples) == HV_RX_EVENT)
        step(fw, &ev, now);
}

/* When the loop must run again without a frame: the next tick while a plan runs, the
 * status line, the upload status while waiting for a plan. */
static uint64_t next_deadline(const hv_fw_t *fw)
{
    uint64_t t = fw->next_report_ns;
    if (fw->running && fw->next_tick_ns < t)
        t = fw->next_tick_ns;
    if (!fw->running && fw->board.open && fw->next_upload_status_ns < t)
        t = fw->next_upload_status_ns;
    return t;
}

void hv_fw_main(void)
{
    /* the firmware's one instance: static storage (RAM the linker accounts for), reached
     * from here only */
    static hv_fw_t fw;
    hv_fw_port_init(&fw.port, &fw.board);
    hv_fw_uart_puts("harvest-fw: mps2-an386 cortex-m4f, SLCAN on UART0, waiting for a plan\r");
    if (fw.board.store_status != HV_OK)
        hv_fw_port_report_error(fw.board.store_status); /* every upload is refused with it */
    for (;;) {
        uint64_t now = fw.port.now_ns(fw.port.ctx);
        hv_can_frame_t f;
        int busy = 0;
        for (int k = 0; k < 8 && fw.port.can_recv(fw.port.ctx, &f) == HV_OK; k++, busy = 1)
            on_frame(&fw, &f, now);
        if (fw.running && now >= fw.next_tick_ns) {
            hv_exec_event_t tick;
            memset(&tick, 0, sizeof tick);
            tick.kind = HV_EV_TICK;
            step(&fw, &tick, now);
            fw.next_tick_ns = now + TICK_NS;
        }
        if (!fw.running && fw.board.open && now >= fw.next_upload_status_ns)
            send_upload_status(&fw, now);
        if (now >= fw.next_report_ns) {
            report(&fw, now);
            fw.next_report_ns = now + REPORT_NS;
        }
        if (!busy) /* WFI (fw_port.c); it cannot fail */
            (void)fw.port.wait(fw.port.ctx, next_deadline(&fw));
    }
}
