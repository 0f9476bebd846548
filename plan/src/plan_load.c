/* JSON tree -> hv_plan_t, checking the schema of docs/PLAN_FORMAT.md (plan_schema.h) field
 * by field. Every field is required (except "horizon"), every unknown field is an error.
 * The JSON itself is parsed by jansson (strict: RFC 8259, duplicate keys and NUL in
 * strings refused); this file checks the tree against it. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jansson.h>

#include "hv/file_io.h"
#include "hv/fruit_id.h"
#include "hv/plan_io.h"
#include "plan_schema.h"

/* What the schema asks a value to be (jansson's integer and real are both numbers). */
typedef enum rd_kind { RD_NULL, RD_BOOL, RD_NUMBER, RD_STRING, RD_ARRAY, RD_OBJECT } rd_kind_t;

static rd_kind_t rd_kind_of(const json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return RD_OBJECT;
    case JSON_ARRAY: return RD_ARRAY;
    case JSON_STRING: return RD_STRING;
    case JSON_INTEGER:
    case JSON_REAL: return RD_NUMBER;
    case JSON_TRUE:
    case JSON_FALSE: return RD_BOOL;
    case JSON_NULL: break;
    }
    return RD_NULL;
}

typedef struct rd {
    const char *name; /* file name for messages */
    char *err;
    size_t errlen;
    int failed;
    hv_status_t code; /* of the first failure */
} rd_t;

/* snprintf through a va_list: field paths are diagnostics, cut short if ever too long. */
static void fmt_path(char *dst, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, cap, fmt, ap);
    va_end(ap);
}

/* "path.key", or "key" at the top. */
static void key_path(char *dst, size_t cap, const char *path, const char *key)
{
    fmt_path(dst, cap, "%s%s%s", path, *path ? "." : "", key);
}

static void rd_vfail(rd_t *r, hv_status_t code, const char *path, const char *fmt, va_list ap)
{
    if (r->failed) {
        return;
    }
    r->failed = 1;
    r->code = code;
    if (r->err == NULL || r->errlen == 0) {
        return;
    }
    char msg[256];
    vsnprintf(msg, sizeof msg, fmt, ap);
    snprintf(r->err, r->errlen, "%s: %s: %s", r->name, path, msg);
}

/* A field missing, of the wrong type or value: HV_ERR_PLAN_FORMAT. */
static void rd_fail(rd_t *r, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    rd_vfail(r, HV_ERR_PLAN_FORMAT, path, fmt, ap);
    va_end(ap);
}

/* A failure with its own code (a bad fruit id, stops out of order). */
static void rd_fail_code(rd_t *r, hv_status_t code, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    rd_vfail(r, code, path, fmt, ap);
    va_end(ap);
}

/* Reject members of `obj` that are not fields of `o`. */
static void rd_only(rd_t *r, const json_t *obj, const char *path, const plan_object_t *o)
{
    /* jansson's iterators take a mutable object; nothing here changes it */
    for (void *it = json_object_iter((json_t *)obj); it != NULL && !r->failed;
         it = json_object_iter_next((json_t *)obj, it)) {
        const char *key = json_object_iter_key(it);
        int ok = 0;
        for (size_t i = 0; i < o->n && !ok; ++i) {
            ok = strcmp(o->field[i].key, key) == 0;
        }
        if (!ok) {
            char p[160];
            key_path(p, sizeof p, path, key);
            rd_fail(r, p, "unknown field");
        }
    }
}

static const json_t *rd_field(rd_t *r, const json_t *obj, const char *path, const char *key,
                              rd_kind_t type, char *full, size_t fullcap)
{
    key_path(full, fullcap, path, key);
    if (r->failed) {
        return NULL;
    }
    const json_t *v = json_object_get(obj, key);
    if (v == NULL) {
        rd_fail(r, full, "missing");
        return NULL;
    }
    if (rd_kind_of(v) != type) {
        static const char *const names[] = {"null",     "a boolean", "a number",
                                            "a string", "an array",  "an object"};
        rd_fail(r, full, "expected %s", names[type]);
        return NULL;
    }
    return v;
}

static double rd_num(rd_t *r, const json_t *obj, const char *path, const char *key)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_NUMBER, full, sizeof full);
    return v ? json_number_value(v) : 0.0;
}

/* A number >= 0 (times and costs). */
static double rd_nonneg(rd_t *r, const json_t *obj, const char *path, const char *key)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_NUMBER, full, sizeof full);
    if (v == NULL) {
        return 0.0;
    }
    if (!(json_number_value(v) >= 0.0)) {
        rd_fail(r, full, "expected a number >= 0");
        return 0.0;
    }
    return json_number_value(v);
}

/* A non-negative integer no larger than `max`. */
static double rd_count(rd_t *r, const json_t *obj, const char *path, const char *key, double max)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_NUMBER, full, sizeof full);
    if (v == NULL) {
        return 0.0;
    }
    /* an integer literal only (jansson keeps 1.0 a real) */
    double x = json_number_value(v);
    if (!json_is_integer(v) || x < 0 || x > max) {
        rd_fail(r, full, "expected an integer in [0, %.0f]", max);
        return 0.0;
    }
    return json_number_value(v);
}

static void rd_str(rd_t *r, const json_t *obj, const char *path, const char *key, char *dst,
                   size_t cap)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_STRING, full, sizeof full);
    if (v == NULL) {
        return;
    }
    if (hv_plan_copy_str(dst, cap, json_string_value(v)) != HV_OK) {
        rd_fail(r, full, "longer than %zu bytes", cap - 1);
    }
}

/* A fruit id: a string inside the id set (hv/fruit_id.h), so that what the executor
 * journals reads back as the same fruit. */
static void rd_id(rd_t *r, const json_t *obj, const char *path, const char *key, char *dst,
                  size_t cap)
{
    char full[224];
    const json_t *v = rd_field(r, obj, path, key, RD_STRING, full, sizeof full);
    if (v == NULL) {
        return;
    }
    hv_diag_t d;
    if (hv_fruit_id_check(json_string_value(v), strlen(json_string_value(v)), &d) != HV_OK) {
        rd_fail_code(r, HV_ERR_PLAN_ID, full, "%s", d.message);
    } else if (hv_plan_copy_str(dst, cap, json_string_value(v)) != HV_OK) {
        rd_fail(r, full, "longer than %zu bytes", cap - 1);
    }
}

static int one_of(const char *s, const char *const *list)
{
    for (; *list != NULL; ++list) {
        if (strcmp(s, *list) == 0) {
            return 1;
        }
    }
    return 0;
}

/* Stop s against the one before it: docs/PLAN_FORMAT.md lists stops in driving order, by
 * pass, then strictly increasing y_m (a stop listed twice is out of order too). */
static void rd_stop_order(rd_t *r, const hv_plan_stop_t *stops, size_t s)
{
    const hv_plan_stop_t *st = &stops[s], *prev = &stops[s - 1];
    char f[64];
    if (r->failed) {
        return;
    }
    if (st->pass < prev->pass) {
        fmt_path(f, sizeof f, "stops[%zu].pass", s);
        rd_fail_code(r, HV_ERR_PLAN_ORDER, f,
                     "%d after pass %d of stops[%zu] (stops are listed by pass, then "
                     "increasing y_m)",
                     st->pass, prev->pass, s - 1);
    } else if (st->pass == prev->pass && !(st->y_m > prev->y_m)) {
        fmt_path(f, sizeof f, "stops[%zu].y_m", s);
        rd_fail_code(r, HV_ERR_PLAN_ORDER, f,
                     "%.9g not after %.9g of stops[%zu] in pass %d (stops are listed by "
                     "pass, then increasing y_m)",
                     st->y_m, prev->y_m, s - 1, st->pass);
    }
}

/* A string of the schema: within its size and, when the schema lists the values, one of
 * them. */
static void rd_string(rd_t *r, const json_t *obj, const char *path, const plan_field_t *f,
                      char *dst)
{
    rd_str(r, obj, path, f->key, dst, f->size);
    if (!r->failed && f->values != NULL && !one_of(dst, f->values)) {
        char full[224];
        key_path(full, sizeof full, path, f->key);
        rd_fail(r, full, "%s \"%s\"", f->refusal, dst);
    }
}

/* The solver's gap: a number >= 0, or null when unknown (heuristic plans), read as -1. */
static void rd_gap(rd_t *r, const json_t *obj, const char *path, const char *key, double *dst)
{
    char full[224];
    key_path(full, sizeof full, path, key);
    const json_t *g = json_object_get(obj, key);
    if (g == NULL) {
        rd_fail(r, full, "missing");
    } else if (json_is_null(g)) {
        *dst = -1.0;
    } else {
        *dst = rd_num(r, obj, path, key);
        if (!r->failed && *dst < 0) {
            rd_fail(r, full, "negative");
        }
    }
}

static void rd_side(rd_t *r, const json_t *obj, const char *path, const char *key, hv_side_t *dst)
{
    char side[4] = "", full[224];
    rd_str(r, obj, path, key, side, sizeof side);
    if (!r->failed && strcmp(side, "L") == 0) {
        *dst = HV_SIDE_LEFT;
    } else if (!r->failed && strcmp(side, "R") == 0) {
        *dst = HV_SIDE_RIGHT;
    } else if (!r->failed) {
        key_path(full, sizeof full, path, key);
        rd_fail(r, full, "expected \"L\" or \"R\"");
    }
}

/* The two constants every plan file opens with. */
static void rd_format(rd_t *r, const json_t *obj, const char *path, const plan_field_t *f)
{
    char full[224];
    if (f->kind == PLAN_FORMAT) {
        const json_t *v = rd_field(r, obj, path, f->key, RD_STRING, full, sizeof full);
        if (v != NULL && strcmp(json_string_value(v), "harvest-plan") != 0) {
            rd_fail(r, full, "expected \"harvest-plan\", got \"%s\"", json_string_value(v));
        }
        return;
    }
    double version = rd_count(r, obj, path, f->key, f->max);
    if (!r->failed && version != HV_PLAN_FORMAT_VERSION) {
        key_path(full, sizeof full, path, f->key);
        rd_fail(r, full, "unsupported version %.0f (this reader knows %d)", version,
                HV_PLAN_FORMAT_VERSION);
    }
}

static void rd_object(rd_t *r, const json_t *obj, const char *path, const plan_object_t *o,
                      char *base);

/* A nested object of the schema; an optional one only when the file has it. */
static void rd_nested(rd_t *r, const json_t *obj, const char *path, const plan_field_t *f,
                      char *base)
{
    if (f->optional && json_object_get(obj, f->key) == NULL) {
        return;
    }
    char full[224];
    const json_t *v = rd_field(r, obj, path, f->key, RD_OBJECT, full, sizeof full);
    if (v == NULL) {
        return;
    }
    if (f->optional) {
        *(int *)(base + f->at) = 1;
    }
    rd_object(r, v, full, f->object, base);
}

/* An array of objects: allocated (none when empty), its count set, each element read. */
static void rd_array(rd_t *r, const json_t *obj, const char *path, const plan_field_t *f,
                     char *base)
{
    const plan_array_t *a = f->array;
    char full[224];
    const json_t *arr = rd_field(r, obj, path, f->key, RD_ARRAY, full, sizeof full);
    size_t n = arr != NULL ? json_array_size(arr) : 0;
    if (n == 0) {
        return;
    }
    char *elems = calloc(n, a->element_size);
    if (elems == NULL) {
        rd_fail(r, full, "out of memory");
        return;
    }
    memcpy(base + f->at, &elems, sizeof elems);
    memcpy(base + f->count_at, &n, sizeof n);
    for (size_t i = 0; i < n && !r->failed; ++i) {
        char p[240];
        fmt_path(p, sizeof p, "%s[%zu]", full, i);
        const json_t *o = json_array_get(arr, i);
        if (!json_is_object(o)) {
            rd_fail(r, p, "expected an object");
            break;
        }
        rd_object(r, o, p, a->element, elems + i * a->element_size);
        if (a->driving_order && i > 0) {
            rd_stop_order(r, (const hv_plan_stop_t *)(const void *)elems, i);
        }
    }
}

/* Field `f` of `obj` (at `path`) into its member of the struct at `base`. */
static void rd_value(rd_t *r, const json_t *obj, const char *path, const plan_field_t *f,
                     char *base)
{
    char *m = base + f->at;
    switch (f->kind) {
    case PLAN_NUM: *(double *)m = rd_num(r, obj, path, f->key); break;
    case PLAN_NONNEG: *(double *)m = rd_nonneg(r, obj, path, f->key); break;
    case PLAN_GAP: rd_gap(r, obj, path, f->key, (double *)m); break;
    case PLAN_INT: *(int *)m = (int)rd_count(r, obj, path, f->key, f->max); break;
    case PLAN_U32: *(uint32_t *)m = (uint32_t)rd_count(r, obj, path, f->key, f->max); break;
    case PLAN_LONG: *(long *)m = (long)rd_count(r, obj, path, f->key, f->max); break;
    case PLAN_SIZE: *(size_t *)m = (size_t)rd_count(r, obj, path, f->key, f->max); break;
    case PLAN_STR: rd_string(r, obj, path, f, m); break;
    case PLAN_ID: rd_id(r, obj, path, f->key, m, f->size); break;
    case PLAN_SIDE: rd_side(r, obj, path, f->key, (hv_side_t *)m); break;
    case PLAN_FORMAT:
    case PLAN_VERSION: rd_format(r, obj, path, f); break;
    case PLAN_OBJECT: rd_nested(r, obj, path, f, base); break;
    case PLAN_ARRAY: rd_array(r, obj, path, f, base); break;
    }
}

/* An object of the schema: no field it does not list, then each of its fields in order,
 * up to the first failure. */
static void rd_object(rd_t *r, const json_t *obj, const char *path, const plan_object_t *o,
                      char *base)
{
    rd_only(r, obj, path, o);
    for (size_t i = 0; i < o->n && !r->failed; ++i) {
        rd_value(r, obj, path, &o->field[i], base);
    }
}

static void rd_plan(rd_t *r, const json_t *root, hv_plan_t *plan)
{
    if (!json_is_object(root)) {
        rd_fail(r, "(top)", "expected an object");
        return;
    }
    rd_object(r, root, "", &plan_schema, (char *)plan);
}

hv_status_t hv_plan_parse(const char *text, size_t len, const char *name, hv_plan_t *plan,
                          char *err, size_t errlen)
{
    if (plan == NULL || text == NULL) {
        return HV_ERR_ARG;
    }
    memset(plan, 0, sizeof *plan);
    if (name == NULL) {
        name = "(plan)";
    }
    json_error_t jerr;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &jerr);
    if (root == NULL) {
        if (err != NULL && errlen > 0) {
            snprintf(err, errlen, "%s: JSON: line %d, column %d: %s", name, jerr.line, jerr.column,
                     jerr.text);
        }
        return HV_ERR_PLAN_JSON;
    }
    rd_t r = {name, err, errlen, 0, HV_OK};
    rd_plan(&r, root, plan);
    json_decref(root);
    if (r.failed) {
        hv_plan_free(plan);
        return r.code;
    }
    return HV_OK;
}

hv_status_t hv_plan_load(const char *path, hv_plan_t *plan, char *err, size_t errlen)
{
    if (path == NULL || plan == NULL) {
        return HV_ERR_ARG;
    }
    memset(plan, 0, sizeof *plan);
    void *data = NULL;
    size_t len = 0;
    hv_status_t st = hv_file_read_all(path, &data, &len, err, errlen);
    if (st != HV_OK) {
        return st;
    }
    st = hv_plan_parse(data, len, path, plan, err, errlen);
    free(data);
    return st;
}
