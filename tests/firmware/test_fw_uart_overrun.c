/* The firmware's port on a fake UART (firmware/fw_port.c): a UART with the CMSDK's one-byte
 * receive register, fed from a wire where a burst of bytes arrives at once, more than the
 * register holds, as when the main loop polls late. The port counts the overrun, reports it
 * by name, never acts on what is left of the damaged line, and takes the lines after it.
 *
 * fw_port.c calls the board's functions (fw_board.h) by name, so the fake is one UART in
 * static storage, set up by each test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw_port.h"
#include "fw_status.h"

typedef struct fake_uart {
    const char *wire; /* what the host sends */
    size_t len, pos;
    size_t burst_at, burst_len; /* at wire[burst_at], burst_len bytes arrive at once */
    uint8_t hold;               /* the receive register */
    int full, overrun;
    char out[512]; /* what the firmware wrote */
    size_t out_len;
} fake_uart_t;

static fake_uart_t uart;

static void fake_wire(const char *wire, size_t burst_at, size_t burst_len)
{
    memset(&uart, 0, sizeof uart);
    uart.wire = wire;
    uart.len = strlen(wire);
    uart.burst_at = burst_at;
    uart.burst_len = burst_len;
}

/* a byte arriving while the register is full takes the place of the one there, which is
 * lost, and sets the overrun flag: the register holds the byte after the loss (fw_board.h) */
static void arrive(void)
{
    size_t n = uart.pos == uart.burst_at ? uart.burst_len : 1;
    for (size_t i = 0; i < n && uart.pos < uart.len; i++, uart.pos++) {
        uart.overrun |= uart.full;
        uart.hold = (uint8_t)uart.wire[uart.pos];
        uart.full = 1;
    }
}

/* ---- the board (fw_board.h) ---- */

int hv_fw_uart_getc(uint8_t *b)
{
    if (!uart.full)
        arrive();
    if (uart.overrun) { /* as fw_board.c: the flag cleared, the register read */
        uart.overrun = 0;
        uart.full = 0;
        *b = uart.hold;
        return HV_ERR_FW_UART_OVERRUN;
    }
    if (!uart.full)
        return 1;
    uart.full = 0;
    *b = uart.hold;
    return HV_OK;
}

void hv_fw_uart_write(const char *s, size_t n)
{
    for (size_t i = 0; i < n && uart.out_len + 1 < sizeof uart.out; i++)
        uart.out[uart.out_len++] = s[i];
}

void hv_fw_uart_puts(const char *s)
{
    hv_fw_uart_write(s, strlen(s));
}

void hv_fw_uart_init(void)
{
}
void hv_fw_wake_init(void)
{
}
void hv_fw_idle(void)
{
}
void hv_fw_clock_init(hv_fw_clock_t *c)
{
    memset(c, 0, sizeof *c);
}
uint64_t hv_fw_clock_ns(hv_fw_clock_t *c)
{
    return c->cycles;
}

hv_status_t hv_fw_semihost_open(hv_fw_semihost_t *s, hv_fw_store_t *store)
{
    s->handle = -1;
    memset(store, 0, sizeof *store);
    return HV_ERR_FW_JOURNAL_IO; /* no journal: the port's receive side needs none */
}

/* ---- tests ---- */

/* The frames the port hands over until the wire is read, their ids into ids[]. */
static int frames_in(hv_exec_port_t *port, uint32_t *ids, int max)
{
    int n = 0;
    hv_can_frame_t f;
    while (port->can_recv(port->ctx, &f) == HV_OK)
        if (n < max)
            ids[n++] = f.id;
    return n;
}

static void test_wire_without_loss(void **state)
{
    (void)state;
    static hv_fw_port_t ctx;
    hv_exec_port_t port;
    fake_wire("O\rt0212ABCC\rt0221FF\r", (size_t)-1, 0);
    hv_fw_port_init(&port, &ctx);
    uint32_t ids[4];
    assert_int_equal(frames_in(&port, ids, 4), 2);
    assert_int_equal(ids[0], 0x021);
    assert_int_equal(ids[1], 0x022);
    assert_int_equal(ctx.overruns, 0);
    assert_int_equal(ctx.bad_lines, 0);
}

/* The burst hits the first frame: "t0212AB" arrive at once, all but the 'B' lost; what
 * follows the loss ("C" and the CR) is the rest of the damaged line, not the command C:
 * the channel stays open and the next frame arrives. */
static void test_overrun_drops_the_line(void **state)
{
    (void)state;
    static hv_fw_port_t ctx;
    hv_exec_port_t port;
    fake_wire("O\rt0212ABCC\rt0221FF\r", 2, 7);
    hv_fw_port_init(&port, &ctx);
    uint32_t ids[4];
    assert_int_equal(frames_in(&port, ids, 4), 1);
    assert_int_equal(ids[0], 0x022);
    assert_int_equal(ctx.overruns, 1);
    assert_int_equal(ctx.open, 1);
    assert_int_equal(ctx.frames_rx, 1);
    assert_int_equal(ctx.bad_lines, 0); /* the damaged line is the overrun's, reported once */
    assert_non_null(strstr(uart.out, "\aharvest-fw: error HV_ERR_FW_UART_OVERRUN\r"));
}

/* A burst that swallows the CR between two lines: both are damaged, both dropped, and the
 * line after them is taken; a burst whose last byte is a CR damages its line only. */
static void test_overrun_across_lines(void **state)
{
    (void)state;
    static hv_fw_port_t ctx;
    hv_exec_port_t port;
    fake_wire("O\rt0211AA\rt0221BB\rt0231CC\r", 6, 6);
    hv_fw_port_init(&port, &ctx);
    uint32_t ids[4];
    int n = frames_in(&port, ids, 4);
    assert_int_equal(ctx.overruns, 1);
    assert_int_equal(ctx.open, 1);
    assert_int_equal(n, 1);
    assert_int_equal(ids[0], 0x023);
    fake_wire("O\rt0211AA\rt0221BB\rt0231CC\r", 4, 6); /* "21AA\r" lost, its CR held */
    hv_fw_port_init(&port, &ctx);
    assert_int_equal(frames_in(&port, ids, 4), 2);
    assert_int_equal(ids[0], 0x022);
    assert_int_equal(ids[1], 0x023);
    assert_int_equal(ctx.overruns, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wire_without_loss),
        cmocka_unit_test(test_overrun_drops_the_line),
        cmocka_unit_test(test_overrun_across_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
