/* A growable array for the solver's work space (internal).
 *
 * Capacity doubles from 64 entries, so appending n entries costs O(n) amortised.
 */
#ifndef HV_GROW_ARRAY_H
#define HV_GROW_ARRAY_H

#include <stdlib.h>

/* Make *p (of *cap entries of `elem` bytes) hold at least `need` entries. Returns 1, or 0
 * when out of memory (then *p and *cap are unchanged). */
static inline int hv_grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) {
        return 1;
    }
    size_t c = *cap ? *cap : 64;
    while (c < need) {
        c *= 2;
    }
    void *q = realloc(*p, c * elem);
    if (q == NULL) {
        return 0;
    }
    *p = q;
    *cap = c;
    return 1;
}

#endif /* HV_GROW_ARRAY_H */
