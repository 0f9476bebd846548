/* Strict recursive-descent JSON parser (RFC 8259) into json_dom.h's tree.
 * Strict because a plan file drives a robot: no comments, no trailing commas, no
 * duplicate keys, no leading zeros, no NaN, bounded nesting depth. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "json_dom.h"

#define JSON_MAX_DEPTH 64

typedef struct jp {
    const char *s;
    size_t len, pos;
    char *err;
    size_t errlen;
    int failed;
} jp_t;

static void jp_fail(jp_t *p, const char *msg)
{
    if (p->failed) {
        return;
    }
    p->failed = 1;
    size_t line = 1, col = 1;
    for (size_t i = 0; i < p->pos && i < p->len; ++i) {
        if (p->s[i] == '\n') {
            ++line;
            col = 1;
        } else {
            ++col;
        }
    }
    if (p->err != NULL && p->errlen > 0) {
        snprintf(p->err, p->errlen, "line %zu, column %zu: %s", line, col, msg);
    }
}

static void jp_ws(jp_t *p)
{
    while (p->pos < p->len) {
        char c = p->s[p->pos];
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            ++p->pos;
        } else {
            break;
        }
    }
}

static int jp_peek(const jp_t *p) { return p->pos < p->len ? (unsigned char)p->s[p->pos] : -1; }

void json_free(json_value_t *v)
{
    if (v == NULL) {
        return;
    }
    free(v->string);
    for (size_t i = 0; v->items != NULL && i < v->n; ++i) {
        json_free(v->items[i]);
    }
    free(v->items);
    for (size_t i = 0; v->members != NULL && i < v->n; ++i) {
        free(v->members[i].key);
        json_free(v->members[i].value);
    }
    free(v->members);
    free(v);
}

static int hexval(int c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

static long jp_hex4(jp_t *p)
{
    if (p->pos + 4 > p->len) {
        jp_fail(p, "truncated \\u escape");
        return -1;
    }
    long v = 0;
    for (int i = 0; i < 4; ++i) {
        int h = hexval((unsigned char)p->s[p->pos + (size_t)i]);
        if (h < 0) {
            jp_fail(p, "bad hex digit in \\u escape");
            return -1;
        }
        v = v * 16 + h;
    }
    p->pos += 4;
    return v;
}

/* Append one code point as UTF-8. */
static size_t utf8_put(char *out, unsigned long cp)
{
    if (cp < 0x80) { out[0] = (char)cp; return 1; }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | (cp >> 6)); out[1] = (char)(0x80 | (cp & 0x3F)); return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | (cp >> 12)); out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (char)(0x80 | (cp & 0x3F)); return 3;
    }
    out[0] = (char)(0xF0 | (cp >> 18)); out[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (char)(0x80 | ((cp >> 6) & 0x3F)); out[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* At the opening quote. Returns a malloc'd string or NULL (failed set). */
static char *jp_string(jp_t *p)
{
    ++p->pos; /* opening quote */
    size_t start = p->pos;
    /* the decoded string is never longer than the source text */
    size_t end = start;
    while (end < p->len && p->s[end] != '"') {
        end += (p->s[end] == '\\') ? 2 : 1;
    }
    char *out = malloc(end - start + 1);
    if (out == NULL) {
        jp_fail(p, "out of memory");
        return NULL;
    }
    size_t n = 0;
    for (;;) {
        if (p->pos >= p->len) {
            jp_fail(p, "unterminated string");
            break;
        }
        unsigned char c = (unsigned char)p->s[p->pos];
        if (c == '"') {
            ++p->pos;
            out[n] = '\0';
            return out;
        }
        if (c < 0x20) {
            jp_fail(p, "control character in string");
            break;
        }
        if (c != '\\') {
            out[n++] = (char)c;
            ++p->pos;
            continue;
        }
        ++p->pos;
        int e = jp_peek(p);
        ++p->pos;
        switch (e) {
        case '"': out[n++] = '"'; break;
        case '\\': out[n++] = '\\'; break;
        case '/': out[n++] = '/'; break;
        case 'b': out[n++] = '\b'; break;
        case 'f': out[n++] = '\f'; break;
        case 'n': out[n++] = '\n'; break;
        case 'r': out[n++] = '\r'; break;
        case 't': out[n++] = '\t'; break;
        case 'u': {
            long cp = jp_hex4(p);
            if (cp < 0) {
                goto fail;
            }
            if (cp >= 0xD800 && cp <= 0xDBFF) { /* high surrogate: a low one must follow */
                if (p->pos + 2 > p->len || p->s[p->pos] != '\\' || p->s[p->pos + 1] != 'u') {
                    jp_fail(p, "unpaired surrogate in \\u escape");
                    goto fail;
                }
                p->pos += 2;
                long lo = jp_hex4(p);
                if (lo < 0xDC00 || lo > 0xDFFF) {
                    jp_fail(p, "unpaired surrogate in \\u escape");
                    goto fail;
                }
                cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
            } else if (cp >= 0xDC00 && cp <= 0xDFFF) {
                jp_fail(p, "unpaired surrogate in \\u escape");
                goto fail;
            }
            if (cp == 0) {
                jp_fail(p, "\\u0000 is not allowed in plan strings");
                goto fail;
            }
            /* \uXXXX (6 source bytes) decodes to at most 3 bytes, a pair (12) to 4 */
            n += utf8_put(out + n, (unsigned long)cp);
            break;
        }
        default:
            --p->pos;
            jp_fail(p, "bad escape in string");
            goto fail;
        }
    }
fail:
    free(out);
    return NULL;
}

static json_value_t *jp_value(jp_t *p, int depth);

static json_value_t *jp_new(jp_t *p, json_type_t t)
{
    json_value_t *v = calloc(1, sizeof *v);
    if (v == NULL) {
        jp_fail(p, "out of memory");
        return NULL;
    }
    v->type = t;
    return v;
}

static int jp_digits(jp_t *p)
{
    size_t start = p->pos;
    while (p->pos < p->len && p->s[p->pos] >= '0' && p->s[p->pos] <= '9') {
        ++p->pos;
    }
    return p->pos > start;
}

static json_value_t *jp_number(jp_t *p)
{
    size_t start = p->pos;
    int integer = 1;
    if (jp_peek(p) == '-') {
        ++p->pos;
    }
    if (jp_peek(p) == '0') {
        ++p->pos;
        if (jp_peek(p) >= '0' && jp_peek(p) <= '9') {
            jp_fail(p, "leading zero in number");
            return NULL;
        }
    } else if (!jp_digits(p)) {
        jp_fail(p, "bad number");
        return NULL;
    }
    if (jp_peek(p) == '.') {
        ++p->pos;
        integer = 0;
        if (!jp_digits(p)) {
            jp_fail(p, "digits expected after '.'");
            return NULL;
        }
    }
    if (jp_peek(p) == 'e' || jp_peek(p) == 'E') {
        ++p->pos;
        integer = 0;
        if (jp_peek(p) == '+' || jp_peek(p) == '-') {
            ++p->pos;
        }
        if (!jp_digits(p)) {
            jp_fail(p, "digits expected in exponent");
            return NULL;
        }
    }
    char tmp[64];
    size_t n = p->pos - start;
    if (n >= sizeof tmp) {
        jp_fail(p, "number literal too long");
        return NULL;
    }
    memcpy(tmp, p->s + start, n);
    tmp[n] = '\0';
    errno = 0;
    double d = strtod(tmp, NULL);
    if (!isfinite(d)) {
        p->pos = start;
        jp_fail(p, "number out of range");
        return NULL;
    }
    json_value_t *v = jp_new(p, JSON_NUMBER);
    if (v != NULL) {
        v->number = d;
        v->is_integer = integer;
    }
    return v;
}

static int jp_literal(jp_t *p, const char *word)
{
    size_t n = strlen(word);
    if (p->pos + n <= p->len && memcmp(p->s + p->pos, word, n) == 0) {
        p->pos += n;
        return 1;
    }
    return 0;
}

static json_value_t *jp_array(jp_t *p, int depth)
{
    json_value_t *v = jp_new(p, JSON_ARRAY);
    if (v == NULL) {
        return NULL;
    }
    ++p->pos; /* [ */
    size_t cap = 0;
    jp_ws(p);
    if (jp_peek(p) == ']') {
        ++p->pos;
        return v;
    }
    for (;;) {
        json_value_t *item = jp_value(p, depth + 1);
        if (item == NULL) {
            break;
        }
        if (v->n == cap) {
            size_t nc = cap ? cap * 2 : 8;
            json_value_t **ni = realloc(v->items, nc * sizeof *ni);
            if (ni == NULL) {
                json_free(item);
                jp_fail(p, "out of memory");
                break;
            }
            v->items = ni;
            cap = nc;
        }
        v->items[v->n++] = item;
        jp_ws(p);
        int c = jp_peek(p);
        if (c == ',') {
            ++p->pos;
            continue;
        }
        if (c == ']') {
            ++p->pos;
            return v;
        }
        jp_fail(p, "',' or ']' expected");
        break;
    }
    json_free(v);
    return NULL;
}

static json_value_t *jp_object(jp_t *p, int depth)
{
    json_value_t *v = jp_new(p, JSON_OBJECT);
    if (v == NULL) {
        return NULL;
    }
    ++p->pos; /* { */
    size_t cap = 0;
    jp_ws(p);
    if (jp_peek(p) == '}') {
        ++p->pos;
        return v;
    }
    for (;;) {
        jp_ws(p);
        if (jp_peek(p) != '"') {
            jp_fail(p, "object key (a string) expected");
            break;
        }
        size_t key_pos = p->pos;
        char *key = jp_string(p);
        if (key == NULL) {
            break;
        }
        if (json_get(v, key) != NULL) {
            free(key);
            p->pos = key_pos;
            jp_fail(p, "duplicate key in object");
            break;
        }
        jp_ws(p);
        if (jp_peek(p) != ':') {
            free(key);
            jp_fail(p, "':' expected");
            break;
        }
        ++p->pos;
        json_value_t *item = jp_value(p, depth + 1);
        if (item == NULL) {
            free(key);
            break;
        }
        if (v->n == cap) {
            size_t nc = cap ? cap * 2 : 8;
            json_member_t *nm = realloc(v->members, nc * sizeof *nm);
            if (nm == NULL) {
                free(key);
                json_free(item);
                jp_fail(p, "out of memory");
                break;
            }
            v->members = nm;
            cap = nc;
        }
        v->members[v->n].key = key;
        v->members[v->n].value = item;
        ++v->n;
        jp_ws(p);
        int c = jp_peek(p);
        if (c == ',') {
            ++p->pos;
            continue;
        }
        if (c == '}') {
            ++p->pos;
            return v;
        }
        jp_fail(p, "',' or '}' expected");
        break;
    }
    json_free(v);
    return NULL;
}

static json_value_t *jp_value(jp_t *p, int depth)
{
    if (depth > JSON_MAX_DEPTH) {
        jp_fail(p, "nesting too deep");
        return NULL;
    }
    jp_ws(p);
    int c = jp_peek(p);
    json_value_t *v = NULL;
    switch (c) {
    case '{': return jp_object(p, depth);
    case '[': return jp_array(p, depth);
    case '"': {
        char *s = jp_string(p);
        if (s == NULL) {
            return NULL;
        }
        v = jp_new(p, JSON_STRING);
        if (v == NULL) {
            free(s);
            return NULL;
        }
        v->string = s;
        return v;
    }
    case 't':
    case 'f':
    case 'n':
        if (jp_literal(p, "true") || jp_literal(p, "false")) {
            v = jp_new(p, JSON_BOOL);
            if (v != NULL) {
                v->boolean = (c == 't');
            }
            return v;
        }
        if (jp_literal(p, "null")) {
            return jp_new(p, JSON_NULL);
        }
        jp_fail(p, "unknown literal");
        return NULL;
    case -1:
        jp_fail(p, "unexpected end of input");
        return NULL;
    default:
        if (c == '-' || (c >= '0' && c <= '9')) {
            return jp_number(p);
        }
        jp_fail(p, "unexpected character");
        return NULL;
    }
}

json_value_t *json_parse(const char *text, size_t len, char *err, size_t errlen)
{
    jp_t p = {text, len, 0, err, errlen, 0};
    if (text == NULL) {
        jp_fail(&p, "no input");
        return NULL;
    }
    json_value_t *v = jp_value(&p, 0);
    if (v == NULL) {
        jp_fail(&p, "bad JSON"); /* no-op when a more precise message is set */
        return NULL;
    }
    jp_ws(&p);
    if (p.pos != p.len) {
        jp_fail(&p, "trailing characters after the JSON value");
        json_free(v);
        return NULL;
    }
    return v;
}

const json_value_t *json_get(const json_value_t *obj, const char *key)
{
    if (obj == NULL || obj->type != JSON_OBJECT) {
        return NULL;
    }
    for (size_t i = 0; i < obj->n; ++i) {
        if (strcmp(obj->members[i].key, key) == 0) {
            return obj->members[i].value;
        }
    }
    return NULL;
}
