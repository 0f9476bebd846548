/* The journal under power loss (issue 43, docs/RELIABILITY.md), on a journal harvest-exec
 * wrote for fuzz/data/plan.json against the simulator (data/run.journal, made by
 * fuzz/make_seeds.sh):
 *  - cut at every byte offset (a record torn anywhere, the last record included), it opens
 *    with exactly the progress of its complete records, the torn bytes dropped, and
 *    appending the lost record again gives the progress of the uncut journal;
 *  - a byte of any record changed (several kinds of damage at every offset) is detected
 *    by the checksum: the open is refused naming that line, and the file is left as it
 *    was for the operator to see. */
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

#include "hv/exec_journal.h"
#include "hv/exec_plan_json.h"
#include "hv/exec_status.h"
#include "hv/file_io.h"

typedef struct fixture {
    char dir[64], path[128];
    hv_exec_plan_t plan;
    char *journal; /* the whole journal harvest-exec wrote */
    size_t len;
    size_t line_end[512]; /* offset just past each line's newline */
    int lines;
} fixture_t;

static int setup(void **state)
{
    static fixture_t f; /* one per group run (the plan is ~200 KB) */
    char path[1024], err[512];
    snprintf(path, sizeof path, "%s/fuzz/data/plan.json", HV_SOURCE_DIR);
    if (hv_exec_plan_load_json(path, &f.plan, err, sizeof err) != HV_OK) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    snprintf(path, sizeof path, "%s/tests/reliability/data/run.journal", HV_SOURCE_DIR);
    void *data;
    if (hv_file_read_all(path, &data, &f.len, err, sizeof err) != HV_OK) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    f.journal = data;
    f.lines = 0;
    for (size_t i = 0; i < f.len && f.lines < 512; i++)
        if (f.journal[i] == '\n')
            f.line_end[f.lines++] = i + 1;
    snprintf(f.dir, sizeof f.dir, "/tmp/hv_powerloss_XXXXXX");
    if (!mkdtemp(f.dir))
        return -1;
    snprintf(f.path, sizeof f.path, "%s/j.journal", f.dir);
    *state = &f;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *f = *state;
    unlink(f->path);
    rmdir(f->dir);
    free(f->journal);
    return 0;
}

static void write_file(const char *path, const char *bytes, size_t n)
{
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    assert_int_equal(fwrite(bytes, 1, n, fp), n);
    assert_int_equal(fclose(fp), 0);
}

static void append_file(const char *path, const char *bytes, size_t n)
{
    FILE *fp = fopen(path, "ab");
    assert_non_null(fp);
    assert_int_equal(fwrite(bytes, 1, n, fp), n);
    assert_int_equal(fclose(fp), 0);
}

static size_t file_size(const char *path)
{
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    assert_int_equal(fseek(fp, 0, SEEK_END), 0);
    long n = ftell(fp);
    fclose(fp);
    return (size_t)n;
}

/* Open the journal at f->path: HV_OK with *prog and the torn bytes, the file closed. */
static hv_status_t open_at(fixture_t *f, hv_exec_progress_t *prog, unsigned *torn, char *err,
                           size_t errlen)
{
    hv_exec_journal_t j;
    hv_status_t st = hv_exec_journal_open(&j, f->path, &f->plan, prog, err, errlen);
    if (st == HV_OK) {
        *torn = j.torn_bytes;
        hv_exec_journal_close(&j);
    }
    return st;
}

/* The progress of the first `lines` complete records (lines >= 1: the header). */
static void progress_of(fixture_t *f, int lines, hv_exec_progress_t *prog)
{
    char err[256];
    unsigned torn;
    write_file(f->path, f->journal, f->line_end[lines - 1]);
    assert_int_equal(open_at(f, prog, &torn, err, sizeof err), HV_OK);
    assert_int_equal(torn, 0);
}

static void the_journal_is_a_whole_run(void **state)
{
    fixture_t *f = *state;
    /* header, stops, cuts, releases, outcomes and the row's end: every kind of record */
    assert_true(f->lines > 10);
    assert_int_equal(f->line_end[f->lines - 1], f->len);
    assert_memory_equal(f->journal, "HVJ 1 ", 6);
    hv_exec_progress_t prog;
    progress_of(f, f->lines, &prog);
    assert_int_equal(prog.row_done, 1);
    for (unsigned i = 0; i < f->plan.n_picks; i++)
        assert_int_equal(prog.pick[i], HV_PROG_DONE);
}

static void torn_at_every_byte_resumes_exactly(void **state)
{
    fixture_t *f = *state;
    static hv_exec_progress_t want[512], got, resumed; /* per complete-line count */
    for (int k = 1; k <= f->lines; k++)
        progress_of(f, k, &want[k]);
    int cases = 0;
    for (int k = 1; k < f->lines; k++) {
        size_t from = f->line_end[k - 1], to = f->line_end[k]; /* record k+1: [from, to) */
        for (size_t cut = from; cut < to; cut++) {
            char err[256];
            unsigned torn = 99;
            write_file(f->path, f->journal, cut);
            assert_int_equal(open_at(f, &got, &torn, err, sizeof err), HV_OK);
            /* exactly the records before the torn one, and its bytes gone from the file */
            assert_memory_equal(&got, &want[k], sizeof got);
            assert_int_equal(torn, cut - from);
            assert_int_equal(file_size(f->path), from);
            /* the executor writes the lost record again: the uncut journal's progress */
            append_file(f->path, f->journal + from, to - from);
            assert_int_equal(open_at(f, &resumed, &torn, err, sizeof err), HV_OK);
            assert_memory_equal(&resumed, &want[k + 1], sizeof resumed);
            cases++;
        }
    }
    /* every byte after the header was a cut point once */
    assert_int_equal(cases, (int)(f->len - f->line_end[0]));
    printf("torn journal: %d cut points over %d records, each resumed exactly\n", cases,
           f->lines - 1);
}

static void torn_header_starts_a_new_journal(void **state)
{
    fixture_t *f = *state;
    for (size_t cut = 0; cut < f->line_end[0]; cut++) {
        char err[256];
        unsigned torn;
        hv_exec_progress_t got, none;
        memset(&none, 0, sizeof none);
        write_file(f->path, f->journal, cut);
        assert_int_equal(open_at(f, &got, &torn, err, sizeof err), HV_OK);
        assert_memory_equal(&got, &none, sizeof got);
        /* the header is written again, byte for byte */
        assert_int_equal(file_size(f->path), f->line_end[0]);
    }
}

/* What damage does to one byte. */
static char damaged(char c, int kind)
{
    switch (kind) {
    case 0: return (char)(c ^ 0x01); /* one bit */
    case 1: return (char)(c ^ 0x20); /* letter case */
    case 2: return (char)(c ^ 0x80); /* high bit */
    case 3: return c == ' ' ? '0' : ' ';
    case 4: return c == '0' ? '1' : '0';
    case 5: return c == 'x' ? 'y' : 'x';
    default: return c == '+' ? '-' : '+';
    }
}

static void corrupt_record_is_detected_and_named(void **state)
{
    fixture_t *f = *state;
    static char copy[1 << 16]; /* static: a failed check leaves the test without freeing */
    assert_true(f->len <= sizeof copy);
    int cases = 0;
    for (int k = 0; k < f->lines; k++) {
        size_t from = k ? f->line_end[k - 1] : 0, to = f->line_end[k] - 1; /* not the '\n' */
        for (size_t at = from; at < to; at++)
            for (int kind = 0; kind < 7; kind++) {
                memcpy(copy, f->journal, f->len);
                copy[at] = damaged(copy[at], kind);
                if (copy[at] == f->journal[at] || copy[at] == '\n')
                    continue;
                write_file(f->path, copy, f->len);
                char err[256] = "", line[32];
                unsigned torn;
                hv_exec_progress_t got;
                hv_status_t st = open_at(f, &got, &torn, err, sizeof err);
                if (st != HV_ERR_EXEC_JOURNAL_FORMAT)
                    fail_msg("record %d byte %zu ('%c' -> '%c'): %s, not refused: %s", k + 1,
                             at - from, f->journal[at], copy[at], hv_status_name(st), err);
                snprintf(line, sizeof line, ": line %d: ", k + 1);
                if (!strstr(err, line))
                    fail_msg("record %d: the message does not name its line: %s", k + 1, err);
                /* refused, not repaired: the file is as it was found */
                assert_int_equal(file_size(f->path), f->len);
                cases++;
            }
    }
    printf("corrupt journal: %d damaged bytes, each refused naming its line\n", cases);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_journal_is_a_whole_run),
        cmocka_unit_test(torn_at_every_byte_resumes_exactly),
        cmocka_unit_test(torn_header_starts_a_new_journal),
        cmocka_unit_test(corrupt_record_is_detected_and_named),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
