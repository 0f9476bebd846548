/* Plan -> JSON text (docs/PLAN_FORMAT.md), with a small writer of our own: a growable
 * buffer, escaped strings, and numbers in the shortest form that reads back exactly. The
 * fields, their order and the line breaks between them are the schema's (plan_schema.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/file_io.h"
#include "hv/plan_io.h"
#include "plan_schema.h"

typedef struct jw {
    char *buf;
    size_t len, cap;
    int failed; /* sticky: out of memory or a non-finite number */
    hv_status_t why;
} jw_t;

static void jw_put(jw_t *w, const char *s, size_t n)
{
    if (w->failed) {
        return;
    }
    if (w->len + n + 1 > w->cap) {
        size_t cap = w->cap ? w->cap : 4096;
        while (w->len + n + 1 > cap) {
            cap *= 2;
        }
        char *nb = realloc(w->buf, cap);
        if (nb == NULL) {
            w->failed = 1;
            w->why = HV_ERR_PLAN_NOMEM;
            return;
        }
        w->buf = nb;
        w->cap = cap;
    }
    memcpy(w->buf + w->len, s, n);
    w->len += n;
    w->buf[w->len] = '\0';
}

static void jw_raw(jw_t *w, const char *s)
{
    jw_put(w, s, strlen(s));
}

static void jw_str(jw_t *w, const char *s)
{
    jw_put(w, "\"", 1);
    for (const unsigned char *p = (const unsigned char *)s; *p; ++p) {
        char esc[8];
        switch (*p) {
        case '"': jw_put(w, "\\\"", 2); break;
        case '\\': jw_put(w, "\\\\", 2); break;
        case '\n': jw_put(w, "\\n", 2); break;
        case '\r': jw_put(w, "\\r", 2); break;
        case '\t': jw_put(w, "\\t", 2); break;
        case '\b': jw_put(w, "\\b", 2); break;
        case '\f': jw_put(w, "\\f", 2); break;
        default:
            if (*p < 0x20) { /* other control characters must be \u-escaped in JSON */
                snprintf(esc, sizeof esc, "\\u%04x", (unsigned)*p);
                jw_put(w, esc, 6);
            } else {
                jw_put(w, (const char *)p, 1); /* UTF-8 bytes pass through */
            }
        }
    }
    jw_put(w, "\"", 1);
}

/* Shortest of %.15g..%.17g that parses back to the same double, so files stay readable
 * (0.01, not 0.010000000000000000208) and round trips stay exact. */
static void jw_num(jw_t *w, double v)
{
    if (!isfinite(v)) {
        if (!w->failed) {
            w->failed = 1;
            w->why = HV_ERR_NAN;
        }
        return;
    }
    char tmp[40];
    for (int prec = 15; prec <= 17; ++prec) {
        snprintf(tmp, sizeof tmp, "%.*g", prec, v);
        if (strtod(tmp, NULL) == v) {
            break;
        }
    }
    jw_raw(w, tmp);
}

static void jw_key(jw_t *w, const char *k)
{
    jw_str(w, k);
    jw_put(w, ": ", 2);
}

static void jw_fmt(jw_t *w, const char *fmt, ...)
{
    char tmp[64];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0) {
        jw_put(w, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
    }
}

static void jw_object(jw_t *w, const plan_object_t *o, const char *base);

/* An array of objects: the pointer at f->at, its count at f->count_at. */
static void jw_array(jw_t *w, const plan_field_t *f, const char *base)
{
    const plan_array_t *a = f->array;
    const char *elems;
    size_t n;
    memcpy(&elems, base + f->at, sizeof elems);
    memcpy(&n, base + f->count_at, sizeof n);
    jw_raw(w, "[");
    for (size_t i = 0; i < n; ++i) {
        jw_raw(w, i ? a->next : a->first);
        jw_object(w, a->element, elems + i * a->element_size);
    }
    jw_raw(w, n ? a->close : "]");
}

/* The value of field `f` of the struct at `base`. */
static void jw_value(jw_t *w, const plan_field_t *f, const char *base)
{
    const char *m = base + f->at;
    switch (f->kind) {
    case PLAN_NUM:
    case PLAN_NONNEG: jw_num(w, *(const double *)m); break;
    case PLAN_GAP:
        if (*(const double *)m < 0) {
            jw_raw(w, "null");
        } else {
            jw_num(w, *(const double *)m);
        }
        break;
    case PLAN_INT: jw_fmt(w, "%d", *(const int *)m); break;
    case PLAN_U32: jw_fmt(w, "%u", (unsigned)*(const uint32_t *)m); break;
    case PLAN_LONG: jw_fmt(w, "%ld", *(const long *)m); break;
    case PLAN_SIZE: jw_fmt(w, "%zu", *(const size_t *)m); break;
    case PLAN_STR:
    case PLAN_ID: jw_str(w, m); break;
    case PLAN_SIDE: jw_str(w, *(const hv_side_t *)m == HV_SIDE_LEFT ? "L" : "R"); break;
    case PLAN_FORMAT: jw_str(w, "harvest-plan"); break;
    case PLAN_VERSION: jw_fmt(w, "%d", HV_PLAN_FORMAT_VERSION); break;
    case PLAN_OBJECT: jw_object(w, f->object, base); break;
    case PLAN_ARRAY: jw_array(w, f, base); break;
    }
}

/* The fields of `o` from the struct at `base`; an optional object that is not there is
 * left out, key and all. */
static void jw_object(jw_t *w, const plan_object_t *o, const char *base)
{
    jw_raw(w, o->open);
    int first = 1;
    for (size_t i = 0; i < o->n; ++i) {
        const plan_field_t *f = &o->field[i];
        if (f->optional && !*(const int *)(base + f->at)) {
            continue;
        }
        if (!first) {
            jw_raw(w, f->sep ? f->sep : ", ");
        }
        first = 0;
        jw_key(w, f->key);
        jw_value(w, f, base);
    }
    jw_raw(w, o->close);
}

hv_status_t hv_plan_to_json(const hv_plan_t *plan, char **text, size_t *len)
{
    if (plan == NULL || text == NULL || len == NULL) {
        return HV_ERR_ARG;
    }
    jw_t w = {0};
    jw_object(&w, &plan_schema, (const char *)plan);
    if (w.failed) {
        free(w.buf);
        return w.why;
    }
    *text = w.buf;
    *len = w.len;
    return HV_OK;
}

hv_status_t hv_plan_save(const char *path, const hv_plan_t *plan, char *err, size_t errlen)
{
    char *text = NULL;
    size_t len = 0;
    hv_status_t st = hv_plan_to_json(plan, &text, &len);
    if (st != HV_OK) {
        if (err != NULL && errlen > 0) {
            snprintf(err, errlen, "%s: plan: cannot serialise (%s)", path ? path : "(null)",
                     hv_plan_file_status_name(st));
        }
        return st;
    }
    st = hv_file_write_atomic(path, text, len, err, errlen);
    free(text);
    return st;
}
