/* A small strict JSON reader for the plan file: the whole text parsed into a flat node
 * array (caller-supplied, no allocation), then looked up by key. RFC 8259 grammar; string
 * escapes other than \uXXXX for ASCII are rejected (plan files never need them). */
#ifndef HV_JSON_DOM_H
#define HV_JSON_DOM_H

#include <stddef.h>

typedef enum json_type {
    JSON_NULL, JSON_FALSE, JSON_TRUE, JSON_NUMBER, JSON_STRING, JSON_ARRAY, JSON_OBJECT
} json_type_t;

typedef struct json_node {
    json_type_t type;
    int next;        /* next sibling (array element or object member value), -1 at the end */
    int first;       /* first child (ARRAY/OBJECT), -1 when empty */
    int key;         /* for an object member: the node of its key string, else -1 */
    size_t start;    /* text offset of the value (strings: after the opening quote) */
    size_t len;      /* bytes of the raw value (strings: between the quotes) */
    int count;       /* ARRAY/OBJECT: number of children */
} json_node_t;

typedef struct json_doc {
    const char *text;
    size_t text_len;
    json_node_t *nodes;
    int n_nodes, cap;
} json_doc_t;

/* Parse; root is node 0. On failure returns -1 and writes a message with the line number. */
int json_parse(json_doc_t *doc, const char *text, size_t len, json_node_t *nodes, int cap,
               char *err, size_t errlen);

/* Member `key` of object node `obj`, or -1. */
int json_get(const json_doc_t *doc, int obj, const char *key);

/* Value of a NUMBER node; returns 0 on success, -1 when not a number. */
int json_number(const json_doc_t *doc, int node, double *out);

/* Decoded STRING into out (NUL-terminated); -1 when not a string or too long. */
int json_string(const json_doc_t *doc, int node, char *out, size_t outlen);

/* 1 when the STRING node equals s. */
int json_string_is(const json_doc_t *doc, int node, const char *s);

#endif /* HV_JSON_DOM_H */
