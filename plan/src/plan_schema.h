/* The plan file's schema (docs/PLAN_FORMAT.md) as data, private to plan/src: every JSON
 * object of the format is a table of its fields in file order, each with its kind and the
 * member of hv_plan_t (or of a stop, pick or unreachable fruit) it lives in. The reader
 * (plan_load.c) checks a file against these tables and the writer (plan_json_write.c)
 * writes a plan through them, so the two cannot disagree on a key or its order. */
#ifndef HV_PLAN_SCHEMA_H
#define HV_PLAN_SCHEMA_H

#include <stddef.h>

/* What a field holds, in the file and in memory. */
typedef enum plan_kind {
    PLAN_NUM,     /* double, any finite number */
    PLAN_NONNEG,  /* double >= 0 (times, costs) */
    PLAN_GAP,     /* double; the file's null is a gap < 0 (unknown) */
    PLAN_INT,     /* int; an integer literal in [0, max] */
    PLAN_U32,     /* uint32_t; likewise */
    PLAN_LONG,    /* long; likewise */
    PLAN_SIZE,    /* size_t; likewise */
    PLAN_STR,     /* char[size]; one of `values` when that is not NULL */
    PLAN_ID,      /* char[size]: a fruit id (hv/fruit_id.h) */
    PLAN_SIDE,    /* hv_side_t: "L" or "R" */
    PLAN_FORMAT,  /* the constant "harvest-plan", no member */
    PLAN_VERSION, /* HV_PLAN_FORMAT_VERSION, no member */
    PLAN_OBJECT,  /* a nested object whose fields are members of the same struct */
    PLAN_ARRAY    /* an array of objects: a pointer and a count (size_t) */
} plan_kind_t;

struct plan_object;
struct plan_array;

typedef struct plan_field {
    const char *key;
    plan_kind_t kind;
    /* offsetof its member; for an optional PLAN_OBJECT, of the int that says it is there */
    size_t at;
    size_t size;     /* the member's size (PLAN_STR, PLAN_ID: the longest string + 1) */
    size_t count_at; /* PLAN_ARRAY: offsetof its count (size_t) beside the pointer at `at` */
    double max;      /* PLAN_INT..PLAN_SIZE, PLAN_VERSION: the largest value the reader takes */
    /* PLAN_STR: the values allowed (NULL-terminated; NULL: any), and the message for
     * another: <refusal> "<value>" */
    const char *const *values;
    const char *refusal;
    const struct plan_object *object; /* PLAN_OBJECT: its fields */
    const struct plan_array *array;   /* PLAN_ARRAY: its elements */
    int optional;                     /* PLAN_OBJECT: may be left out (the int at `at` is 0) */
    /* the writer's text before it, unless it is its object's first field; NULL: ", " */
    const char *sep;
} plan_field_t;

typedef struct plan_object {
    const plan_field_t *field;
    size_t n;
    const char *open, *close; /* the writer's text around the fields */
} plan_object_t;

typedef struct plan_array {
    const plan_object_t *element;
    size_t element_size;
    const char *first, *next; /* the writer's text before the first element, before others */
    const char *close;        /* ... after the last one; an empty array is "[]" */
    int driving_order;        /* the stops: each after the one before it (the reader checks) */
} plan_array_t;

/* The whole file: an hv_plan_t. */
extern const plan_object_t plan_schema;

#endif /* HV_PLAN_SCHEMA_H */
