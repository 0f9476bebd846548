/* Weighted selection by quickselect (weighted_select.h). */
#include <math.h>

#include "hv/weighted_select.h"

static void swap_pair(double *pairs, size_t i, size_t j)
{
    double k = pairs[2 * i], w = pairs[2 * i + 1];
    pairs[2 * i] = pairs[2 * j];
    pairs[2 * i + 1] = pairs[2 * j + 1];
    pairs[2 * j] = k;
    pairs[2 * j + 1] = w;
}

double hv_weighted_select(double *pairs, size_t n, double need)
{
    size_t lo = 0, hi = n; /* the answer's key is among pairs [lo, hi) */
    while (hi > lo) {
        double pivot = pairs[2 * (lo + (hi - lo) / 2)], below = 0.0, at = 0.0;
        size_t lt = lo, i = lo, gt = hi;
        while (i < gt) { /* [lo, lt) < pivot, [lt, i) == pivot, [gt, hi) > pivot */
            double k = pairs[2 * i];
            if (k < pivot) {
                below += pairs[2 * i + 1];
                swap_pair(pairs, lt++, i++);
            } else if (k > pivot) {
                swap_pair(pairs, i, --gt);
            } else {
                at += pairs[2 * i++ + 1];
            }
        }
        if (below >= need) {
            hi = lt;
        } else if (below + at >= need) {
            return pivot;
        } else {
            need -= below + at; /* what the larger keys must still add */
            lo = gt;
        }
    }
    return INFINITY;
}
