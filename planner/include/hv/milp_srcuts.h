/* Subset-row cuts for the branch-and-price master (internal; planner/src/price/).
 *
 * For three fruits S = {i, j, k}, at most one pattern of a plan holds two or more of them
 * (each fruit is in exactly one pattern), so
 *     sum over patterns P with |P n S| >= 2 of lambda_P <= 1
 * holds for every plan: the rank-1 Chvatal-Gomory cut of S's three partition rows with
 * multipliers 1/2. The pattern LP violates it where fractional patterns at neighbouring
 * stops share fruits pairwise (an odd cycle). A cut's dual sigma <= 0 adds -sigma to the
 * reduced cost of every pattern holding two of S, which the pricing carries
 * (milp_pricing.h). Triples hold fruits of one side: over both sides their pricing cost
 * more than their bound gave (SOLVER.md's history).
 */
#ifndef HV_MILP_SRCUTS_H
#define HV_MILP_SRCUTS_H

#include <stddef.h>
#include <stdint.h>

#include "hv/plan_instance.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_src {
    size_t nf;
    uint32_t (*tri)[3]; /* the cuts' fruits, ascending */
    size_t n, cap;
    size_t *fbeg; /* per fruit: its cuts are fcut[fbeg[f] .. fbeg[f + 1]) */
    uint32_t *fcut;
    size_t fcut_cap;
    uint32_t *cnt; /* per cut: scratch counter, 0 between calls */
} hv_src_t;

/* One master column with a positive value: its fruits (ascending) and that value. */
typedef struct hv_src_col {
    const uint32_t *fruit;
    uint32_t n;
    double x;
} hv_src_col_t;

/* Returns HV_OK or HV_ERR_PLAN_NOMEM. */
hv_status_t hv_src_init(hv_src_t *s, size_t n_fruits);
void hv_src_free(hv_src_t *s);

/* Adds up to max_new of the cuts the master point cols[0 .. n) violates by more than
 * min_viol, the most violated first, each fruit in at most per_fruit of them, none twice;
 * their indices are s->n before the call .. s->n after, *added of them. Same-side triples
 * only (`inst` gives the sides). Returns HV_OK or HV_ERR_PLAN_NOMEM. */
hv_status_t hv_src_separate(hv_src_t *s, const hv_instance_t *inst, const hv_src_col_t *cols,
                            size_t n, size_t max_new, size_t per_fruit, double min_viol,
                            size_t *added);

/* dst (from hv_src_init, same number of fruits) holds src's cuts, in src's order.
 * Returns HV_OK, HV_ERR_ARG or HV_ERR_PLAN_NOMEM. */
hv_status_t hv_src_copy(hv_src_t *dst, const hv_src_t *src);

/* Forgets every cut (the caller deletes their rows). */
void hv_src_clear(hv_src_t *s);

/* Keeps the cuts c with keep[c] != 0, in their order (the caller deletes the others'
 * rows). Returns HV_OK or HV_ERR_PLAN_NOMEM. */
hv_status_t hv_src_keep(hv_src_t *s, const unsigned char *keep);

/* The cuts holding two or more of the fruits f[0 .. n) (distinct), into out (room for
 * s->n); returns their number. */
size_t hv_src_hits(hv_src_t *s, const uint32_t *f, size_t n, uint32_t *out);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_SRCUTS_H */
