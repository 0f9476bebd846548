/* The board's storage for the journal, as one small driver interface: what survives a
 * reset (flash, FRAM; in QEMU a host file through semihosting, fw_semihost.h). The
 * journal (fw_journal.h) decides what goes where; a driver only keeps bytes:
 *   - read returns what earlier writes left, from the start of the journal area, and
 *     stops where they end (a flash driver: at the first slot still erased);
 *   - write stores bytes at an offset durably: when it returns HV_OK they outlive a reset.
 * A write at an offset the journal wrote before replaces a record torn by a reset (only
 * the last record can be torn): a flash driver that cannot overwrite in place keeps the
 * records' order another way (e.g. skips the torn slot and reads it back as absent). */
#ifndef HV_FW_STORE_H
#define HV_FW_STORE_H

#include <stdint.h>

#include "hv/status.h"

typedef struct hv_fw_store {
    void *ctx; /* the driver's state, passed to every call */
    /* up to n bytes from `offset` (bytes) into buf; *got: how many there were (fewer than
     * n only where what was written ends). HV_OK or HV_ERR_FW_JOURNAL_IO. */
    hv_status_t (*read)(void *ctx, uint32_t offset, uint8_t *buf, uint32_t n, uint32_t *got);
    /* n bytes at `offset`, durable on return. HV_OK or HV_ERR_FW_JOURNAL_IO. */
    hv_status_t (*write)(void *ctx, uint32_t offset, const uint8_t *buf, uint32_t n);
} hv_fw_store_t;

#endif /* HV_FW_STORE_H */
