/* The executor's port on mps2-an386 (hv/exec_port.h): the SysTick clock, CAN as SLCAN
 * lines on UART0 (slcan.h), the journal (fw_journal.h) on the board's storage (in QEMU a
 * host file through semihosting, fw_semihost.h), so a reset resumes the row. */
#ifndef HV_FW_PORT_H
#define HV_FW_PORT_H

#include <stdint.h>

#include "fw_board.h"
#include "fw_journal.h"
#include "fw_semihost.h"
#include "hv/exec_port.h"
#include "slcan.h"

typedef struct hv_fw_port {
    hv_fw_clock_t clock;
    hv_slcan_rx_t rx;
    int open; /* the host opened the SLCAN channel (O) */
    uint32_t frames_rx, frames_tx, bad_lines, overruns, journal_records;
    hv_fw_semihost_t storage;
    hv_fw_store_t store;
    hv_status_t store_status; /* of opening the storage at init */
    hv_fw_journal_t journal;  /* opened on the plan, once it arrived (fw_main.c) */
} hv_fw_port_t;

/* Set up the board's clock, UART and storage and fill `port` with the firmware's
 * functions; ctx->store_status tells whether the storage opened. */
void hv_fw_port_init(hv_exec_port_t *port, hv_fw_port_t *ctx);

/* A named error on the UART: Lawicel's BELL, then "harvest-fw: error NAME". */
void hv_fw_port_report_error(int status);

#endif /* HV_FW_PORT_H */
