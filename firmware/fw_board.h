/* Board support of QEMU's mps2-an386 (Arm AN386, Cortex-M4 at SYSCLK 25 MHz; QEMU
 * hw/arm/mps2.c): the SysTick as the clock, UART0 (CMSDK APB UART at 0x40004000, QEMU's
 * first -serial), a panic line. The main loop is the only thread and polls; interrupts
 * only wake it from its idle WFI (a received byte, timer 0 every millisecond) and keep no
 * state: their handlers just clear the source. Idling matters in QEMU too: a loop that
 * polls device registers without pause starves QEMU's I/O thread, and the serial line's
 * bytes then arrive late. */
#ifndef HV_FW_BOARD_H
#define HV_FW_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "hv/status.h"

#define HV_FW_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

#define HV_FW_SYSCLK_HZ 25000000u /* AN386 SYSCLK, which also clocks the SysTick */
#define HV_FW_UART_BAUD 115200u   /* QEMU ignores it; a real board's host side must match */

/* Monotonic time from the 24-bit SysTick down-counter, extended to 64 bits by reading it
 * at least every 0.67 s (2^24 / 25 MHz): the main loop does. */
typedef struct hv_fw_clock {
    uint32_t last;   /* counter at the previous read */
    uint64_t cycles; /* SYSCLK cycles since hv_fw_clock_init */
} hv_fw_clock_t;

void hv_fw_clock_init(hv_fw_clock_t *c);
uint64_t hv_fw_clock_cycles(hv_fw_clock_t *c); /* SYSCLK cycles since init */
uint64_t hv_fw_clock_ns(hv_fw_clock_t *c);     /* the same in ns */

/* UART0, 8N1, polled. */
void hv_fw_uart_init(void);
void hv_fw_uart_write(const char *s, size_t n); /* blocks while the TX buffer is full */
void hv_fw_uart_puts(const char *s);
/* One received byte into *b: HV_OK, 1 when none waits, HV_ERR_FW_UART_OVERRUN when the
 * UART lost a byte since the last call (the byte in *b is the one after the loss; the
 * caller drops the line it was in). */
int hv_fw_uart_getc(uint8_t *b);

/* Timer 0 at 1 kHz and the UART's RX interrupt as wake-up sources (NVIC). */
void hv_fw_wake_init(void);
/* Sleep until an interrupt (at most 1 ms). */
void hv_fw_idle(void);
/* the interrupt handlers (startup.c's vector table) */
void hv_fw_irq_uart_rx(void);
void hv_fw_irq_timer(void);

/* Report `what` on the UART and stop (interrupts off, wait forever). */
void hv_fw_board_panic(const char *what) __attribute__((noreturn));

/* The firmware's entry, called by the reset handler (fw_main.c). */
void hv_fw_main(void);

#endif /* HV_FW_BOARD_H */
