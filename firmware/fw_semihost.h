/* The journal's storage in QEMU: a host file through Arm semihosting (QEMU runs with
 * -semihosting-config enable=on,target=native), standing for the flash or FRAM of a real
 * board; it implements fw_store.h, so a board's flash driver takes its place unchanged.
 * The firmware issues the calls itself (BKPT 0xAB with the operation in r0 and its
 * parameter block in r1; Arm's semihosting specification): SYS_GET_CMDLINE for the file's
 * name, SYS_OPEN, SYS_SEEK, SYS_READ, SYS_WRITE. A written record is in the host's file
 * when SYS_WRITE returns, so it outlives QEMU however QEMU ends (SIGKILL included).
 *
 * The file is named on QEMU's semihosting command line (its arg= values, joined by
 * spaces): "harvest-fw --journal PATH". Without semihosting enabled, BKPT 0xAB faults:
 * every QEMU command line of the firmware enables it (harvest.firmware.rig). */
#ifndef HV_FW_SEMIHOST_H
#define HV_FW_SEMIHOST_H

#include <stdint.h>

#include "fw_store.h"

#define HV_FW_SEMIHOST_PATH_MAX 200u

typedef struct hv_fw_semihost {
    int32_t handle; /* the host file's, -1 when not open */
} hv_fw_semihost_t;

/* Open (create when absent, never truncate) the journal file the command line names and
 * fill `store` with its functions. HV_ERR_FW_JOURNAL_IO when no file is named or it cannot
 * be opened (store's calls then fail with it too). */
hv_status_t hv_fw_semihost_open(hv_fw_semihost_t *s, hv_fw_store_t *store);

#endif /* HV_FW_SEMIHOST_H */
