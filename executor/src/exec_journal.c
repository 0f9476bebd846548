/* The harvest journal (see hv/exec_journal.h). */
#define _POSIX_C_SOURCE 200809L
#include "hv/exec_journal.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hv/cost_table.h" /* hv_crc32 */
#include "hv/exec_sm.h"     /* node indices and names */
#include "hv/exec_status.h"
#include "hv/fruit_id.h"

#define JOURNAL_VERSION 1
#define LINE_MAX_BYTES 256

uint32_t hv_exec_plan_hash(const hv_exec_plan_t *plan)
{
    uint32_t crc = 0;
    for (uint16_t p = 0; p < plan->n_stops; p++) {
        uint32_t idx = plan->stops[p].plan_index;
        crc = hv_crc32(crc, &idx, sizeof idx);
    }
    for (uint16_t i = 0; i < plan->n_picks; i++) {
        const hv_exec_pick_t *pk = &plan->picks[i];
        unsigned char tag[3] = {(unsigned char)pk->side, (unsigned char)(pk->stop & 0xFF),
                                (unsigned char)(pk->stop >> 8)};
        crc = hv_crc32(crc, tag, sizeof tag);
        crc = hv_crc32(crc, pk->id, strlen(pk->id) + 1);
    }
    return crc;
}

static char side_char(hv_side_t s)
{
    return s == HV_SIDE_LEFT ? 'L' : 'R';
}

/* Append " *<crc>\n" and write the line with one write(), then fdatasync(). */
static hv_status_t append(hv_exec_journal_t *j, char *line, size_t len)
{
    if (j->fd < 0)
        return HV_ERR_EXEC_JOURNAL_IO;
    uint32_t crc = hv_crc32(0, line, len);
    int n = snprintf(line + len, LINE_MAX_BYTES - len, " *%08x\n", (unsigned)crc);
    if (n < 0 || (size_t)n >= LINE_MAX_BYTES - len)
        return HV_ERR_EXEC_JOURNAL_IO;
    len += (size_t)n;
    size_t off = 0;
    while (off < len) {
        ssize_t w = write(j->fd, line + off, len - off);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            return HV_ERR_EXEC_JOURNAL_IO;
        }
        off += (size_t)w;
    }
    if (fdatasync(j->fd) != 0)
        return HV_ERR_EXEC_JOURNAL_IO;
    j->records++;
    return HV_OK;
}

static hv_status_t fmt_append(hv_exec_journal_t *j, const char *fmt_prefix, ...)
    __attribute__((format(printf, 2, 3)));

static hv_status_t fmt_append(hv_exec_journal_t *j, const char *fmt_prefix, ...)
{
    char line[LINE_MAX_BYTES];
    va_list ap;
    va_start(ap, fmt_prefix);
    int n = vsnprintf(line, LINE_MAX_BYTES - 16, fmt_prefix, ap);
    va_end(ap);
    if (n < 0 || n >= LINE_MAX_BYTES - 16)
        return HV_ERR_EXEC_JOURNAL_IO;
    return append(j, line, (size_t)n);
}

static int pick_ok(const hv_exec_journal_t *j, int pick)
{
    return j && j->plan && pick >= 0 && pick < j->plan->n_picks;
}

/* A fruit record is written only when its id reads back as the same fruit: replay splits
 * records at spaces and lines at newlines, so an id outside the set is refused, never
 * written (the plan readers refuse such ids already; this guards plans built otherwise). */
static hv_status_t id_ok(const hv_exec_pick_t *pk)
{
    size_t n = strnlen(pk->id, sizeof pk->id);
    return hv_fruit_id_check(pk->id, n, NULL) == HV_OK ? HV_OK : HV_ERR_EXEC_JOURNAL_ID;
}

hv_status_t hv_exec_journal_stop(hv_exec_journal_t *j, int stop, double t_s)
{
    if (!j || !j->plan || stop < 0 || stop >= j->plan->n_stops)
        return HV_ERR_ARG;
    return fmt_append(j, "S %d t=%.3f", stop, t_s);
}

hv_status_t hv_exec_journal_cut(hv_exec_journal_t *j, int pick, int attempt, double t_s)
{
    if (!pick_ok(j, pick))
        return HV_ERR_ARG;
    const hv_exec_pick_t *pk = &j->plan->picks[pick];
    if (id_ok(pk) != HV_OK)
        return HV_ERR_EXEC_JOURNAL_ID;
    return fmt_append(j, "C %c %s a=%d t=%.3f", side_char(pk->side), pk->id, attempt, t_s);
}

hv_status_t hv_exec_journal_release(hv_exec_journal_t *j, int pick, int attempt, double t_s)
{
    if (!pick_ok(j, pick))
        return HV_ERR_ARG;
    const hv_exec_pick_t *pk = &j->plan->picks[pick];
    if (id_ok(pk) != HV_OK)
        return HV_ERR_EXEC_JOURNAL_ID;
    return fmt_append(j, "R %c %s a=%d t=%.3f", side_char(pk->side), pk->id, attempt, t_s);
}

hv_status_t hv_exec_journal_outcome(hv_exec_journal_t *j, int pick, int outcome, int reason,
                                    int attempt, double t_s)
{
    if (!pick_ok(j, pick) || outcome < 0 || outcome >= HV_OUT_COUNT || reason < 0 ||
        reason >= HV_RSN_COUNT)
        return HV_ERR_ARG;
    const hv_exec_pick_t *pk = &j->plan->picks[pick];
    if (id_ok(pk) != HV_OK)
        return HV_ERR_EXEC_JOURNAL_ID;
    return fmt_append(j, "F %c %s %s %s a=%d t=%.3f", side_char(pk->side), pk->id,
                      hv_exec_outcome_name(outcome), hv_exec_reason_name(reason), attempt, t_s);
}

hv_status_t hv_exec_journal_done(hv_exec_journal_t *j, double t_s)
{
    if (!j)
        return HV_ERR_ARG;
    return fmt_append(j, "D t=%.3f", t_s);
}

#define OPERATOR_MAX 32

int hv_exec_journal_operator_ok(const char *name)
{
    size_t n = name ? strlen(name) : 0;
    if (n == 0 || n > OPERATOR_MAX)
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!hv_fruit_id_char((unsigned char)name[i]))
            return 0;
    return 1;
}

hv_status_t hv_exec_journal_estop_clear(hv_exec_journal_t *j, const char *operator_name,
                                        unsigned nodes, double t_s)
{
    char list[64];
    if (!j || !hv_exec_journal_operator_ok(operator_name) || nodes == 0 ||
        hv_exec_node_list(nodes, list, sizeof list) != HV_OK)
        return HV_ERR_ARG;
    return fmt_append(j, "E %s nodes=%s t=%.3f", operator_name, list, t_s);
}

/* "vehicle,right_arm" -> 1 << HV_EXEC_*; 0 for an empty list, a repeat or an unknown name. */
static unsigned parse_nodes(char *list)
{
    unsigned mask = 0;
    for (char *save = NULL, *tok = strtok_r(list, ",", &save); tok;
         tok = strtok_r(NULL, ",", &save)) {
        int found = -1;
        for (int i = 0; i < HV_EXEC_NODES; i++)
            if (strcmp(tok, hv_exec_node_name(i)) == 0)
                found = i;
        if (found < 0 || (mask & (1u << found)))
            return 0;
        mask |= 1u << found;
    }
    return mask;
}

void hv_exec_journal_close(hv_exec_journal_t *j)
{
    if (j && j->fd >= 0) {
        close(j->fd);
        j->fd = -1;
    }
}

/* ---- replay ---------------------------------------------------------------------- */

typedef struct replay {
    hv_exec_journal_t *j;
    hv_exec_progress_t *prog;
    char *err;
    size_t errlen;
    int line;
} replay_t;

static hv_status_t bad(replay_t *r, hv_status_t code, const char *what)
{
    snprintf(r->err, r->errlen, "%s: line %d: %s", r->j->path, r->line, what);
    return code;
}

static int find_pick(replay_t *r, const char *side, const char *id)
{
    if (strcmp(side, "L") != 0 && strcmp(side, "R") != 0)
        return -2;
    return hv_exec_plan_find(r->j->plan, side[0] == 'L' ? HV_SIDE_LEFT : HV_SIDE_RIGHT, id);
}

/* The checksum field exactly as written ("%08x": 8 lowercase hex digits, nothing after).
 * strtoul would also take a sign, spaces, "0x" and upper case, so a damaged field could
 * still read as the right value and the damage go unseen. */
static int crc_field(const char *s, uint32_t *out)
{
    uint32_t v = 0;
    for (int i = 0; i < 8; i++) {
        char ch = s[i];
        if (ch >= '0' && ch <= '9')
            v = (v << 4) | (uint32_t)(ch - '0');
        else if (ch >= 'a' && ch <= 'f')
            v = (v << 4) | (uint32_t)(ch - 'a' + 10);
        else
            return -1;
    }
    if (s[8] != '\0')
        return -1;
    *out = v;
    return 0;
}

/* One complete line (without its newline). */
static hv_status_t replay_line(replay_t *r, char *line, size_t len)
{
    char *star = NULL;
    for (size_t i = len; i >= 2; i--)
        if (line[i - 2] == ' ' && line[i - 1] == '*') {
            star = line + i - 2;
            break;
        }
    if (!star)
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "no checksum");
    uint32_t want;
    if (crc_field(star + 2, &want) != 0)
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad checksum field");
    if (hv_crc32(0, line, (size_t)(star - line)) != want)
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "checksum mismatch (corrupt record)");
    *star = '\0';

    char kind[8], a[40], b[40], c[24], d[32];
    if (r->line == 1) {
        unsigned version, hash, picks, stops;
        if (sscanf(line, "HVJ %u plan=%x picks=%u stops=%u", &version, &hash, &picks, &stops) != 4)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "not a harvest journal header");
        if (version != JOURNAL_VERSION)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unsupported journal version");
        if (hash != r->j->plan_hash || picks != r->j->plan->n_picks ||
            stops != r->j->plan->n_stops)
            return bad(r, HV_ERR_EXEC_JOURNAL_PLAN, "the journal belongs to another plan");
        return HV_OK;
    }
    if (sscanf(line, "%7s", kind) != 1 || kind[1] != '\0')
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unknown record");
    int attempt;
    double t;
    switch (kind[0]) {
    case 'S': {
        int stop;
        if (sscanf(line, "S %d t=%lf", &stop, &t) != 2 || stop < 0 ||
            stop >= r->j->plan->n_stops)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad stop record");
        r->prog->stop_reached[stop] = 1;
        return HV_OK;
    }
    case 'C':
    case 'R': {
        if (sscanf(line, "%*c %39s %39s a=%d t=%lf", a, b, &attempt, &t) != 4)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad cut/release record");
        int pick = find_pick(r, a, b);
        if (pick < 0)
            return bad(r, HV_ERR_EXEC_JOURNAL_UNKNOWN, "fruit not in the plan");
        if (r->prog->pick[pick] != HV_PROG_DONE)
            r->prog->pick[pick] = kind[0] == 'C' ? HV_PROG_CUT : HV_PROG_RELEASE;
        return HV_OK;
    }
    case 'F': {
        if (sscanf(line, "F %39s %39s %23s %31s a=%d t=%lf", a, b, c, d, &attempt, &t) != 6)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad outcome record");
        int pick = find_pick(r, a, b);
        if (pick < 0)
            return bad(r, HV_ERR_EXEC_JOURNAL_UNKNOWN, "fruit not in the plan");
        int outcome = hv_exec_outcome_parse(c), reason = hv_exec_reason_parse(d);
        if (outcome < 0 || reason < 0)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unknown outcome or reason");
        if (r->prog->pick[pick] == HV_PROG_DONE)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "second outcome for one fruit");
        r->prog->pick[pick] = HV_PROG_DONE;
        r->prog->outcome[pick] = (uint8_t)outcome;
        r->prog->reason[pick] = (uint8_t)reason;
        return HV_OK;
    }
    case 'D':
        if (sscanf(line, "D t=%lf", &t) != 1)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad row-done record");
        r->prog->row_done = 1;
        return HV_OK;
    case 'E': {
        int end = 0;
        if (sscanf(line, "E %39s nodes=%39s t=%lf%n", a, b, &t, &end) != 3 || line[end] != '\0')
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad e-stop clear record");
        if (!hv_exec_journal_operator_ok(a))
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "e-stop clear: bad operator name");
        if (parse_nodes(b) == 0)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "e-stop clear: bad node list");
        r->prog->estop_clears++;
        return HV_OK;
    }
    default:
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unknown record");
    }
}

/* Make a new file's directory entry durable too. */
static void sync_dir(const char *path)
{
    char copy[512];
    snprintf(copy, sizeof copy, "%s", path);
    int dfd = open(dirname(copy), O_RDONLY | O_DIRECTORY);
    if (dfd >= 0) {
        fsync(dfd);
        close(dfd);
    }
}

hv_status_t hv_exec_journal_open(hv_exec_journal_t *j, const char *path,
                                 const hv_exec_plan_t *plan, hv_exec_progress_t *progress,
                                 char *err, size_t errlen)
{
    if (!j || !path || !plan || !progress || !err || errlen == 0)
        return HV_ERR_ARG;
    memset(j, 0, sizeof *j);
    memset(progress, 0, sizeof *progress);
    j->fd = -1;
    j->plan = plan;
    j->plan_hash = hv_exec_plan_hash(plan);
    snprintf(j->path, sizeof j->path, "%s", path);

    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot open the journal: %s", path, strerror(errno));
        return HV_ERR_EXEC_JOURNAL_IO;
    }
    struct stat sb;
    if (fstat(fd, &sb) != 0) {
        snprintf(err, errlen, "%s: cannot stat the journal: %s", path, strerror(errno));
        close(fd);
        return HV_ERR_EXEC_JOURNAL_IO;
    }
    size_t size = (size_t)sb.st_size;
    char *buf = malloc(size + 1);
    if (!buf) {
        snprintf(err, errlen, "%s: out of memory", path);
        close(fd);
        return HV_ERR_NOMEM;
    }
    size_t got = 0;
    while (got < size) {
        ssize_t n = pread(fd, buf + got, size - got, (off_t)got);
        if (n <= 0) {
            snprintf(err, errlen, "%s: cannot read the journal: %s", path,
                     n < 0 ? strerror(errno) : "short read");
            free(buf);
            close(fd);
            return HV_ERR_EXEC_JOURNAL_IO;
        }
        got += (size_t)n;
    }
    replay_t r = {j, progress, err, errlen, 0};
    size_t start = 0, complete = 0;
    hv_status_t st = HV_OK;
    for (size_t i = 0; i < size && st == HV_OK; i++) {
        if (buf[i] != '\n')
            continue;
        r.line++;
        buf[i] = '\0';
        if (i - start >= LINE_MAX_BYTES)
            st = bad(&r, HV_ERR_EXEC_JOURNAL_FORMAT, "line too long");
        else
            st = replay_line(&r, buf + start, i - start);
        start = i + 1;
        complete = start;
        j->records++;
    }
    free(buf);
    if (st != HV_OK) {
        close(fd);
        return st;
    }
    if (complete < size) {
        /* torn by a crash during a write: that record never counted, drop its bytes */
        j->torn_bytes = (unsigned)(size - complete);
        if (ftruncate(fd, (off_t)complete) != 0 || fdatasync(fd) != 0) {
            snprintf(err, errlen, "%s: cannot cut the torn last record: %s", path,
                     strerror(errno));
            close(fd);
            return HV_ERR_EXEC_JOURNAL_IO;
        }
    }
    if (lseek(fd, 0, SEEK_END) < 0) {
        snprintf(err, errlen, "%s: cannot seek: %s", path, strerror(errno));
        close(fd);
        return HV_ERR_EXEC_JOURNAL_IO;
    }
    j->fd = fd;
    if (complete == 0) {
        st = fmt_append(j, "HVJ %d plan=%08x picks=%u stops=%u", JOURNAL_VERSION,
                        (unsigned)j->plan_hash, (unsigned)plan->n_picks,
                        (unsigned)plan->n_stops);
        if (st != HV_OK) {
            snprintf(err, errlen, "%s: cannot write the journal header: %s", path,
                     strerror(errno));
            hv_exec_journal_close(j);
            return st;
        }
        sync_dir(path);
    }
    return HV_OK;
}
