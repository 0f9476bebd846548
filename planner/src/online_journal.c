/* harvest-plan-online's journal (see online_journal.h). */
#include "hv/online_journal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hv/file_io.h"
#include "hv/fruit_id.h"
#include "hv/plan_status.h"
#include "hv/record_line.h"

#define LINE_BYTES 256

static hv_status_t put(hv_online_journal_t *j, int sync, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static hv_status_t put(hv_online_journal_t *j, int sync, const char *fmt, ...)
{
    char line[LINE_BYTES];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(line, LINE_BYTES - HV_RECORD_FRAMING, fmt, ap);
    va_end(ap);
    if (n < 0 || n >= (int)(LINE_BYTES - HV_RECORD_FRAMING)) {
        return HV_ERR_ARG;
    }
    return hv_record_write(j->fd, line, (size_t)n, LINE_BYTES, sync);
}

hv_status_t hv_online_journal_detection(hv_online_journal_t *j, const hv_fruit_t *f)
{
    if (j == NULL || f == NULL || memchr(f->id, '\0', sizeof f->id) == NULL ||
        hv_fruit_id_check(f->id, strlen(f->id), NULL) != HV_OK) {
        return HV_ERR_ARG;
    }
    return put(j, 0, "D %c %s x=%.17g y=%.17g z=%.17g yaw=%.17g",
               f->side == HV_SIDE_LEFT ? 'L' : 'R', f->id, f->x_m, f->y_m, f->z_m, f->yaw_rad);
}

hv_status_t hv_online_journal_seen(hv_online_journal_t *j, double seen_to_m)
{
    return j == NULL ? HV_ERR_ARG : put(j, 1, "V %.17g", seen_to_m);
}

hv_status_t hv_online_journal_horizon(hv_online_journal_t *j, const hv_online_t *o,
                                      size_t stops_from)
{
    if (j == NULL || o == NULL || stops_from > o->n_stops) {
        return HV_ERR_ARG;
    }
    size_t first = stops_from < o->n_stops ? o->stops[stops_from].first : o->n_order;
    hv_status_t st = HV_OK;
    for (size_t i = first; i < o->n_order && st == HV_OK; ++i) {
        uint32_t f = o->fruit_of[i];
        st = put(j, 0, "F %u %u", (unsigned)f, (unsigned)o->fruit_stop[f]);
    }
    return st == HV_OK ? put(j, 1, "H %zu n=%zu", o->pos, o->n_order - first) : st;
}

void hv_online_journal_close(hv_online_journal_t *j)
{
    if (j != NULL && j->fd >= 0) {
        close(j->fd);
        j->fd = -1;
    }
}

/* ---- replay ---------------------------------------------------------------------- */

typedef struct replay {
    hv_online_journal_t *j;
    hv_online_t *o;
    char *err;
    size_t errlen;
    int line;
    uint32_t *fruits, *stops; /* the F records of the horizon being read */
    size_t n, cap;
    size_t group_off; /* where its first F record starts */
} replay_t;

static hv_status_t bad(replay_t *r, hv_status_t code, const char *what)
{
    snprintf(r->err, r->errlen, "%s: line %d: %s", r->j->path, r->line, what);
    return code;
}

static hv_status_t header(replay_t *r, const char *line)
{
    const hv_instance_params_t *p = &r->o->params;
    double y0, len, margin, step;
    int end = 0;
    if (sscanf(line, "HVP 1 start=%lf length=%lf margin=%lf step=%lf%n", &y0, &len, &margin, &step,
               &end) != 4 ||
        line[end] != '\0') {
        return bad(r, HV_ERR_PLAN_FORMAT, "not an online planner's journal (version 1)");
    }
    if (y0 != p->row_start_m || len != p->row_length_m || margin != p->stop_margin_m ||
        step != p->stop_step_m) {
        return bad(r, HV_ERR_PLAN_FORMAT,
                   "the journal of another course (row, stop margin "
                   "or stop step of the config differ)");
    }
    return HV_OK;
}

static hv_status_t replay_line(replay_t *r, char *line, size_t len, size_t off)
{
    hv_record_check_t rc = hv_record_check(line, len);
    if (rc != HV_RECORD_OK) {
        return bad(r, HV_ERR_PLAN_FORMAT, hv_record_check_name(rc));
    }
    if (r->line == 1) {
        return header(r, line);
    }
    int end = 0;
    if (line[0] != 'F' && line[0] != 'H' && r->n > 0) {
        return bad(r, HV_ERR_PLAN_FORMAT, "a horizon's fruit records without their H record");
    }
    switch (line[0]) {
    case 'D': {
        hv_fruit_t f;
        char side[4], id[40];
        memset(&f, 0, sizeof f);
        if (sscanf(line, "D %3s %39s x=%lf y=%lf z=%lf yaw=%lf%n", side, id, &f.x_m, &f.y_m, &f.z_m,
                   &f.yaw_rad, &end) != 6 ||
            line[end] != '\0' || (strcmp(side, "L") != 0 && strcmp(side, "R") != 0) ||
            strlen(id) >= sizeof f.id || hv_fruit_id_check(id, strlen(id), NULL) != HV_OK) {
            return bad(r, HV_ERR_PLAN_FORMAT, "bad detection record");
        }
        memcpy(f.id, id, strlen(id) + 1);
        f.side = side[0] == 'L' ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
        hv_online_verdict_t v;
        r->j->detections++;
        return hv_online_detect(r->o, &f, &v);
    }
    case 'V': {
        double y;
        if (sscanf(line, "V %lf%n", &y, &end) != 1 || line[end] != '\0') {
            return bad(r, HV_ERR_PLAN_FORMAT, "bad view record");
        }
        hv_online_seen(r->o, y);
        return HV_OK;
    }
    case 'F': {
        unsigned f, s;
        if (sscanf(line, "F %u %u%n", &f, &s, &end) != 2 || line[end] != '\0') {
            return bad(r, HV_ERR_PLAN_FORMAT, "bad committed-fruit record");
        }
        if (r->n == r->cap) {
            size_t cap = r->cap ? 2 * r->cap : 64;
            uint32_t *a = realloc(r->fruits, cap * sizeof *a);
            if (a != NULL) {
                r->fruits = a;
            }
            uint32_t *b = a != NULL ? realloc(r->stops, cap * sizeof *b) : NULL;
            if (b == NULL) {
                return bad(r, HV_ERR_PLAN_NOMEM, "out of memory");
            }
            r->stops = b;
            r->cap = cap;
        }
        if (r->n == 0) {
            r->group_off = off;
        }
        r->fruits[r->n] = f;
        r->stops[r->n++] = s;
        return HV_OK;
    }
    case 'H': {
        size_t commit_end, n;
        if (sscanf(line, "H %zu n=%zu%n", &commit_end, &n, &end) != 2 || line[end] != '\0' ||
            n != r->n) {
            return bad(r, HV_ERR_PLAN_FORMAT,
                       "bad horizon record (or not as many fruit "
                       "records before it as it says)");
        }
        if (hv_online_recommit(r->o, commit_end, r->fruits, r->stops, n) != HV_OK) {
            return bad(r, HV_ERR_ARG,
                       "a horizon that cannot be what was committed (a fruit "
                       "unknown, committed twice or out of reach, or the course behind)");
        }
        r->n = 0;
        r->j->horizons++;
        return HV_OK;
    }
    default: return bad(r, HV_ERR_PLAN_FORMAT, "unknown record");
    }
}

hv_status_t hv_online_journal_open(hv_online_journal_t *j, const char *path, hv_online_t *o,
                                   char *err, size_t errlen)
{
    if (j == NULL || path == NULL || o == NULL || err == NULL || errlen == 0) {
        return HV_ERR_ARG;
    }
    memset(j, 0, sizeof *j);
    j->fd = -1;
    snprintf(j->path, sizeof j->path, "%s", path);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot open the journal: %s", path, strerror(errno));
        return HV_ERR_IO;
    }
    void *data = NULL;
    size_t size = 0;
    hv_status_t st = hv_file_read_all(path, &data, &size, err, errlen);
    replay_t r = {j, o, err, errlen, 0, NULL, NULL, 0, 0, 0};
    char *buf = data;
    size_t start = 0, complete = 0;
    for (size_t i = 0; st == HV_OK && i < size; ++i) {
        if (buf[i] != '\n') {
            continue;
        }
        r.line++;
        buf[i] = '\0';
        st = i - start >= LINE_BYTES ? bad(&r, HV_ERR_PLAN_FORMAT, "line too long")
                                     : replay_line(&r, buf + start, i - start, start);
        start = complete = i + 1;
    }
    free(data);
    free(r.fruits);
    free(r.stops);
    if (st == HV_OK && r.n > 0) {
        complete = r.group_off; /* a horizon not whole: never published */
    }
    if (st == HV_OK && complete < size) {
        j->torn_bytes = (unsigned)(size - complete);
        if (ftruncate(fd, (off_t)complete) != 0 || fdatasync(fd) != 0) {
            snprintf(err, errlen, "%s: cannot cut the torn end: %s", path, strerror(errno));
            st = HV_ERR_IO;
        }
    }
    if (st == HV_OK && lseek(fd, 0, SEEK_END) < 0) {
        snprintf(err, errlen, "%s: cannot seek: %s", path, strerror(errno));
        st = HV_ERR_IO;
    }
    if (st != HV_OK) {
        close(fd);
        return st;
    }
    j->fd = fd;
    if (complete == 0) {
        const hv_instance_params_t *p = &o->params;
        st = put(j, 1, "HVP 1 start=%.17g length=%.17g margin=%.17g step=%.17g", p->row_start_m,
                 p->row_length_m, p->stop_margin_m, p->stop_step_m);
        if (st != HV_OK) {
            snprintf(err, errlen, "%s: cannot write the journal header: %s", path, strerror(errno));
            hv_online_journal_close(j);
        }
    }
    return st;
}
