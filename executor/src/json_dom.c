/* Strict recursive-descent JSON parser into a flat node array (see json_dom.h). */
#include "json_dom.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define JSON_MAX_DEPTH 32

typedef struct parser {
    json_doc_t *doc;
    size_t pos;
    char *err;
    size_t errlen;
    int failed;
} parser_t;

static int line_of(const parser_t *p, size_t off)
{
    int line = 1;
    for (size_t i = 0; i < off && i < p->doc->text_len; i++)
        line += p->doc->text[i] == '\n';
    return line;
}

static int fail(parser_t *p, const char *what)
{
    if (!p->failed)
        snprintf(p->err, p->errlen, "line %d: %s", line_of(p, p->pos), what);
    p->failed = 1;
    return -1;
}

static void skip_ws(parser_t *p)
{
    const char *t = p->doc->text;
    while (p->pos < p->doc->text_len &&
           (t[p->pos] == ' ' || t[p->pos] == '\t' || t[p->pos] == '\n' || t[p->pos] == '\r'))
        p->pos++;
}

static int new_node(parser_t *p, json_type_t type)
{
    json_doc_t *d = p->doc;
    if (d->n_nodes >= d->cap)
        return fail(p, "document has more values than the reader holds");
    json_node_t *n = &d->nodes[d->n_nodes];
    n->type = type;
    n->next = n->first = n->key = -1;
    n->start = p->pos;
    n->len = 0;
    n->count = 0;
    return d->n_nodes++;
}

static int is_hex(char c)
{
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

static int parse_string(parser_t *p)
{
    const char *t = p->doc->text;
    p->pos++; /* opening quote */
    int id = new_node(p, JSON_STRING);
    if (id < 0)
        return -1;
    while (p->pos < p->doc->text_len && t[p->pos] != '"') {
        unsigned char c = (unsigned char)t[p->pos];
        if (c < 0x20)
            return fail(p, "control character inside a string");
        if (c == '\\') {
            p->pos++;
            if (p->pos >= p->doc->text_len)
                break;
            char e = t[p->pos];
            if (e == 'u') {
                for (int k = 1; k <= 4; k++)
                    if (p->pos + (size_t)k >= p->doc->text_len || !is_hex(t[p->pos + (size_t)k]))
                        return fail(p, "bad \\u escape");
                p->pos += 4;
            } else if (!strchr("\"\\/bfnrt", e)) {
                return fail(p, "bad escape in a string");
            }
        }
        p->pos++;
    }
    if (p->pos >= p->doc->text_len)
        return fail(p, "unterminated string");
    p->doc->nodes[id].len = p->pos - p->doc->nodes[id].start;
    p->pos++;
    return id;
}

static int parse_number(parser_t *p)
{
    const char *t = p->doc->text;
    size_t n = p->doc->text_len, i = p->pos;
    int id = new_node(p, JSON_NUMBER);
    if (id < 0)
        return -1;
    if (i < n && t[i] == '-')
        i++;
    if (i < n && t[i] == '0') {
        i++;
    } else if (i < n && t[i] >= '1' && t[i] <= '9') {
        while (i < n && t[i] >= '0' && t[i] <= '9')
            i++;
    } else {
        return fail(p, "bad number");
    }
    if (i < n && t[i] == '.') {
        i++;
        if (!(i < n && t[i] >= '0' && t[i] <= '9'))
            return fail(p, "bad number: digit expected after '.'");
        while (i < n && t[i] >= '0' && t[i] <= '9')
            i++;
    }
    if (i < n && (t[i] == 'e' || t[i] == 'E')) {
        i++;
        if (i < n && (t[i] == '+' || t[i] == '-'))
            i++;
        if (!(i < n && t[i] >= '0' && t[i] <= '9'))
            return fail(p, "bad number: digit expected in the exponent");
        while (i < n && t[i] >= '0' && t[i] <= '9')
            i++;
    }
    p->doc->nodes[id].len = i - p->pos;
    p->pos = i;
    return id;
}

static int parse_literal(parser_t *p, const char *word, json_type_t type)
{
    size_t w = strlen(word);
    if (p->pos + w > p->doc->text_len || memcmp(p->doc->text + p->pos, word, w) != 0)
        return fail(p, "unexpected character");
    int id = new_node(p, type);
    if (id < 0)
        return -1;
    p->doc->nodes[id].len = w;
    p->pos += w;
    return id;
}

static int parse_value(parser_t *p, int depth);

/* Append child to a container, keeping a pointer to the last child for O(1) appends. */
static void link_child(json_doc_t *d, int parent, int *last, int child)
{
    if (*last < 0)
        d->nodes[parent].first = child;
    else
        d->nodes[*last].next = child;
    *last = child;
    d->nodes[parent].count++;
}

static int parse_container(parser_t *p, int depth, int is_object)
{
    int id = new_node(p, is_object ? JSON_OBJECT : JSON_ARRAY);
    if (id < 0)
        return -1;
    char close = is_object ? '}' : ']';
    p->pos++;
    skip_ws(p);
    int last = -1;
    if (p->pos < p->doc->text_len && p->doc->text[p->pos] == close) {
        p->pos++;
        return id;
    }
    for (;;) {
        int key = -1;
        if (is_object) {
            skip_ws(p);
            if (p->pos >= p->doc->text_len || p->doc->text[p->pos] != '"')
                return fail(p, "object key (a string) expected");
            key = parse_string(p);
            if (key < 0)
                return -1;
            skip_ws(p);
            if (p->pos >= p->doc->text_len || p->doc->text[p->pos] != ':')
                return fail(p, "':' expected after an object key");
            p->pos++;
        }
        int v = parse_value(p, depth + 1);
        if (v < 0)
            return -1;
        p->doc->nodes[v].key = key;
        link_child(p->doc, id, &last, v);
        skip_ws(p);
        if (p->pos >= p->doc->text_len)
            return fail(p, "unexpected end of the document");
        char c = p->doc->text[p->pos++];
        if (c == close)
            break;
        if (c != ',')
            return fail(p, is_object ? "',' or '}' expected" : "',' or ']' expected");
    }
    return id;
}

static int parse_value(parser_t *p, int depth)
{
    if (depth > JSON_MAX_DEPTH)
        return fail(p, "nesting too deep");
    skip_ws(p);
    if (p->pos >= p->doc->text_len)
        return fail(p, "value expected, end of the document found");
    char c = p->doc->text[p->pos];
    switch (c) {
    case '{': return parse_container(p, depth, 1);
    case '[': return parse_container(p, depth, 0);
    case '"': return parse_string(p);
    case 't': return parse_literal(p, "true", JSON_TRUE);
    case 'f': return parse_literal(p, "false", JSON_FALSE);
    case 'n': return parse_literal(p, "null", JSON_NULL);
    default:
        if (c == '-' || (c >= '0' && c <= '9'))
            return parse_number(p);
        return fail(p, "unexpected character");
    }
}

int json_parse(json_doc_t *doc, const char *text, size_t len, json_node_t *nodes, int cap,
               char *err, size_t errlen)
{
    doc->text = text;
    doc->text_len = len;
    doc->nodes = nodes;
    doc->n_nodes = 0;
    doc->cap = cap;
    parser_t p = {doc, 0, err, errlen, 0};
    if (parse_value(&p, 0) < 0)
        return -1;
    skip_ws(&p);
    if (p.pos != len)
        return fail(&p, "trailing characters after the document");
    return 0;
}

/* Compare a raw string node with a plain key; keys with escapes never match. */
static int raw_equals(const json_doc_t *doc, int node, const char *s)
{
    const json_node_t *n = &doc->nodes[node];
    size_t sl = strlen(s);
    return n->len == sl && memcmp(doc->text + n->start, s, sl) == 0;
}

int json_get(const json_doc_t *doc, int obj, const char *key)
{
    if (obj < 0 || doc->nodes[obj].type != JSON_OBJECT)
        return -1;
    for (int c = doc->nodes[obj].first; c >= 0; c = doc->nodes[c].next)
        if (raw_equals(doc, doc->nodes[c].key, key))
            return c;
    return -1;
}

int json_number(const json_doc_t *doc, int node, double *out)
{
    if (node < 0 || doc->nodes[node].type != JSON_NUMBER)
        return -1;
    char buf[64];
    const json_node_t *n = &doc->nodes[node];
    if (n->len >= sizeof buf)
        return -1;
    memcpy(buf, doc->text + n->start, n->len);
    buf[n->len] = '\0';
    *out = strtod(buf, NULL);
    return 0;
}

static int hexval(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return c - 'A' + 10;
}

int json_string(const json_doc_t *doc, int node, char *out, size_t outlen)
{
    if (node < 0 || doc->nodes[node].type != JSON_STRING || outlen == 0)
        return -1;
    const json_node_t *n = &doc->nodes[node];
    const char *s = doc->text + n->start;
    size_t o = 0;
    for (size_t i = 0; i < n->len; i++) {
        char c = s[i];
        if (c == '\\') {
            char e = s[++i];
            switch (e) {
            case 'b': c = '\b'; break;
            case 'f': c = '\f'; break;
            case 'n': c = '\n'; break;
            case 'r': c = '\r'; break;
            case 't': c = '\t'; break;
            case 'u': {
                int v = (hexval(s[i + 1]) << 12) | (hexval(s[i + 2]) << 8) |
                        (hexval(s[i + 3]) << 4) | hexval(s[i + 4]);
                if (v == 0 || v > 0x7f)
                    return -1; /* only ASCII: ids and paths in plans need no more */
                c = (char)v;
                i += 4;
                break;
            }
            default: c = e; break; /* " \ / */
            }
        }
        if (o + 1 >= outlen)
            return -1;
        out[o++] = c;
    }
    out[o] = '\0';
    return 0;
}

int json_string_is(const json_doc_t *doc, int node, const char *s)
{
    char buf[128];
    return json_string(doc, node, buf, sizeof buf) == 0 && strcmp(buf, s) == 0;
}
