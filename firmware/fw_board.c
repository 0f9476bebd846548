/* mps2-an386 board support: SysTick clock, CMSDK UART0, panic (see fw_board.h). */
#include "fw_board.h"

#include <string.h>

#include "fw_status.h"

/* SysTick (ARMv7-M system control space) */
#define SYST_CSR        0xE000E010u
#define SYST_RVR        0xE000E014u
#define SYST_CVR        0xE000E018u
#define SYST_CSR_ENABLE 0x1u
#define SYST_CSR_CPUCLK 0x4u /* count the processor clock, no interrupt */
#define SYST_MASK       0x00FFFFFFu

/* CMSDK APB UART registers (Arm CMSDK TRM) */
#define UART0_BASE            0x40004000u
#define UART_DATA             (UART0_BASE + 0x00u)
#define UART_STATE            (UART0_BASE + 0x04u)
#define UART_CTRL             (UART0_BASE + 0x08u)
#define UART_INTCLEAR         (UART0_BASE + 0x0Cu)
#define UART_BAUDDIV          (UART0_BASE + 0x10u)
#define UART_STATE_TX_FULL    0x1u
#define UART_STATE_RX_FULL    0x2u
#define UART_STATE_RX_OVERRUN 0x8u /* write 1 to clear */
#define UART_CTRL_TX_EN       0x1u
#define UART_CTRL_RX_EN       0x2u
#define UART_CTRL_RX_IRQ      0x8u
#define UART_INT_RX           0x2u

/* CMSDK APB timer 0: the idle loop's wake-up every millisecond */
#define TIMER0_BASE    0x40000000u
#define TIMER_CTRL     (TIMER0_BASE + 0x00u)
#define TIMER_VALUE    (TIMER0_BASE + 0x04u)
#define TIMER_RELOAD   (TIMER0_BASE + 0x08u)
#define TIMER_INTCLEAR (TIMER0_BASE + 0x0Cu)
#define TIMER_CTRL_EN  0x1u
#define TIMER_CTRL_IRQ 0x8u
#define WAKE_HZ        1000u

/* NVIC: the AN386's interrupt numbers (QEMU hw/arm/mps2.c) */
#define NVIC_ISER0   0xE000E100u
#define IRQ_UART0_RX 0u
#define IRQ_TIMER0   8u

void hv_fw_clock_init(hv_fw_clock_t *c)
{
    HV_FW_REG(SYST_CSR) = 0u;
    HV_FW_REG(SYST_RVR) = SYST_MASK;
    HV_FW_REG(SYST_CVR) = 0u; /* any write reloads */
    HV_FW_REG(SYST_CSR) = SYST_CSR_ENABLE | SYST_CSR_CPUCLK;
    c->last = HV_FW_REG(SYST_CVR) & SYST_MASK;
    c->cycles = 0u;
}

uint64_t hv_fw_clock_cycles(hv_fw_clock_t *c)
{
    uint32_t now = HV_FW_REG(SYST_CVR) & SYST_MASK;
    c->cycles += (c->last - now) & SYST_MASK; /* counts down, wraps at 2^24 */
    c->last = now;
    return c->cycles;
}

uint64_t hv_fw_clock_ns(hv_fw_clock_t *c)
{
    return hv_fw_clock_cycles(c) * (1000000000u / HV_FW_SYSCLK_HZ);
}

void hv_fw_uart_init(void)
{
    HV_FW_REG(UART_CTRL) = 0u;
    HV_FW_REG(UART_BAUDDIV) = HV_FW_SYSCLK_HZ / HV_FW_UART_BAUD;
    HV_FW_REG(UART_STATE) = UART_STATE_RX_OVERRUN;
    HV_FW_REG(UART_CTRL) = UART_CTRL_TX_EN | UART_CTRL_RX_EN | UART_CTRL_RX_IRQ;
}

void hv_fw_wake_init(void)
{
    HV_FW_REG(TIMER_CTRL) = 0u;
    HV_FW_REG(TIMER_RELOAD) = HV_FW_SYSCLK_HZ / WAKE_HZ;
    HV_FW_REG(TIMER_VALUE) = HV_FW_SYSCLK_HZ / WAKE_HZ;
    HV_FW_REG(TIMER_CTRL) = TIMER_CTRL_EN | TIMER_CTRL_IRQ;
    HV_FW_REG(NVIC_ISER0) = (1u << IRQ_UART0_RX) | (1u << IRQ_TIMER0);
}

void hv_fw_idle(void)
{
    __asm__ volatile("wfi" ::: "memory");
}

void hv_fw_irq_uart_rx(void)
{
    HV_FW_REG(UART_INTCLEAR) = UART_INT_RX;
}

void hv_fw_irq_timer(void)
{
    HV_FW_REG(TIMER_INTCLEAR) = 1u;
}

void hv_fw_uart_write(const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        while (HV_FW_REG(UART_STATE) & UART_STATE_TX_FULL) {
        }
        HV_FW_REG(UART_DATA) = (uint8_t)s[i];
    }
}

void hv_fw_uart_puts(const char *s)
{
    hv_fw_uart_write(s, strlen(s));
}

int hv_fw_uart_getc(uint8_t *b)
{
    uint32_t st = HV_FW_REG(UART_STATE);
    if (st & UART_STATE_RX_OVERRUN) {
        HV_FW_REG(UART_STATE) = UART_STATE_RX_OVERRUN;
        *b = (uint8_t)HV_FW_REG(UART_DATA);
        return HV_ERR_FW_UART_OVERRUN;
    }
    if (!(st & UART_STATE_RX_FULL))
        return 1;
    *b = (uint8_t)HV_FW_REG(UART_DATA);
    return HV_OK;
}

void hv_fw_board_panic(const char *what)
{
    __asm__ volatile("cpsid i" ::: "memory");
    hv_fw_uart_puts("harvest-fw: panic: ");
    hv_fw_uart_puts(what);
    hv_fw_uart_puts("\r\n");
    for (;;)
        __asm__ volatile("wfi");
}
