/* Fuzz target: the journal replay (hv_exec_journal_open, hv/exec_journal.h), against the
 * plan of fuzz/data/plan.json.
 *
 * Input: one flag byte, then the journal file. Flag bit 0 re-signs every complete line
 * with its correct CRC-32 first, so inputs reach the record parser behind the checksum.
 * Properties: no crash or undefined behaviour; a refusal names the journal file and the
 * line; an accepted journal is cut back to its complete lines (a torn tail dropped), and
 * after one more record it opens again with the same progress plus that record: what was
 * replayed is what a resume continues from. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "fuzz_plan.h"
#include "fuzz_support.h"
#include "hv/cost_table.h"
#include "hv/exec_journal.h"

/* Each complete line's " *<crc>" (if any) replaced by the right one. */
static size_t resign(const uint8_t *in, size_t n, char *out, size_t cap)
{
    size_t o = 0, start = 0;
    for (size_t i = 0; i < n; i++) {
        if (in[i] != '\n')
            continue;
        size_t end = i;
        for (size_t k = i; k >= start + 2; k--)
            if (in[k - 2] == ' ' && in[k - 1] == '*') {
                end = k - 2;
                break;
            }
        if (o + (end - start) + 12 > cap)
            break;
        memcpy(out + o, in + start, end - start);
        uint32_t crc = hv_crc32(0, in + start, end - start);
        o += end - start;
        o += (size_t)snprintf(out + o, cap - o, " *%08x\n", (unsigned)crc);
        start = i + 1;
    }
    if (start < n && o + (n - start) <= cap) { /* a torn tail stays torn */
        memcpy(out + o, in + start, n - start);
        o += n - start;
    }
    return o;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 65536)
        return 0;
    const hv_exec_plan_t *plan = hv_fuzz_plan(0);
    char *text = malloc(2 * size + 64);
    if (!text)
        abort();
    size_t len = size - 1;
    if (data[0] & 1)
        len = resign(data + 1, size - 1, text, 2 * size + 64);
    else
        memcpy(text, data + 1, len);

    int fd = memfd_create("journal", 0);
    if (fd < 0 || write(fd, text, len) != (ssize_t)len)
        abort();
    char path[64], err[512] = "";
    snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    static hv_exec_progress_t prog, again; /* 3 KB each, off the fuzzer's stack */
    hv_exec_journal_t j;
    hv_status_t st = hv_exec_journal_open(&j, path, plan, &prog, err, sizeof err);
    if (st != HV_OK) {
        if (strncmp(err, path, strlen(path)) != 0 || !strstr(err, "line"))
            hv_fuzz_fail("refused (%s) without naming the file and line: '%s'", hv_status_name(st),
                         err);
        close(fd);
        free(text);
        return 0;
    }
    if (j.torn_bytes > len)
        hv_fuzz_fail("cut %u torn bytes of %zu", j.torn_bytes, len);
    if (hv_exec_journal_done(&j, 1.0) != HV_OK)
        hv_fuzz_fail("cannot append to an accepted journal");
    hv_exec_journal_close(&j);
    st = hv_exec_journal_open(&j, path, plan, &again, err, sizeof err);
    if (st != HV_OK)
        hv_fuzz_fail("an accepted journal plus one record is refused: %s", err);
    if (j.torn_bytes != 0 || !again.row_done)
        hv_fuzz_fail("the appended record did not read back");
    again.row_done = prog.row_done;
    if (memcmp(&prog, &again, sizeof prog) != 0)
        hv_fuzz_fail("the replayed progress changed after one more record");
    hv_exec_journal_close(&j);
    close(fd);
    free(text);
    return 0;
}
