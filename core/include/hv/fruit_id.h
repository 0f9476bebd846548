/* Fruit ids: the one definition of what an id may be (docs/PLAN_FORMAT.md, docs/FRAMES.md).
 *
 * An id is 1 to HV_FRUIT_ID_MAX_CHARS characters, each one of A-Z a-z 0-9 _ . -
 * Why so narrow: an id travels through a CSV field, a JSON string, a space-separated
 * journal record and the 32-byte id fields of the planner and the executor; with this
 * set it needs no quoting or escaping in any of them and always reads back as written
 * (a newline or a space in an id would break the journal's records, a comma the map's).
 */
#ifndef HV_FRUIT_ID_H
#define HV_FRUIT_ID_H

#include <stddef.h>

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_FRUIT_ID_MAX_CHARS 31 /* the 32-byte id fields, with their NUL */

/* 1 when `c` is in the id set, else 0. Other names that travel the same ways (the
 * operator's in the executor's journal) use the same set. */
int hv_fruit_id_char(int c);

/* HV_OK when the `len` bytes at `id` form a valid id (they need no NUL); else
 * HV_ERR_FRUIT_ID with `diag` (may be NULL) saying why: field "id", the message names
 * the first byte outside the set (as 0xNN) and its position, or the length. */
hv_status_t hv_fruit_id_check(const char *id, size_t len, hv_diag_t *diag);

#ifdef __cplusplus
}
#endif
#endif /* HV_FRUIT_ID_H */
