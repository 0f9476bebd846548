/* The harvest journal: write, replay, torn and corrupt records, another plan's journal,
 * and a run interrupted mid-row then resumed from its journal (state machine + journal). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "exec_fixture.h"
#include "hv/cost_table.h" /* hv_crc32 */
#include "hv/exec_journal.h"
#include "hv/exec_status.h"

static char dir[64];

static int setup(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/hv_journal_XXXXXX");
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

static void path_of(char *out, size_t n, const char *name)
{
    int k = snprintf(out, n, "%s/%s", dir, name);
    assert_true(k > 0 && (size_t)k < n);
}

static void append_raw(const char *path, const char *bytes)
{
    FILE *f = fopen(path, "ab");
    assert_non_null(f);
    fputs(bytes, f);
    fclose(f);
}

static void test_write_replay(void **state)
{
    (void)state;
    fx_t *fx = malloc(sizeof *fx);
    fx_plan(fx, 2, 2);
    char path[128], err[256];
    path_of(path, sizeof path, "a.journal");
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(j.records, 1); /* the header */
    assert_int_equal(hv_exec_journal_stop(&j, 0, 1.0), HV_OK);
    assert_int_equal(hv_exec_journal_cut(&j, 0, 1, 2.0), HV_OK);
    assert_int_equal(hv_exec_journal_release(&j, 0, 1, 3.0), HV_OK);
    assert_int_equal(hv_exec_journal_outcome(&j, 0, HV_OUT_PICKED, HV_RSN_OK, 1, 4.0), HV_OK);
    assert_int_equal(hv_exec_journal_cut(&j, 2, 2, 5.0), HV_OK);
    assert_int_equal(hv_exec_journal_outcome(&j, 3, HV_OUT_SKIPPED, HV_RSN_REJECTED, 3, 6.0),
                     HV_OK);
    assert_int_equal(hv_exec_journal_outcome(&j, 99, HV_OUT_PICKED, HV_RSN_OK, 1, 4.0), HV_ERR_ARG);
    hv_exec_journal_close(&j);

    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(j.records, 7);
    assert_int_equal(prog.stop_reached[0], 1);
    assert_int_equal(prog.stop_reached[1], 0);
    assert_int_equal(prog.pick[0], HV_PROG_DONE);
    assert_int_equal(prog.outcome[0], HV_OUT_PICKED);
    assert_int_equal(prog.pick[1], HV_PROG_PENDING);
    assert_int_equal(prog.pick[2], HV_PROG_CUT);
    assert_int_equal(prog.pick[3], HV_PROG_DONE);
    assert_int_equal(prog.outcome[3], HV_OUT_SKIPPED);
    assert_int_equal(prog.reason[3], HV_RSN_REJECTED);
    assert_int_equal(prog.row_done, 0);
    assert_int_equal(hv_exec_journal_done(&j, 9.0), HV_OK);
    hv_exec_journal_close(&j);
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(prog.row_done, 1);
    hv_exec_journal_close(&j);
    free(fx);
}

/* A new journal `name` of a one-stop plan whose first fruit is picked; still open. */
static fx_t *one_picked(const char *name, char *path, size_t n, hv_exec_journal_t *j)
{
    fx_t *fx = malloc(sizeof *fx);
    assert_non_null(fx);
    fx_plan(fx, 1, 2);
    path_of(path, n, name);
    char err[256];
    hv_exec_progress_t prog;
    assert_int_equal(hv_exec_journal_open(j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(hv_exec_journal_outcome(j, 0, HV_OUT_PICKED, HV_RSN_OK, 1, 1.0), HV_OK);
    return fx;
}

static void test_torn_and_corrupt(void **state)
{
    (void)state;
    char path[128], err[256];
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    fx_t *fx = one_picked("b.journal", path, sizeof path, &j);
    hv_exec_journal_close(&j);
    /* a crash in the middle of a write leaves a line without its newline */
    append_raw(path, "F L L0_1 pick");
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(j.torn_bytes, strlen("F L L0_1 pick"));
    assert_int_equal(prog.pick[1], HV_PROG_PENDING);
    assert_int_equal(hv_exec_journal_outcome(&j, 1, HV_OUT_FAILED, HV_RSN_TIMEOUT, 3, 2.0), HV_OK);
    hv_exec_journal_close(&j);
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(j.torn_bytes, 0);
    assert_int_equal(prog.outcome[1], HV_OUT_FAILED);
    assert_int_equal(prog.reason[1], HV_RSN_TIMEOUT);
    hv_exec_journal_close(&j);

    /* a complete line whose text does not match its checksum: refuse, name the line */
    append_raw(path, "F R R0_0 picked ok a=1 t=3.000 *00000000\n");
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_FORMAT);
    assert_non_null(strstr(err, "line 4"));
    assert_non_null(strstr(err, path));
    free(fx);
}

static void test_other_plan(void **state)
{
    (void)state;
    fx_t *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    fx_plan(a, 1, 2);
    fx_plan(b, 1, 2);
    snprintf(b->plan.picks[1].id, sizeof b->plan.picks[1].id, "other");
    assert_int_not_equal(hv_exec_plan_hash(&a->plan), hv_exec_plan_hash(&b->plan));
    char path[128], err[256];
    path_of(path, sizeof path, "c.journal");
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    assert_int_equal(hv_exec_journal_open(&j, path, &a->plan, &prog, err, sizeof err), HV_OK);
    hv_exec_journal_close(&j);
    assert_int_equal(hv_exec_journal_open(&j, path, &b->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_PLAN);
    assert_non_null(strstr(err, "another plan"));
    /* not a journal at all */
    path_of(path, sizeof path, "d.journal");
    append_raw(path, "hello\n");
    assert_int_equal(hv_exec_journal_open(&j, path, &a->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_FORMAT);
    /* unwritable place */
    assert_int_equal(
        hv_exec_journal_open(&j, "/nonexistent/dir/j", &a->plan, &prog, err, sizeof err),
        HV_ERR_EXEC_JOURNAL_IO);
    free(a);
    free(b);
}

/* A complete line with its checksum, as the executor writes it. */
static void append_record(const char *path, const char *text)
{
    char line[256];
    snprintf(line, sizeof line, "%s *%08x\n", text, (unsigned)hv_crc32(0, text, strlen(text)));
    append_raw(path, line);
}

static void test_estop_clear_record(void **state)
{
    (void)state;
    char path[128], err[256];
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    fx_t *fx = one_picked("e.journal", path, sizeof path, &j);
    unsigned two = (1u << HV_EXEC_VEHICLE) | (1u << HV_EXEC_RIGHT);
    assert_int_equal(hv_exec_journal_estop_clear(&j, "a.n-other_2", two, 2.5), HV_OK);
    /* what cannot stand in a record: refused before anything is written */
    const char *bad_names[] = {"", "two words", "x\n", "a*b", "0123456789012345678901234567890123"};
    for (size_t k = 0; k < sizeof bad_names / sizeof bad_names[0]; k++)
        assert_int_equal(hv_exec_journal_estop_clear(&j, bad_names[k], two, 3.0), HV_ERR_ARG);
    assert_int_equal(hv_exec_journal_estop_clear(&j, NULL, two, 3.0), HV_ERR_ARG);
    assert_int_equal(hv_exec_journal_estop_clear(&j, "ann", 0, 3.0), HV_ERR_ARG);
    assert_int_equal(hv_exec_journal_estop_clear(&j, "ann", 1u << HV_EXEC_NODES, 3.0), HV_ERR_ARG);
    hv_exec_journal_close(&j);

    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char text[1024];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    assert_non_null(strstr(text, "\nE a.n-other_2 nodes=vehicle,right_arm t=2.500 *"));
    assert_null(strstr(text, "ann")); /* nothing of the refused calls was written */

    /* replayed: the clear counted, the fruits' progress as before */
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(prog.estop_clears, 1);
    assert_int_equal(prog.pick[0], HV_PROG_DONE);
    assert_int_equal(prog.pick[1], HV_PROG_PENDING);
    hv_exec_journal_close(&j);

    /* a torn E record is cut off like any other */
    append_raw(path, "E ann nodes=left_a");
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(j.torn_bytes, strlen("E ann nodes=left_a"));
    assert_int_equal(prog.estop_clears, 1);
    hv_exec_journal_close(&j);

    /* complete E lines with a good checksum but a bad field: refused, the line named */
    const char *bad_lines[] = {"E ann nodes=left_arm,left_arm t=1.000", "E ann nodes=arm t=1.000",
                               "E a*b nodes=vehicle t=1.000", "E ann nodes= t=1.000",
                               "E ann nodes=vehicle t=1.000 extra"};
    for (size_t k = 0; k < sizeof bad_lines / sizeof bad_lines[0]; k++) {
        char bad[128];
        snprintf(bad, sizeof bad, "bad%zu.journal", k);
        char bpath[160];
        path_of(bpath, sizeof bpath, bad);
        assert_int_equal(hv_exec_journal_open(&j, bpath, &fx->plan, &prog, err, sizeof err), HV_OK);
        hv_exec_journal_close(&j);
        append_record(bpath, bad_lines[k]);
        assert_int_equal(hv_exec_journal_open(&j, bpath, &fx->plan, &prog, err, sizeof err),
                         HV_ERR_EXEC_JOURNAL_FORMAT);
        assert_non_null(strstr(err, "line 2"));
        assert_non_null(strstr(err, "e-stop clear"));
    }
    free(fx);
}

/* A controlled stop's record: written with its reason, replayed as nothing to undo; a bad
 * reason is refused when written and when read. */
static void test_halt_record(void **state)
{
    (void)state;
    char path[160], err[256];
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    fx_t *fx = one_picked("h.journal", path, sizeof path, &j);
    assert_int_equal(hv_exec_journal_halt(&j, HV_STOP_OPERATOR, 4.25), HV_OK);
    assert_int_equal(hv_exec_journal_halt(&j, HV_STOP_NONE, 5.0), HV_ERR_ARG);
    assert_int_equal(hv_exec_journal_halt(&j, HV_STOP_COUNT, 5.0), HV_ERR_ARG);
    hv_exec_journal_close(&j);
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(prog.pick[0], HV_PROG_DONE);
    assert_int_equal(prog.row_done, 0);
    hv_exec_journal_close(&j);
    append_record(path, "H plan_timeout t=9.000");
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    hv_exec_journal_close(&j);
    append_record(path, "H tired t=9.500");
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_FORMAT);
    assert_non_null(strstr(err, "halt"));
    free(fx);
}

/* Carry out the journal actions of a fake run into a real journal. */
static void write_journal(const fx_t *fx, hv_exec_journal_t *j, int upto)
{
    for (int i = 0; i < upto; i++) {
        const hv_exec_action_t *a = &fx->log[i].a;
        if (a->kind != HV_ACT_JOURNAL)
            continue;
        hv_status_t st = HV_OK;
        switch (a->u.jr.kind) {
        case HV_JR_STOP: st = hv_exec_journal_stop(j, a->u.jr.stop, 0.0); break;
        case HV_JR_CUT: st = hv_exec_journal_cut(j, a->u.jr.pick, a->u.jr.attempt, 0.0); break;
        case HV_JR_RELEASE:
            st = hv_exec_journal_release(j, a->u.jr.pick, a->u.jr.attempt, 0.0);
            break;
        case HV_JR_OUTCOME:
            st = hv_exec_journal_outcome(j, a->u.jr.pick, a->u.jr.outcome, a->u.jr.reason,
                                         a->u.jr.attempt, 0.0);
            break;
        case HV_JR_DONE: st = hv_exec_journal_done(j, 0.0); break;
        case HV_JR_ESTOP_CLEAR:
            st = hv_exec_journal_estop_clear(j, "test", a->u.jr.nodes, 0.0);
            break;
        case HV_JR_HALT: st = hv_exec_journal_halt(j, a->u.jr.reason, 0.0); break;
        }
        assert_int_equal(st, HV_OK);
    }
}

/* Interrupt a run at many points (the log index where the "kill" happens), resume from the
 * journal with the same nodes, and check: every fruit ends with exactly one outcome and
 * no fruit is cut twice. */
static void test_kill_and_resume(void **state)
{
    (void)state;
    fx_t *full = malloc(sizeof *full);
    fx_plan(full, 2, 2);
    fx_start(full, NULL);
    fx_run(full, 30.0);
    assert_int_equal(full->sm.phase, HV_PH_ROW_DONE);
    int total = full->nlog;
    free(full);

    for (int cut_at = 5; cut_at < total; cut_at += 7) {
        fx_t *fx = malloc(sizeof *fx);
        fx_plan(fx, 2, 2);
        fx_start(fx, NULL);
        fx_run(fx, 30.0);
        char path[128], err[256];
        snprintf(path, sizeof path, "%s/k%d.journal", dir, cut_at);
        hv_exec_journal_t j;
        hv_exec_progress_t prog;
        assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
        write_journal(fx, &j, cut_at);
        hv_exec_journal_close(&j);
        /* what the fake nodes did up to the kill */
        int cuts[2][HV_EXEC_MAX_PICKS];
        memset(cuts, 0, sizeof cuts);
        int held[2] = {0, 0}, cur[2] = {-1, -1};
        for (int i = 0; i < cut_at; i++) {
            const hv_exec_action_t *a = &fx->log[i].a;
            if (a->kind == HV_ACT_FRUIT_EVENT && a->u.fe.kind == HV_FE_APPROACH)
                cur[fx->plan.picks[a->u.fe.pick].side] = a->u.fe.pick;
            if (a->kind == HV_ACT_EE) {
                int side = a->node == HV_EXEC_LEFT ? 0 : 1;
                if (a->u.ee.action == HV_CAN_EE_ACTION_CUT) {
                    cuts[side][cur[side]]++; /* the fake cuts every cut it is sent */
                    held[side] = 1;
                } else {
                    held[side] = 0;
                }
            }
        }
        /* restart: a new executor with the journal, the nodes as the kill left them */
        fx_t *re = malloc(sizeof *re);
        fx_plan(re, 2, 2);
        assert_int_equal(hv_exec_journal_open(&j, path, &re->plan, &prog, err, sizeof err), HV_OK);
        fx_start(re, &prog);
        re->node[HV_EXEC_LEFT].held = held[0];
        re->node[HV_EXEC_RIGHT].held = held[1];
        fx_run(re, 60.0);
        assert_int_equal(re->sm.phase, HV_PH_ROW_DONE);
        write_journal(re, &j, re->nlog);
        hv_exec_journal_close(&j);
        assert_int_equal(hv_exec_journal_open(&j, path, &re->plan, &prog, err, sizeof err), HV_OK);
        hv_exec_journal_close(&j);
        for (int p = 0; p < re->plan.n_picks; p++) {
            int side = re->plan.picks[p].side;
            assert_int_equal(prog.pick[p], HV_PROG_DONE);
            assert_int_equal(prog.outcome[p], HV_OUT_PICKED);
            assert_true(cuts[side][p] + re->cuts_done[side][p] == 1);
        }
        assert_int_equal(prog.row_done, 1);
        free(fx);
        free(re);
    }
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

/* A plan built in memory (not read from a file) may hold ids the journal could not read
 * back: such a record is refused and nothing is written, so the journal still replays. */
static void test_unreadable_ids_never_written(void **state)
{
    (void)state;
    fx_t *fx = malloc(sizeof *fx);
    fx_plan(fx, 1, 3);
    static const char *const bad[] = {"a\nb", "a b", "L0_1 *0"};
    for (int k = 0; k < 3; ++k) {
        snprintf(fx->plan.picks[k].id, sizeof fx->plan.picks[k].id, "%s", bad[k]);
    }
    char path[128], err[256];
    path_of(path, sizeof path, "ids.journal");
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    long header = file_size(path);
    for (int k = 0; k < 3; ++k) {
        assert_int_equal(hv_exec_journal_cut(&j, k, 1, 1.0), HV_ERR_EXEC_JOURNAL_ID);
        assert_int_equal(hv_exec_journal_release(&j, k, 1, 2.0), HV_ERR_EXEC_JOURNAL_ID);
        assert_int_equal(hv_exec_journal_outcome(&j, k, HV_OUT_PICKED, HV_RSN_OK, 1, 3.0),
                         HV_ERR_EXEC_JOURNAL_ID);
    }
    assert_int_equal(file_size(path), header);
    assert_int_equal(j.records, 1);
    /* a valid id of the same plan is journalled, and the whole journal replays */
    assert_int_equal(hv_exec_journal_outcome(&j, 3, HV_OUT_PICKED, HV_RSN_OK, 1, 4.0), HV_OK);
    hv_exec_journal_close(&j);
    assert_int_equal(hv_exec_journal_open(&j, path, &fx->plan, &prog, err, sizeof err), HV_OK);
    assert_int_equal(j.records, 2);
    assert_int_equal(prog.pick[3], HV_PROG_DONE);
    assert_int_equal(prog.pick[0], HV_PROG_PENDING);
    hv_exec_journal_close(&j);
    free(fx);
}

/* ---- online: the committed stops in the journal ---------------------------------- */

/* An online start's plan: empty, no course (what harvest-exec has before a message). */
static void empty_plan(fx_t *fx)
{
    fx->plan.n_stops = 0;
    fx->plan.n_picks = 0;
    fx->plan.row_start_m = fx->plan.row_length_m = fx->plan.stop_margin_m = 0.0;
}

/* The planner's course and stop s of src, as the feed appends them. */
static void grow(fx_t *fx, const fx_t *src, int s)
{
    fx->plan.row_start_m = src->plan.row_start_m;
    fx->plan.row_length_m = src->plan.row_length_m;
    fx->plan.stop_margin_m = src->plan.stop_margin_m;
    assert_int_equal(fx_append_stop(fx, &src->plan, s), HV_OK);
}

static void assert_same_stops(const hv_exec_plan_t *a, const hv_exec_plan_t *b, int n)
{
    assert_int_equal(a->n_stops, n);
    assert_true(a->row_start_m == b->row_start_m && a->row_length_m == b->row_length_m &&
                a->stop_margin_m == b->stop_margin_m);
    for (int s = 0; s < n; s++) {
        const hv_exec_stop_t *x = &a->stops[s], *y = &b->stops[s];
        assert_int_equal(x->plan_index, y->plan_index);
        assert_true(x->y_m == y->y_m); /* 17 digits: the same double */
        for (int side = 0; side < 2; side++) {
            assert_int_equal(x->count[side], y->count[side]);
            for (unsigned k = 0; k < x->count[side]; k++) {
                const hv_exec_pick_t *p = &a->picks[x->first[side] + k];
                const hv_exec_pick_t *q = &b->picks[y->first[side] + k];
                assert_string_equal(p->id, q->id);
                assert_int_equal(p->side, q->side);
                assert_true(p->x_m == q->x_m && p->y_m == q->y_m && p->z_m == q->z_m &&
                            p->yaw_rad == q->yaw_rad && p->cost_s == q->cost_s);
            }
        }
    }
}

/* The file's text (at most cap - 1 bytes), NUL-terminated; its length. */
static size_t read_text(const char *path, char *text, size_t cap)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    size_t n = fread(text, 1, cap - 1, f);
    fclose(f);
    text[n] = '\0';
    return n;
}

static void truncate_by(const char *path, long bytes)
{
    assert_int_equal(truncate(path, file_size(path) - bytes), 0);
}

/* Stops written before they are acted on read back as the same plan; outcomes replay onto
 * it; a stop whose pick records a crash cut short is dropped whole, a torn line too. */
static void test_online_stops_rebuilt(void **state)
{
    (void)state;
    fx_t *src = malloc(sizeof *src), *fx = malloc(sizeof *fx), *re = malloc(sizeof *re);
    assert_true(src && fx && re);
    fx_plan(src, 3, 2);
    fx_plan(fx, 3, 2);
    fx_plan(re, 3, 2);
    empty_plan(fx);
    char path[128], err[256];
    path_of(path, sizeof path, "online.journal");
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    assert_int_equal(hv_exec_journal_open_online(&j, path, &fx->plan, &prog, err, sizeof err),
                     HV_OK);
    assert_int_equal(hv_exec_journal_stops(&j), HV_OK); /* nothing yet: nothing written */
    assert_int_equal(j.records, 1);
    grow(fx, src, 0);
    grow(fx, src, 1);
    assert_int_equal(hv_exec_journal_stops(&j), HV_OK);
    assert_int_equal(j.records, 1 + 1 + 2 * 5); /* course, 2 x (stop + 4 picks) */
    assert_int_equal(hv_exec_journal_stop(&j, 0, 1.0), HV_OK);
    assert_int_equal(hv_exec_journal_outcome(&j, 0, HV_OUT_PICKED, HV_RSN_OK, 1, 2.0), HV_OK);
    assert_int_equal(hv_exec_journal_cut(&j, 1, 1, 3.0), HV_OK);
    grow(fx, src, 2);
    assert_int_equal(hv_exec_journal_stops(&j), HV_OK);
    hv_exec_journal_close(&j);

    /* a restart: the plan rebuilt, the progress on it */
    empty_plan(re);
    assert_int_equal(hv_exec_journal_open_online(&j, path, &re->plan, &prog, err, sizeof err),
                     HV_OK);
    assert_same_stops(&re->plan, &fx->plan, 3);
    assert_int_equal(j.stops_journalled, 3);
    assert_int_equal(prog.stop_reached[0], 1);
    assert_int_equal(prog.pick[0], HV_PROG_DONE);
    assert_int_equal(prog.pick[1], HV_PROG_CUT);
    assert_int_equal(prog.pick[4], HV_PROG_PENDING);
    hv_exec_journal_close(&j);

    /* the last stop's last pick record lost in a crash: that stop was never acted on */
    char text[4096];
    size_t n = read_text(path, text, sizeof text);
    const char *last_q = strrchr(text, 'Q');
    assert_non_null(last_q);
    long q_bytes = (long)(text + n - last_q);
    truncate_by(path, q_bytes);
    empty_plan(re);
    assert_int_equal(hv_exec_journal_open_online(&j, path, &re->plan, &prog, err, sizeof err),
                     HV_OK);
    assert_same_stops(&re->plan, &fx->plan, 2);
    assert_true(j.torn_bytes > (unsigned)q_bytes); /* its P and other Q records too */
    /* written again when the planner's next message brings it */
    assert_int_equal(fx_append_stop(re, &src->plan, 2), HV_OK);
    assert_int_equal(hv_exec_journal_stops(&j), HV_OK);
    hv_exec_journal_close(&j);
    /* a torn line (no newline) inside a stop's records: the same */
    truncate_by(path, 5);
    empty_plan(re);
    assert_int_equal(hv_exec_journal_open_online(&j, path, &re->plan, &prog, err, sizeof err),
                     HV_OK);
    assert_same_stops(&re->plan, &fx->plan, 2);
    hv_exec_journal_close(&j);
    free(src);
    free(fx);
    free(re);
}

/* Corrupt or misplaced online records are refused with the line named; an online journal
 * is no plan file's, and the other way round. */
static void test_online_records_refused(void **state)
{
    (void)state;
    fx_t *fx = malloc(sizeof *fx), *src = malloc(sizeof *src);
    assert_true(fx && src);
    fx_plan(src, 2, 1);
    fx_plan(fx, 2, 1);
    empty_plan(fx);
    char path[128], err[256];
    path_of(path, sizeof path, "bad-online.journal");
    hv_exec_journal_t j;
    hv_exec_progress_t prog;
    assert_int_equal(hv_exec_journal_open_online(&j, path, &fx->plan, &prog, err, sizeof err),
                     HV_OK);
    grow(fx, src, 0);
    assert_int_equal(hv_exec_journal_stops(&j), HV_OK);
    hv_exec_journal_close(&j);
    /* a plan file's run may not take it, nor an online run a plan file's journal */
    assert_int_equal(hv_exec_journal_open(&j, path, &src->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_PLAN);
    assert_non_null(strstr(err, "online"));
    char offline[128];
    path_of(offline, sizeof offline, "offline.journal");
    assert_int_equal(hv_exec_journal_open(&j, offline, &src->plan, &prog, err, sizeof err), HV_OK);
    hv_exec_journal_close(&j);
    empty_plan(fx);
    assert_int_equal(hv_exec_journal_open_online(&j, offline, &fx->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_PLAN);
    /* a flipped digit in a pick record: its checksum fails, line 4 named */
    char text[2048];
    read_text(path, text, sizeof text);
    char *x = strstr(text, "Q L L0_0 x=");
    assert_non_null(x);
    long at = (long)(x - text) + 11;
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    fseek(f, at, SEEK_SET);
    fputc(text[at] == '1' ? '2' : '1', f);
    fclose(f);
    empty_plan(fx);
    assert_int_equal(hv_exec_journal_open_online(&j, path, &fx->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_FORMAT);
    assert_non_null(strstr(err, "line 4"));
    /* a stop before any course, and a pick record outside a stop, each with a good sum */
    path_of(path, sizeof path, "misplaced.journal");
    append_record(path, "HVJ 1 online");
    append_record(path, "P 3 y=0.5 left=0 right=0");
    empty_plan(fx);
    assert_int_equal(hv_exec_journal_open_online(&j, path, &fx->plan, &prog, err, sizeof err),
                     HV_ERR_EXEC_JOURNAL_FORMAT);
    assert_non_null(strstr(err, "line 2: a stop before the course"));
    free(fx);
    free(src);
}

/* A message that commits again the stops the plan holds must bring the very same ones. */
static void test_online_stop_matches(void **state)
{
    (void)state;
    fx_t *fx = malloc(sizeof *fx);
    fx_plan(fx, 2, 2);
    const hv_exec_plan_t *p = &fx->plan;
    const hv_exec_stop_t *st = &p->stops[1];
    hv_exec_pick_t picks[4];
    memcpy(picks, &p->picks[st->first[HV_SIDE_LEFT]], sizeof picks);
    assert_true(hv_exec_plan_stop_matches(p, 1, st->plan_index, st->y_m, picks, 2, 2));
    assert_false(hv_exec_plan_stop_matches(p, 1, st->plan_index + 1, st->y_m, picks, 2, 2));
    assert_false(hv_exec_plan_stop_matches(p, 1, st->plan_index, st->y_m + 0.01, picks, 2, 2));
    assert_false(hv_exec_plan_stop_matches(p, 1, st->plan_index, st->y_m, picks, 2, 1));
    assert_false(hv_exec_plan_stop_matches(p, 0, st->plan_index, st->y_m, picks, 2, 2));
    assert_false(hv_exec_plan_stop_matches(p, 2, st->plan_index, st->y_m, picks, 2, 2));
    hv_exec_pick_t swapped[4];
    memcpy(swapped, picks, sizeof swapped);
    swapped[0] = picks[1];
    swapped[1] = picks[0];
    assert_false(hv_exec_plan_stop_matches(p, 1, st->plan_index, st->y_m, swapped, 2, 2));
    free(fx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_write_replay),
        cmocka_unit_test(test_torn_and_corrupt),
        cmocka_unit_test(test_other_plan),
        cmocka_unit_test(test_estop_clear_record),
        cmocka_unit_test(test_halt_record),
        cmocka_unit_test(test_kill_and_resume),
        cmocka_unit_test(test_unreadable_ids_never_written),
        cmocka_unit_test(test_online_stops_rebuilt),
        cmocka_unit_test(test_online_records_refused),
        cmocka_unit_test(test_online_stop_matches),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
