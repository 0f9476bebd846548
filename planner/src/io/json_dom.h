/* Private: a minimal, strict JSON document tree (RFC 8259) for the plan reader. */
#ifndef HV_JSON_DOM_H
#define HV_JSON_DOM_H

#include <stddef.h>

typedef enum json_type { JSON_NULL, JSON_BOOL, JSON_NUMBER, JSON_STRING, JSON_ARRAY,
                         JSON_OBJECT } json_type_t;

typedef struct json_value json_value_t;

typedef struct json_member {
    char *key;
    json_value_t *value;
} json_member_t;

struct json_value {
    json_type_t type;
    int boolean;
    double number;
    int is_integer;      /* the literal had no fraction or exponent */
    char *string;        /* UTF-8, NUL-terminated (embedded NULs are rejected) */
    size_t n;            /* array items or object members */
    json_value_t **items;
    json_member_t *members;
};

/* Parse `len` bytes. On error returns NULL and writes "line L, column C: message" to err. */
json_value_t *json_parse(const char *text, size_t len, char *err, size_t errlen);
void json_free(json_value_t *v);

/* Member of an object by key, NULL if absent or `obj` is not an object. */
const json_value_t *json_get(const json_value_t *obj, const char *key);

#endif /* HV_JSON_DOM_H */
