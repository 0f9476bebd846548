/* The firmware's journal: fixed-size binary records for flash-like storage (fw_store.h),
 * each with its own CRC-32, replayed at boot into the state machine's progress through the
 * mapping the Linux journal uses too (hv/exec_progress.h), so a reset resumes the row as a
 * restart of harvest-exec does: no fruit with an outcome tried again, a fruit whose cut
 * was issued released if still held, never cut twice.
 *
 * Record (HV_FW_JOURNAL_RECORD bytes, little-endian; unused fields 0):
 *   0  u8   kind: 'H' header (record 0 only), 'S' stop reached, 'C' cut issued,
 *           'R' release issued, 'F' outcome, 'D' row done, 'E' operator e-stop clear
 *   1  u8   attempt (C, R, F); H: the format's version (HV_FW_JOURNAL_VERSION)
 *   2  u16  pick, the plan's index (C, R, F); stop, the plan's position (S); H: picks
 *   4  u8   outcome (F); H: u16 stops, bytes 4..5
 *   5  u8   reason (F)
 *   6  u8   nodes, 1 << HV_EXEC_* (E)
 *   7  u8   0
 *   8  u32  the run's plan time in ms (informational); H: CRC-32 of the plan image
 *   12 u32  CRC-32 of bytes 0..11
 *
 * At open: a journal of another plan (header's image CRC, picks or stops) is refused
 * (HV_ERR_FW_JOURNAL_PLAN); the last record torn by a reset (fewer bytes than a record,
 * or a bad CRC with nothing after it) never counted and is ignored, and the next append
 * takes its place; a bad CRC before the last is damage (HV_ERR_FW_JOURNAL_CORRUPT); a
 * record with a good CRC that the plan cannot have (kind, pick, stop, a second outcome)
 * is HV_ERR_FW_JOURNAL_FORMAT. Pure code (the host's tests and the firmware share it). */
#ifndef HV_FW_JOURNAL_H
#define HV_FW_JOURNAL_H

#include <stdint.h>

#include "fw_store.h"
#include "hv/exec_sm.h"

#define HV_FW_JOURNAL_RECORD  16u
#define HV_FW_JOURNAL_VERSION 1u

typedef struct hv_fw_journal {
    const hv_fw_store_t *store; /* NULL until opened */
    uint32_t records;    /* records held, the header included: the next goes at records x 16 */
    uint32_t torn_bytes; /* bytes of a torn last record found at open */
    uint32_t bad_record; /* open's error: the record at fault (0 = the header) */
} hv_fw_journal_t;

/* A journal record of the state machine (an HV_ACT_JOURNAL action) at plan time t_s into
 * out. HV_ERR_ARG for one that has no encoding (a field beyond its width). */
hv_status_t hv_fw_journal_encode(const hv_exec_action_t *rec, hv_exec_real_t t_s,
                                 uint8_t out[HV_FW_JOURNAL_RECORD]);

/* A record back into an HV_ACT_JOURNAL action (*t_ms: its plan time, ms; may be NULL).
 * HV_ERR_FW_JOURNAL_CORRUPT for a bad CRC, HV_ERR_FW_JOURNAL_FORMAT for a header, an
 * unknown kind or a field that must be 0 and is not. */
hv_status_t hv_fw_journal_decode(const uint8_t in[HV_FW_JOURNAL_RECORD], hv_exec_action_t *rec,
                                 uint32_t *t_ms);

/* The journal on `store` for `plan`, whose plan image had CRC-32 `plan_crc`: replays what
 * it holds into `progress` (zeroed first), or writes the header when it holds nothing.
 * HV_OK, or the codes above and HV_ERR_FW_JOURNAL_IO (j->bad_record names the record). */
hv_status_t hv_fw_journal_open(hv_fw_journal_t *j, const hv_fw_store_t *store,
                               const hv_exec_plan_t *plan, uint32_t plan_crc,
                               hv_exec_progress_t *progress);

/* Append one record durably (the store's write returned). HV_ERR_FW_JOURNAL_IO when the
 * journal is not open or the store failed; HV_ERR_ARG as hv_fw_journal_encode. */
hv_status_t hv_fw_journal_append(hv_fw_journal_t *j, const hv_exec_action_t *rec,
                                 hv_exec_real_t t_s);

#endif /* HV_FW_JOURNAL_H */
