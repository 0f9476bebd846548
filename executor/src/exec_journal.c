/* The harvest journal (see hv/exec_journal.h). */
#define _POSIX_C_SOURCE 200809L
#include "hv/exec_journal.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <libgen.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hv/cost_table.h" /* hv_crc32 */
#include "hv/exec_progress.h"
#include "hv/exec_sm.h" /* node indices and names */
#include "hv/exec_status.h"
#include "hv/fruit_id.h"
#include "hv/record_line.h"

#define JOURNAL_VERSION 1
#define LINE_MAX_BYTES  256

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

/* Frame and write one record (hv/record_line.h); fdatasync() unless the caller syncs a
 * batch of lines once at its end. */
static hv_status_t append_line(hv_exec_journal_t *j, char *line, size_t len, int sync)
{
    if (j->fd < 0 || hv_record_write(j->fd, line, len, LINE_MAX_BYTES, sync) != HV_OK)
        return HV_ERR_EXEC_JOURNAL_IO;
    j->records++;
    return HV_OK;
}

static hv_status_t vfmt_line(hv_exec_journal_t *j, int sync, const char *fmt, va_list ap)
{
    char line[LINE_MAX_BYTES];
    int n = vsnprintf(line, LINE_MAX_BYTES - 16, fmt, ap);
    if (n < 0 || n >= LINE_MAX_BYTES - 16)
        return HV_ERR_EXEC_JOURNAL_IO;
    return append_line(j, line, (size_t)n, sync);
}

/* One line of a batch: written, not yet synced. */
static hv_status_t fmt_line(hv_exec_journal_t *j, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

static hv_status_t fmt_line(hv_exec_journal_t *j, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    hv_status_t st = vfmt_line(j, 0, fmt, ap);
    va_end(ap);
    return st;
}

static hv_status_t fmt_append(hv_exec_journal_t *j, const char *fmt_prefix, ...)
    __attribute__((format(printf, 2, 3)));

static hv_status_t fmt_append(hv_exec_journal_t *j, const char *fmt_prefix, ...)
{
    va_list ap;
    va_start(ap, fmt_prefix);
    hv_status_t st = vfmt_line(j, 1, fmt_prefix, ap);
    va_end(ap);
    return st;
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

hv_status_t hv_exec_journal_halt(hv_exec_journal_t *j, int reason, double t_s)
{
    if (!j || reason <= HV_STOP_NONE || reason >= HV_STOP_COUNT)
        return HV_ERR_ARG;
    return fmt_append(j, "H %s t=%.3f", hv_exec_stop_reason_name(reason), t_s);
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

/* ---- online: the plan's stops ---------------------------------------------------- */

#define ONLINE_HEADER "HVJ 1 online"

hv_status_t hv_exec_journal_stops(hv_exec_journal_t *j)
{
    if (!j || !j->online || !j->grow)
        return HV_ERR_ARG;
    const hv_exec_plan_t *p = j->grow;
    if (j->stops_journalled >= p->n_stops)
        return HV_OK;
    /* every id first: a stop goes into the journal whole or not at all */
    for (unsigned i = p->stops[j->stops_journalled].first[HV_SIDE_LEFT]; i < p->n_picks; i++)
        if (id_ok(&p->picks[i]) != HV_OK)
            return HV_ERR_EXEC_JOURNAL_ID;
    hv_status_t st = HV_OK;
    if (!j->course_journalled)
        st = fmt_line(j, "O start=%.17g length=%.17g margin=%.17g", p->row_start_m, p->row_length_m,
                      p->stop_margin_m);
    for (uint16_t s = j->stops_journalled; s < p->n_stops && st == HV_OK; s++) {
        const hv_exec_stop_t *sp = &p->stops[s];
        st = fmt_line(j, "P %u y=%.17g left=%u right=%u", (unsigned)sp->plan_index, sp->y_m,
                      (unsigned)sp->count[HV_SIDE_LEFT], (unsigned)sp->count[HV_SIDE_RIGHT]);
        for (int side = 0; side < 2 && st == HV_OK; side++)
            for (unsigned k = 0; k < sp->count[side] && st == HV_OK; k++) {
                const hv_exec_pick_t *pk = &p->picks[sp->first[side] + k];
                st = fmt_line(j, "Q %c %s x=%.17g y=%.17g z=%.17g yaw=%.17g cost=%.17g",
                              side_char(pk->side), pk->id, pk->x_m, pk->y_m, pk->z_m, pk->yaw_rad,
                              pk->cost_s);
            }
    }
    if (st == HV_OK && fdatasync(j->fd) != 0)
        st = HV_ERR_EXEC_JOURNAL_IO;
    if (st == HV_OK) {
        j->course_journalled = 1;
        j->stops_journalled = p->n_stops;
    }
    return st;
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
    size_t line_off; /* where the current line starts in the file */
    /* online: the stop being read (its P record seen, its Q records coming) */
    hv_exec_pick_t *picks; /* HV_EXEC_MAX_PICKS */
    int group_open;
    size_t group_off; /* where its P record starts */
    unsigned g_index, g_left, g_right, g_got;
    double g_y;
    int outcome, reason; /* of the F record being applied */
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

/* Online: O, P and Q records (the plan's course and stops). */
static hv_status_t replay_plan_record(replay_t *r, char kind, const char *line)
{
    hv_exec_plan_t *p = r->j->grow;
    int end = 0;
    if (!p)
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT,
                   "a record of an online plan in the journal "
                   "of a plan file");
    if (kind == 'O') {
        double y0, len, margin;
        if (sscanf(line, "O start=%lf length=%lf margin=%lf%n", &y0, &len, &margin, &end) != 3 ||
            line[end] != '\0' || !isfinite(y0) || !(len > 0) || !isfinite(len) || !(margin >= 0) ||
            !isfinite(margin))
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad course record");
        if (r->j->course_journalled &&
            (y0 != p->row_start_m || len != p->row_length_m || margin != p->stop_margin_m))
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "a second, other course");
        p->row_start_m = y0;
        p->row_length_m = len;
        p->stop_margin_m = margin;
        r->j->course_journalled = 1;
        return HV_OK;
    }
    if (kind == 'P') {
        if (!r->j->course_journalled)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "a stop before the course record");
        if (sscanf(line, "P %u y=%lf left=%u right=%u%n", &r->g_index, &r->g_y, &r->g_left,
                   &r->g_right, &end) != 4 ||
            line[end] != '\0' || r->g_left + r->g_right > HV_EXEC_MAX_PICKS)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad stop record");
        r->group_open = 1;
        r->group_off = r->line_off;
        r->g_got = 0;
    } else {
        char side[4], id[40];
        hv_exec_pick_t *pk = &r->picks[r->g_got];
        memset(pk, 0, sizeof *pk);
        if (!r->group_open)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "a pick record outside a stop");
        if (sscanf(line, "Q %3s %39s x=%lf y=%lf z=%lf yaw=%lf cost=%lf%n", side, id, &pk->x_m,
                   &pk->y_m, &pk->z_m, &pk->yaw_rad, &pk->cost_s, &end) != 7 ||
            line[end] != '\0' || strlen(id) >= sizeof pk->id ||
            hv_fruit_id_check(id, strlen(id), NULL) != HV_OK)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad pick record");
        hv_side_t want = r->g_got < r->g_left ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
        if (strcmp(side, want == HV_SIDE_LEFT ? "L" : "R") != 0)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "a stop's picks out of side order");
        pk->side = want;
        memcpy(pk->id, id, strlen(id) + 1);
        r->g_got++;
    }
    if (r->g_got < r->g_left + r->g_right)
        return HV_OK;
    r->group_open = 0;
    if (hv_exec_plan_append(p, r->g_index, r->g_y, r->picks, (uint16_t)r->g_left,
                            (uint16_t)r->g_right) != HV_OK)
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT,
                   "a stop that does not follow the last one, "
                   "a fruit planned twice, or more than the plan's tables hold");
    r->j->stops_journalled = p->n_stops;
    return HV_OK;
}

/* A parsed record into the progress through the mapping every journal shares
 * (hv/exec_progress.h); `what` names a record it refuses as FORMAT. */
static hv_status_t apply(replay_t *r, hv_exec_journal_kind_t kind, int stop, int pick,
                         unsigned nodes, const char *what)
{
    hv_exec_action_t rec;
    memset(&rec, 0, sizeof rec);
    rec.kind = HV_ACT_JOURNAL;
    rec.u.jr.kind = kind;
    rec.u.jr.stop = stop;
    rec.u.jr.pick = pick;
    rec.u.jr.outcome = r->outcome;
    rec.u.jr.reason = r->reason;
    rec.u.jr.nodes = nodes;
    hv_status_t st = hv_exec_progress_apply(r->prog, r->j->plan, &rec);
    if (st == HV_ERR_EXEC_JOURNAL_UNKNOWN)
        return bad(r, st, "fruit not in the plan");
    return st == HV_OK ? HV_OK : bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, what);
}

/* One complete line (without its newline). */
static hv_status_t replay_line(replay_t *r, char *line, size_t len)
{
    hv_record_check_t rc = hv_record_check(line, len);
    if (rc != HV_RECORD_OK)
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, hv_record_check_name(rc));

    char kind[8], a[40], b[40], c[24], d[32];
    if (r->line == 1 && (strcmp(line, ONLINE_HEADER) == 0) != (r->j->online != 0))
        return bad(
            r, HV_ERR_EXEC_JOURNAL_PLAN,
            r->j->online
                ? "the journal of a plan file's run (--plan), not of an online one"
                : "the journal of an online run (harvest-exec --online), not of a plan file");
    if (r->line == 1 && r->j->online)
        return HV_OK;
    if (r->line == 1) {
        unsigned version, hash, picks, stops;
        if (sscanf(line, "HVJ %u plan=%x picks=%u stops=%u", &version, &hash, &picks, &stops) != 4)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "not a harvest journal header");
        if (version != JOURNAL_VERSION)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unsupported journal version");
        if (hash != r->j->plan_hash || picks != r->j->plan->n_picks || stops != r->j->plan->n_stops)
            return bad(r, HV_ERR_EXEC_JOURNAL_PLAN, "the journal belongs to another plan");
        return HV_OK;
    }
    if (sscanf(line, "%7s", kind) != 1 || kind[1] != '\0')
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unknown record");
    if (r->group_open && kind[0] != 'Q')
        return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "a stop's pick records end too early");
    int attempt;
    double t;
    switch (kind[0]) {
    case 'O':
    case 'P':
    case 'Q': return replay_plan_record(r, kind[0], line);
    case 'S': {
        int stop;
        if (sscanf(line, "S %d t=%lf", &stop, &t) != 2)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad stop record");
        return apply(r, HV_JR_STOP, stop, -1, 0, "bad stop record");
    }
    case 'C':
    case 'R': {
        if (sscanf(line, "%*c %39s %39s a=%d t=%lf", a, b, &attempt, &t) != 4)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad cut/release record");
        return apply(r, kind[0] == 'C' ? HV_JR_CUT : HV_JR_RELEASE, -1, find_pick(r, a, b), 0,
                     "bad cut/release record");
    }
    case 'F': {
        if (sscanf(line, "F %39s %39s %23s %31s a=%d t=%lf", a, b, c, d, &attempt, &t) != 6)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad outcome record");
        int pick = find_pick(r, a, b);
        int outcome = hv_exec_outcome_parse(c), reason = hv_exec_reason_parse(d);
        if (pick >= 0 && (outcome < 0 || reason < 0))
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unknown outcome or reason");
        r->outcome = outcome;
        r->reason = reason;
        return apply(r, HV_JR_OUTCOME, -1, pick, 0, "second outcome for one fruit");
    }
    case 'D':
        if (sscanf(line, "D t=%lf", &t) != 1)
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad row-done record");
        return apply(r, HV_JR_DONE, -1, -1, 0, "bad row-done record");
    case 'H': {
        int end = 0;
        if (sscanf(line, "H %31s t=%lf%n", d, &t, &end) != 2 || line[end] != '\0')
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad halt record");
        r->reason = hv_exec_stop_reason_parse(d);
        return apply(r, HV_JR_HALT, -1, -1, 0, "halt: unknown reason");
    }
    case 'E': {
        int end = 0;
        if (sscanf(line, "E %39s nodes=%39s t=%lf%n", a, b, &t, &end) != 3 || line[end] != '\0')
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "bad e-stop clear record");
        if (!hv_exec_journal_operator_ok(a))
            return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "e-stop clear: bad operator name");
        return apply(r, HV_JR_ESTOP_CLEAR, -1, -1, parse_nodes(b), "e-stop clear: bad node list");
    }
    default: return bad(r, HV_ERR_EXEC_JOURNAL_FORMAT, "unknown record");
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

/* Open and replay; `grow` set for an online journal (the plan it rebuilds). */
static hv_status_t open_journal(hv_exec_journal_t *j, const char *path, const hv_exec_plan_t *plan,
                                hv_exec_plan_t *grow, hv_exec_progress_t *progress, char *err,
                                size_t errlen)
{
    if (!j || !path || !plan || !progress || !err || errlen == 0)
        return HV_ERR_ARG;
    memset(j, 0, sizeof *j);
    memset(progress, 0, sizeof *progress);
    j->fd = -1;
    j->plan = plan;
    j->grow = grow;
    j->online = grow != NULL;
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
    replay_t r;
    memset(&r, 0, sizeof r);
    r.j = j;
    r.prog = progress;
    r.err = err;
    r.errlen = errlen;
    if (grow && !(r.picks = malloc(HV_EXEC_MAX_PICKS * sizeof *r.picks))) {
        snprintf(err, errlen, "%s: out of memory", path);
        free(buf);
        close(fd);
        return HV_ERR_NOMEM;
    }
    size_t start = 0, complete = 0;
    hv_status_t st = HV_OK;
    for (size_t i = 0; i < size && st == HV_OK; i++) {
        if (buf[i] != '\n')
            continue;
        r.line++;
        buf[i] = '\0';
        if (i - start >= LINE_MAX_BYTES)
            st = bad(&r, HV_ERR_EXEC_JOURNAL_FORMAT, "line too long");
        else {
            r.line_off = start;
            st = replay_line(&r, buf + start, i - start);
        }
        start = i + 1;
        complete = start;
        j->records++;
    }
    free(buf);
    free(r.picks);
    if (st != HV_OK) {
        close(fd);
        return st;
    }
    if (r.group_open) /* a stop whose picks were not all written: never acted on */
        complete = r.group_off;
    if (complete < size) {
        /* torn by a crash during a write: that record never counted, drop its bytes */
        j->torn_bytes = (unsigned)(size - complete);
        if (ftruncate(fd, (off_t)complete) != 0 || fdatasync(fd) != 0) {
            snprintf(err, errlen, "%s: cannot cut the torn last record: %s", path, strerror(errno));
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
        st = grow ? fmt_append(j, "%s", ONLINE_HEADER)
                  : fmt_append(j, "HVJ %d plan=%08x picks=%u stops=%u", JOURNAL_VERSION,
                               (unsigned)j->plan_hash, (unsigned)plan->n_picks,
                               (unsigned)plan->n_stops);
        if (st != HV_OK) {
            snprintf(err, errlen, "%s: cannot write the journal header: %s", path, strerror(errno));
            hv_exec_journal_close(j);
            return st;
        }
        sync_dir(path);
    }
    return HV_OK;
}

hv_status_t hv_exec_journal_open(hv_exec_journal_t *j, const char *path, const hv_exec_plan_t *plan,
                                 hv_exec_progress_t *progress, char *err, size_t errlen)
{
    return open_journal(j, path, plan, NULL, progress, err, errlen);
}

hv_status_t hv_exec_journal_open_online(hv_exec_journal_t *j, const char *path,
                                        hv_exec_plan_t *plan, hv_exec_progress_t *progress,
                                        char *err, size_t errlen)
{
    if (!plan || plan->n_stops || plan->n_picks)
        return HV_ERR_ARG;
    return open_journal(j, path, plan, plan, progress, err, errlen);
}
