/* Reset and the vector table of the Cortex-M4 (ARMv7-M): the core loads the stack pointer
 * from word 0 and jumps to word 1. Startup copies .data from its load address, zeroes
 * .bss, turns on the FPU (the code is built for hard float) and calls hv_fw_main. */
#include <stdint.h>

#include "fw_board.h"

/* linker script symbols (mps2_an386.ld) */
extern uint32_t hv_fw_data_start[], hv_fw_data_end[], hv_fw_data_load[];
extern uint32_t hv_fw_bss_start[], hv_fw_bss_end[], hv_fw_stack_top[];

void hv_fw_reset(void);
void hv_fw_fault(void);

void hv_fw_reset(void)
{
    const uint32_t *src = hv_fw_data_load;
    for (uint32_t *dst = hv_fw_data_start; dst < hv_fw_data_end;)
        *dst++ = *src++;
    for (uint32_t *dst = hv_fw_bss_start; dst < hv_fw_bss_end;)
        *dst++ = 0u;
    /* CPACR: full access to CP10 and CP11 (the FPU) before any floating-point code */
    HV_FW_REG(0xE000ED88u) |= (0xFu << 20);
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    hv_fw_main();
    for (;;)
        __asm__ volatile("wfi");
}

/* Any fault or unexpected interrupt: report once on the UART and stop; the nodes see our
 * heartbeat stop and hold (DBC: heartbeat timeout). */
void hv_fw_fault(void)
{
    hv_fw_board_panic("fault");
}

/* Initial SP, reset, then NMI, HardFault, MemManage, BusFault, UsageFault, 4 reserved,
 * SVCall, DebugMonitor, reserved, PendSV, SysTick (its interrupt stays off), then the
 * AN386's interrupts 0..15: only UART0 RX (0) and timer 0 (8) are enabled. */
#define HV_FW_VECTORS (16 + 16)
__attribute__((section(".vectors"), used)) static void (*const vectors[HV_FW_VECTORS])(void) = {
    (void (*)(void))(uintptr_t)hv_fw_stack_top,
    hv_fw_reset,
    hv_fw_fault,
    hv_fw_fault,
    hv_fw_fault,
    hv_fw_fault,
    hv_fw_fault,
    0,
    0,
    0,
    0,
    hv_fw_fault,
    hv_fw_fault,
    0,
    hv_fw_fault,
    hv_fw_fault,
    [16 + 0] = hv_fw_irq_uart_rx,
    [16 + 1] = hv_fw_fault,
    [16 + 2] = hv_fw_fault,
    [16 + 3] = hv_fw_fault,
    [16 + 4] = hv_fw_fault,
    [16 + 5] = hv_fw_fault,
    [16 + 6] = hv_fw_fault,
    [16 + 7] = hv_fw_fault,
    [16 + 8] = hv_fw_irq_timer,
    [16 + 9] = hv_fw_fault,
    [16 + 10] = hv_fw_fault,
    [16 + 11] = hv_fw_fault,
    [16 + 12] = hv_fw_fault,
    [16 + 13] = hv_fw_fault,
    [16 + 14] = hv_fw_fault,
    [16 + 15] = hv_fw_fault,
};
