/* The firmware's journal (see fw_journal.h). */
#include "fw_journal.h"

#include <string.h>

#include "fw_le.h"
#include "fw_status.h"
#include "hv/cost_table.h" /* hv_crc32 */
#include "hv/exec_progress.h"

#define BODY 12u /* bytes the CRC covers */

/* kind letters <-> the state machine's journal kinds, in hv_exec_journal_kind_t order */
static const char kind_letter[] = {'S', 'C', 'R', 'F', 'D', 'E', 'H'}; /* by HV_JR_* */
#define N_KINDS  (sizeof kind_letter)
#define K_HEADER 'H'

static void seal(uint8_t out[HV_FW_JOURNAL_RECORD])
{
    hv_fw_put_u32(out + BODY, hv_crc32(0, out, BODY));
}

static int crc_ok(const uint8_t in[HV_FW_JOURNAL_RECORD])
{
    return hv_fw_get_u32(in + BODY) == hv_crc32(0, in, BODY);
}

/* plan time in whole ms, within u32 (informational: never read back into the run) */
static uint32_t t_ms_of(hv_exec_real_t t_s)
{
    hv_exec_real_t ms = t_s * HV_EXEC_REAL(1000.0);
    if (!(ms > HV_EXEC_REAL(0.0)))
        return 0u;
    /* the largest float below 2^32, so the comparison is exact in either precision */
    return ms >= HV_EXEC_REAL(4294967040.0) ? 0xFFFFFFFFu : (uint32_t)ms;
}

static int fits(int v, int max)
{
    return v >= 0 && v <= max;
}

hv_status_t hv_fw_journal_encode(const hv_exec_action_t *rec, hv_exec_real_t t_s,
                                 uint8_t out[HV_FW_JOURNAL_RECORD])
{
    if (!rec || rec->kind != HV_ACT_JOURNAL || (unsigned)rec->u.jr.kind >= N_KINDS)
        return HV_ERR_ARG;
    memset(out, 0, HV_FW_JOURNAL_RECORD);
    out[0] = (uint8_t)kind_letter[rec->u.jr.kind];
    hv_exec_journal_kind_t k = rec->u.jr.kind;
    if (k == HV_JR_CUT || k == HV_JR_RELEASE || k == HV_JR_OUTCOME) {
        if (!fits(rec->u.jr.pick, 0xFFFF) || !fits(rec->u.jr.attempt, 0xFF))
            return HV_ERR_ARG;
        out[1] = (uint8_t)rec->u.jr.attempt;
        hv_fw_put_u16(out + 2, (uint32_t)rec->u.jr.pick);
    }
    if (k == HV_JR_OUTCOME) {
        if (!fits(rec->u.jr.outcome, 0xFF) || !fits(rec->u.jr.reason, 0xFF))
            return HV_ERR_ARG;
        out[4] = (uint8_t)rec->u.jr.outcome;
        out[5] = (uint8_t)rec->u.jr.reason;
    }
    if (k == HV_JR_STOP) {
        if (!fits(rec->u.jr.stop, 0xFFFF))
            return HV_ERR_ARG;
        hv_fw_put_u16(out + 2, (uint32_t)rec->u.jr.stop);
    }
    if (k == HV_JR_ESTOP_CLEAR) {
        if (rec->u.jr.nodes > 0xFFu)
            return HV_ERR_ARG;
        out[6] = (uint8_t)rec->u.jr.nodes;
    }
    if (k == HV_JR_HALT) {
        if (!fits(rec->u.jr.reason, 0xFF))
            return HV_ERR_ARG;
        out[5] = (uint8_t)rec->u.jr.reason;
    }
    hv_fw_put_u32(out + 8, t_ms_of(t_s));
    seal(out);
    return HV_OK;
}

hv_status_t hv_fw_journal_decode(const uint8_t in[HV_FW_JOURNAL_RECORD], hv_exec_action_t *rec,
                                 uint32_t *t_ms)
{
    if (!crc_ok(in))
        return HV_ERR_FW_JOURNAL_CORRUPT;
    unsigned k = 0;
    while (k < N_KINDS && (uint8_t)kind_letter[k] != in[0])
        k++;
    if (k == N_KINDS)
        return HV_ERR_FW_JOURNAL_FORMAT; /* a header out of place, or no kind at all */
    memset(rec, 0, sizeof *rec);
    rec->kind = HV_ACT_JOURNAL;
    rec->u.jr.kind = (hv_exec_journal_kind_t)k;
    rec->u.jr.pick = rec->u.jr.stop = -1;
    /* which bytes each kind may use; the rest must be 0 (bit i: byte i of 1..7) */
    unsigned used = 0;
    hv_exec_journal_kind_t kind = rec->u.jr.kind;
    if (kind == HV_JR_CUT || kind == HV_JR_RELEASE || kind == HV_JR_OUTCOME) {
        rec->u.jr.attempt = in[1];
        rec->u.jr.pick = (int)hv_fw_get_u16(in + 2);
        used = 0x0Eu;
    }
    if (kind == HV_JR_OUTCOME) {
        rec->u.jr.outcome = in[4];
        rec->u.jr.reason = in[5];
        used |= 0x30u;
    }
    if (kind == HV_JR_STOP) {
        rec->u.jr.stop = (int)hv_fw_get_u16(in + 2);
        used = 0x0Cu;
    }
    if (kind == HV_JR_ESTOP_CLEAR) {
        rec->u.jr.nodes = in[6];
        used = 0x40u;
    }
    if (kind == HV_JR_HALT) {
        rec->u.jr.reason = in[5];
        used = 0x20u;
    }
    for (unsigned i = 1; i < 8; i++)
        if (!(used & (1u << i)) && in[i] != 0)
            return HV_ERR_FW_JOURNAL_FORMAT;
    if (t_ms)
        *t_ms = hv_fw_get_u32(in + 8);
    return HV_OK;
}

static void header(const hv_exec_plan_t *plan, uint32_t plan_crc, uint8_t out[HV_FW_JOURNAL_RECORD])
{
    memset(out, 0, HV_FW_JOURNAL_RECORD);
    out[0] = K_HEADER;
    out[1] = HV_FW_JOURNAL_VERSION;
    hv_fw_put_u16(out + 2, plan->n_picks);
    hv_fw_put_u16(out + 4, plan->n_stops);
    hv_fw_put_u32(out + 8, plan_crc);
    seal(out);
}

/* Record i: HV_OK and *got (0 past the end, < a record for a torn one), or the store's error. */
static hv_status_t read_record(hv_fw_journal_t *j, uint32_t i, uint8_t buf[HV_FW_JOURNAL_RECORD],
                               uint32_t *got)
{
    *got = 0;
    hv_status_t st =
        j->store->read(j->store->ctx, i * HV_FW_JOURNAL_RECORD, buf, HV_FW_JOURNAL_RECORD, got);
    return st == HV_OK && *got <= HV_FW_JOURNAL_RECORD ? HV_OK : HV_ERR_FW_JOURNAL_IO;
}

/* Record i failed its CRC: torn when nothing follows it (1), damage otherwise (0). */
static hv_status_t is_last(hv_fw_journal_t *j, uint32_t i, int *last)
{
    uint8_t next[HV_FW_JOURNAL_RECORD];
    uint32_t got;
    hv_status_t st = read_record(j, i + 1, next, &got);
    *last = got == 0;
    return st;
}

/* The header (record 0) against the plan; its absence (nothing, or torn) is *fresh = 1. */
static hv_status_t check_header(hv_fw_journal_t *j, const hv_exec_plan_t *plan, uint32_t plan_crc,
                                int *fresh)
{
    uint8_t buf[HV_FW_JOURNAL_RECORD];
    uint32_t got;
    int last = 1;
    hv_status_t st = read_record(j, 0, buf, &got);
    if (st == HV_OK && got == HV_FW_JOURNAL_RECORD && !crc_ok(buf))
        st = is_last(j, 0, &last);
    if (st != HV_OK)
        return st;
    *fresh = got < HV_FW_JOURNAL_RECORD || !crc_ok(buf);
    if (*fresh) {
        j->torn_bytes = got;
        return last ? HV_OK : HV_ERR_FW_JOURNAL_CORRUPT;
    }
    if (buf[0] != K_HEADER || buf[1] != HV_FW_JOURNAL_VERSION || buf[6] != 0 || buf[7] != 0)
        return HV_ERR_FW_JOURNAL_FORMAT;
    if (hv_fw_get_u32(buf + 8) != plan_crc || hv_fw_get_u16(buf + 2) != plan->n_picks ||
        hv_fw_get_u16(buf + 4) != plan->n_stops)
        return HV_ERR_FW_JOURNAL_PLAN;
    return HV_OK;
}

hv_status_t hv_fw_journal_open(hv_fw_journal_t *j, const hv_fw_store_t *store,
                               const hv_exec_plan_t *plan, uint32_t plan_crc,
                               hv_exec_progress_t *progress)
{
    if (!j || !store || !plan || !progress)
        return HV_ERR_ARG;
    memset(j, 0, sizeof *j);
    memset(progress, 0, sizeof *progress);
    j->store = store;
    int fresh = 0;
    hv_status_t st = check_header(j, plan, plan_crc, &fresh);
    if (st == HV_OK && fresh) {
        uint8_t buf[HV_FW_JOURNAL_RECORD];
        header(plan, plan_crc, buf);
        st = store->write(store->ctx, 0, buf, HV_FW_JOURNAL_RECORD) == HV_OK ? HV_OK
                                                                             : HV_ERR_FW_JOURNAL_IO;
    }
    if (st != HV_OK || fresh) {
        j->records = st == HV_OK ? 1u : 0u;
        if (st != HV_OK)
            j->store = NULL;
        return st;
    }
    for (uint32_t i = 1;; i++) {
        uint8_t buf[HV_FW_JOURNAL_RECORD];
        hv_exec_action_t rec;
        uint32_t got;
        int last = 1;
        j->bad_record = i;
        st = read_record(j, i, buf, &got);
        if (st == HV_OK && got == HV_FW_JOURNAL_RECORD && !crc_ok(buf))
            st = is_last(j, i, &last);
        if (st == HV_OK && !last)
            st = HV_ERR_FW_JOURNAL_CORRUPT;
        if (st != HV_OK || got < HV_FW_JOURNAL_RECORD || !crc_ok(buf)) {
            /* the end, a torn last record (it never counted: the next append replaces
             * it), or an error */
            j->torn_bytes = got;
            j->records = i;
            break;
        }
        st = hv_fw_journal_decode(buf, &rec, NULL);
        if (st == HV_OK && hv_exec_progress_apply(progress, plan, &rec) != HV_OK)
            st = HV_ERR_FW_JOURNAL_FORMAT;
        if (st != HV_OK)
            break;
    }
    if (st != HV_OK)
        j->store = NULL;
    else
        j->bad_record = 0;
    return st;
}

hv_status_t hv_fw_journal_append(hv_fw_journal_t *j, const hv_exec_action_t *rec,
                                 hv_exec_real_t t_s)
{
    uint8_t buf[HV_FW_JOURNAL_RECORD];
    if (!j || !j->store)
        return HV_ERR_FW_JOURNAL_IO;
    hv_status_t st = hv_fw_journal_encode(rec, t_s, buf);
    if (st != HV_OK)
        return st;
    if (j->store->write(j->store->ctx, j->records * HV_FW_JOURNAL_RECORD, buf,
                        HV_FW_JOURNAL_RECORD) != HV_OK)
        return HV_ERR_FW_JOURNAL_IO;
    j->records++;
    return HV_OK;
}
