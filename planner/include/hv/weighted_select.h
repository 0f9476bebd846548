/* Weighted selection (internal to the pricing, milp_pricing.c): where a piecewise linear
 * concave function stops rising, found without sorting its breakpoints. */
#ifndef HV_WEIGHTED_SELECT_H
#define HV_WEIGHTED_SELECT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* pairs[0 .. 2n) holds n pairs (key, weight), weights >= 0. Returns the least key k such
 * that the weights of the pairs with key <= k sum to at least `need` (> 0), or INFINITY
 * when all of them sum to less. Reorders the pairs. Expected time linear in n (a
 * quickselect on three-way partitions): the pricing calls it once per stop priced, where
 * sorting the pairs cost 3 % of a solve (SOLVER.md's history). */
double hv_weighted_select(double *pairs, size_t n, double need);

#ifdef __cplusplus
}
#endif
#endif /* HV_WEIGHTED_SELECT_H */
