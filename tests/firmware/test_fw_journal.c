/* The firmware's journal (firmware/fw_journal.c) on a store in memory: records read back
 * as written, a replay gives the progress the records mean (the mapping the Linux journal
 * shares, hv/exec_progress.h), a torn last record at every byte offset is ignored and
 * replaced by the next append, damage before the last record and a journal of another plan
 * are refused by name with the store left as it was. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw_journal.h"
#include "fw_status.h"
#include "hv/cost_table.h" /* hv_crc32 */

#define STORE_MAX 1024u
#define PLAN_CRC  0x5eed1234u

typedef struct mem_store {
    uint8_t bytes[STORE_MAX];
    uint32_t len;   /* bytes written so far */
    int fail_write; /* 1: every write fails */
    unsigned writes;
} mem_store_t;

static hv_status_t mem_read(void *ctx, uint32_t offset, uint8_t *buf, uint32_t n, uint32_t *got)
{
    mem_store_t *m = ctx;
    uint32_t have = offset < m->len ? m->len - offset : 0u;
    *got = have < n ? have : n;
    memcpy(buf, m->bytes + offset, *got);
    return HV_OK;
}

static hv_status_t mem_write(void *ctx, uint32_t offset, const uint8_t *buf, uint32_t n)
{
    mem_store_t *m = ctx;
    if (m->fail_write || offset + n > STORE_MAX)
        return HV_ERR_FW_JOURNAL_IO;
    memcpy(m->bytes + offset, buf, n);
    if (offset + n > m->len)
        m->len = offset + n;
    m->writes++;
    return HV_OK;
}

typedef struct fixture {
    hv_exec_plan_t plan; /* 4 picks at 2 stops; large on the host: allocated */
    mem_store_t mem;
    hv_fw_store_t store;
    hv_fw_journal_t j;
    hv_exec_progress_t prog, want;
} fixture_t;

static int setup(void **state)
{
    fixture_t *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    f->plan.n_stops = 2;
    f->plan.n_picks = 4;
    f->store = (hv_fw_store_t){&f->mem, mem_read, mem_write};
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    free(*state);
    return 0;
}

static hv_exec_action_t jr(hv_exec_journal_kind_t kind, int pick, int stop, int outcome, int reason)
{
    hv_exec_action_t a;
    memset(&a, 0, sizeof a);
    a.kind = HV_ACT_JOURNAL;
    a.u.jr.kind = kind;
    a.u.jr.pick = pick;
    a.u.jr.stop = stop;
    a.u.jr.attempt = 1;
    a.u.jr.outcome = outcome;
    a.u.jr.reason = reason;
    return a;
}

/* a row cut short: stop 0 done (pick 0 picked, pick 1 failed), a controlled stop and the
 * restart, stop 1 reached, pick 2's cut issued; the e-stop clear of two nodes before it all */
#define N_ROW 10
static void row_records(hv_exec_action_t r[N_ROW])
{
    r[0] = jr(HV_JR_ESTOP_CLEAR, -1, -1, 0, 0);
    r[0].u.jr.nodes = (1u << HV_EXEC_VEHICLE) | (1u << HV_EXEC_RIGHT);
    r[1] = jr(HV_JR_STOP, -1, 0, 0, 0);
    r[2] = jr(HV_JR_CUT, 0, -1, 0, 0);
    r[3] = jr(HV_JR_RELEASE, 0, -1, 0, 0);
    r[4] = jr(HV_JR_OUTCOME, 0, -1, HV_OUT_PICKED, HV_RSN_OK);
    r[5] = jr(HV_JR_OUTCOME, 1, -1, HV_OUT_FAILED, HV_RSN_TIMEOUT);
    r[6] = jr(HV_JR_HALT, -1, -1, 0, HV_STOP_OPERATOR);
    r[7] = jr(HV_JR_STOP, -1, 1, 0, 0);
    r[8] = jr(HV_JR_CUT, 3, -1, 0, 0);
    r[9] = jr(HV_JR_CUT, 2, -1, 0, 0);
}

/* a fresh journal holding the first n records of the row */
static void write_row(fixture_t *f, unsigned n)
{
    hv_exec_action_t r[N_ROW];
    row_records(r);
    memset(&f->mem, 0, sizeof f->mem);
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog), HV_OK);
    for (unsigned i = 0; i < n; i++)
        assert_int_equal(hv_fw_journal_append(&f->j, &r[i], 1.5 * i), HV_OK);
    assert_int_equal(f->mem.len, (n + 1) * HV_FW_JOURNAL_RECORD);
}

static void test_records_read_back_as_written(void **state)
{
    (void)state;
    hv_exec_action_t r[N_ROW];
    row_records(r);
    for (unsigned i = 0; i < N_ROW; i++) {
        uint8_t buf[HV_FW_JOURNAL_RECORD];
        hv_exec_action_t got;
        uint32_t t_ms = 0;
        assert_int_equal(hv_fw_journal_encode(&r[i], 2.0 + i, buf), HV_OK);
        assert_int_equal(hv_fw_journal_decode(buf, &got, &t_ms), HV_OK);
        assert_int_equal(got.kind, HV_ACT_JOURNAL);
        assert_int_equal(got.u.jr.kind, r[i].u.jr.kind);
        assert_int_equal(t_ms, 1000u * (2u + i));
        if (r[i].u.jr.kind == HV_JR_STOP)
            assert_int_equal(got.u.jr.stop, r[i].u.jr.stop);
        if (r[i].u.jr.kind >= HV_JR_CUT && r[i].u.jr.kind <= HV_JR_OUTCOME) {
            assert_int_equal(got.u.jr.pick, r[i].u.jr.pick);
            assert_int_equal(got.u.jr.attempt, r[i].u.jr.attempt);
        }
        if (r[i].u.jr.kind == HV_JR_OUTCOME) {
            assert_int_equal(got.u.jr.outcome, r[i].u.jr.outcome);
            assert_int_equal(got.u.jr.reason, r[i].u.jr.reason);
        }
        assert_int_equal(got.u.jr.nodes, r[i].u.jr.nodes);
    }
    /* a field beyond its width has no encoding */
    hv_exec_action_t wide = jr(HV_JR_CUT, 70000, -1, 0, 0);
    uint8_t buf[HV_FW_JOURNAL_RECORD];
    assert_int_equal(hv_fw_journal_encode(&wide, 0.0, buf), HV_ERR_ARG);
}

static void test_replay_gives_the_progress_of_the_records(void **state)
{
    fixture_t *f = *state;
    write_row(f, N_ROW);
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog), HV_OK);
    assert_int_equal(f->j.records, N_ROW + 1);
    assert_int_equal(f->j.torn_bytes, 0);
    assert_int_equal(f->prog.estop_clears, 1);
    assert_int_equal(f->prog.stop_reached[0], 1);
    assert_int_equal(f->prog.stop_reached[1], 1);
    assert_int_equal(f->prog.pick[0], HV_PROG_DONE);
    assert_int_equal(f->prog.outcome[0], HV_OUT_PICKED);
    assert_int_equal(f->prog.pick[1], HV_PROG_DONE);
    assert_int_equal(f->prog.outcome[1], HV_OUT_FAILED);
    assert_int_equal(f->prog.reason[1], HV_RSN_TIMEOUT);
    assert_int_equal(f->prog.pick[2], HV_PROG_CUT);
    assert_int_equal(f->prog.pick[3], HV_PROG_CUT);
    assert_int_equal(f->prog.row_done, 0);
    /* a fresh store gets the header only */
    memset(&f->mem, 0, sizeof f->mem);
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog), HV_OK);
    assert_int_equal(f->j.records, 1);
    assert_int_equal(f->mem.len, HV_FW_JOURNAL_RECORD);
}

/* The last record torn at every byte offset, and whole but garbled: the replay is that of
 * the records before it, and appending the record again gives the whole journal's. */
static void test_torn_last_record_is_ignored_and_replaced(void **state)
{
    fixture_t *f = *state;
    hv_exec_action_t r[N_ROW];
    row_records(r);
    write_row(f, N_ROW - 1);
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->want), HV_OK);
    write_row(f, N_ROW);
    mem_store_t whole = f->mem;
    hv_exec_progress_t whole_prog;
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &whole_prog), HV_OK);
    for (uint32_t cut = 0; cut <= HV_FW_JOURNAL_RECORD; cut++) {
        f->mem = whole;
        f->mem.len = N_ROW * HV_FW_JOURNAL_RECORD + cut;
        if (cut == HV_FW_JOURNAL_RECORD) /* all bytes there, one of them wrong */
            f->mem.bytes[N_ROW * HV_FW_JOURNAL_RECORD + 3] ^= 0x40u;
        assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog), HV_OK);
        assert_int_equal(f->j.records, N_ROW);
        assert_int_equal(f->j.torn_bytes, cut);
        assert_memory_equal(&f->prog, &f->want, sizeof f->prog);
        assert_int_equal(hv_fw_journal_append(&f->j, &r[N_ROW - 1], 1.5 * (N_ROW - 1)), HV_OK);
        assert_int_equal(f->mem.len, whole.len);
        assert_memory_equal(f->mem.bytes, whole.bytes, whole.len);
        assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog), HV_OK);
        assert_memory_equal(&f->prog, &whole_prog, sizeof f->prog);
    }
    /* a header torn at every offset: a fresh journal */
    for (uint32_t cut = 1; cut < HV_FW_JOURNAL_RECORD; cut++) {
        f->mem = whole;
        f->mem.len = cut;
        assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog), HV_OK);
        assert_int_equal(f->j.records, 1);
        assert_int_equal(f->prog.pick[0], HV_PROG_PENDING);
        assert_int_equal(f->mem.len, HV_FW_JOURNAL_RECORD);
    }
}

/* A bad CRC before the last record is damage, not a torn write: every bit of every byte
 * of the records before the last, each refused naming the record, the store untouched. */
static void test_damage_before_the_last_record_is_refused(void **state)
{
    fixture_t *f = *state;
    write_row(f, N_ROW);
    mem_store_t whole = f->mem;
    for (uint32_t rec = 0; rec < N_ROW; rec++)
        for (uint32_t b = 0; b < HV_FW_JOURNAL_RECORD; b++)
            for (unsigned bit = 0; bit < 8; bit++) {
                f->mem = whole;
                f->mem.bytes[rec * HV_FW_JOURNAL_RECORD + b] ^= (uint8_t)(1u << bit);
                assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog),
                                 HV_ERR_FW_JOURNAL_CORRUPT);
                assert_int_equal(f->j.bad_record, rec);
                assert_int_equal(f->mem.writes, whole.writes);
                assert_int_equal(f->mem.len, whole.len);
                /* and nothing can be appended to a journal that did not open */
                hv_exec_action_t d = jr(HV_JR_DONE, -1, -1, 0, 0);
                assert_int_equal(hv_fw_journal_append(&f->j, &d, 0.0), HV_ERR_FW_JOURNAL_IO);
            }
}

static void test_journal_of_another_plan_is_refused(void **state)
{
    fixture_t *f = *state;
    write_row(f, 3);
    mem_store_t before = f->mem;
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC ^ 1u, &f->prog),
                     HV_ERR_FW_JOURNAL_PLAN);
    assert_int_equal(f->j.bad_record, 0);
    f->plan.n_picks = 5; /* the same image CRC, other counts */
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog),
                     HV_ERR_FW_JOURNAL_PLAN);
    f->plan.n_picks = 4;
    assert_memory_equal(&f->mem, &before, sizeof before);
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog), HV_OK);
}

/* A record whose CRC is good but whose content the plan cannot have. */
static void put_record(fixture_t *f, uint32_t index, const hv_exec_action_t *a)
{
    uint8_t buf[HV_FW_JOURNAL_RECORD];
    assert_int_equal(hv_fw_journal_encode(a, 0.0, buf), HV_OK);
    assert_int_equal(mem_write(&f->mem, index * HV_FW_JOURNAL_RECORD, buf, sizeof buf), HV_OK);
}

static void test_records_the_plan_cannot_have_are_refused(void **state)
{
    fixture_t *f = *state;
    const hv_exec_action_t bad[] = {
        jr(HV_JR_CUT, 4, -1, 0, 0),                            /* a pick beyond the plan's */
        jr(HV_JR_STOP, -1, 2, 0, 0),                           /* a stop beyond the plan's */
        jr(HV_JR_OUTCOME, 0, -1, HV_OUT_PICKED, HV_RSN_OK),    /* pick 0's second outcome */
        jr(HV_JR_OUTCOME, 2, -1, HV_OUT_COUNT, HV_RSN_OK),     /* no such outcome */
        jr(HV_JR_OUTCOME, 2, -1, HV_OUT_FAILED, HV_RSN_COUNT), /* no such reason */
        jr(HV_JR_ESTOP_CLEAR, -1, -1, 0, 0),                   /* a clear of no node */
    };
    for (unsigned k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        write_row(f, 5);
        put_record(f, 6, &bad[k]);
        assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog),
                         HV_ERR_FW_JOURNAL_FORMAT);
        assert_int_equal(f->j.bad_record, 6);
    }
    /* a header where a record belongs, and a field that must be 0 */
    write_row(f, 2);
    memcpy(f->mem.bytes + 3 * HV_FW_JOURNAL_RECORD, f->mem.bytes, HV_FW_JOURNAL_RECORD);
    f->mem.len += HV_FW_JOURNAL_RECORD;
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog),
                     HV_ERR_FW_JOURNAL_FORMAT);
    uint8_t buf[HV_FW_JOURNAL_RECORD];
    hv_exec_action_t d = jr(HV_JR_DONE, -1, -1, 0, 0), got;
    assert_int_equal(hv_fw_journal_encode(&d, 0.0, buf), HV_OK);
    buf[2] = 1; /* a row-done record has no pick: the byte must be 0 */
    uint32_t crc = hv_crc32(0, buf, 12);
    for (unsigned i = 0; i < 4; i++)
        buf[12 + i] = (uint8_t)(crc >> (8u * i));
    assert_int_equal(hv_fw_journal_decode(buf, &got, NULL), HV_ERR_FW_JOURNAL_FORMAT);
    buf[12] ^= 1u; /* and a CRC that does not match is damage */
    assert_int_equal(hv_fw_journal_decode(buf, &got, NULL), HV_ERR_FW_JOURNAL_CORRUPT);
}

static void test_a_failing_store_is_named(void **state)
{
    fixture_t *f = *state;
    memset(&f->mem, 0, sizeof f->mem);
    f->mem.fail_write = 1;
    assert_int_equal(hv_fw_journal_open(&f->j, &f->store, &f->plan, PLAN_CRC, &f->prog),
                     HV_ERR_FW_JOURNAL_IO);
    write_row(f, 2);
    f->mem.fail_write = 1;
    hv_exec_action_t d = jr(HV_JR_DONE, -1, -1, 0, 0);
    assert_int_equal(hv_fw_journal_append(&f->j, &d, 0.0), HV_ERR_FW_JOURNAL_IO);
    assert_int_equal(f->j.records, 3); /* what failed was not counted */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_records_read_back_as_written),
        cmocka_unit_test_setup_teardown(test_replay_gives_the_progress_of_the_records, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_torn_last_record_is_ignored_and_replaced, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_damage_before_the_last_record_is_refused, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_journal_of_another_plan_is_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_records_the_plan_cannot_have_are_refused, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_a_failing_store_is_named, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
