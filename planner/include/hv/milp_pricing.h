/* Exact pricing of one stop for the branch-and-price (internal; milp_price.h).
 *
 * Given the fruits each arm may pick at the stop, each with its pick time w (ms) and its
 * dual price (profit, ms), find the pattern of least reduced cost
 *     v = offset + max(W(L), W(R)) - P(L) - P(R)
 * over all subsets L of the left items and R of the right items (the empty ones too);
 * offset is tau less the duals of any rows on the number of stops. Subset-row cuts add
 * their penalty pen[c] >= 0 to every pattern holding two or more of their items (cut c is
 * bit c of an item's `cuts`). Each arm's Pareto
 * frontier of (time, profit) is built item by item (Nemhauser-Ullmann), points that cannot
 * lead to v < 0 are dropped, and the two frontiers are merged on the stop time
 * M = max(W(L), W(R)): v = min_M offset + M - P_L(M) - P_R(M). With cuts a point also
 * carries the cuts it holds exactly once that a later item, or the other arm, still belongs
 * to; it dominates later points by its profit less the penalties of those cuts. A cut with
 * items on both arms (cross-arm) is charged within an arm for two items there, and in the
 * merge for one item on each arm: then the frontiers are merged class by class of the
 * cross-arm cuts their points hold once, since the penalty depends on both points. v is
 * exact either way.
 */
#ifndef HV_MILP_PRICING_H
#define HV_MILP_PRICING_H

#include <stddef.h>
#include <stdint.h>

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_price_item {
    uint32_t fruit; /* caller's fruit index, copied to the selection */
    double w_ms;    /* pick time, > 0 */
    double profit;  /* dual price, > 0 (items with profit <= 0 are never worth picking) */
    uint64_t cuts;  /* bit c: the item is in subset-row cut c (pen[c]); 0 for none */
} hv_price_item_t;

/* One frontier point: time, profit, and the item added to its parent point. */
typedef struct hv_front_pt {
    double w, p;
    int32_t item;   /* index into the side's sorted items, -1 for the empty set */
    int32_t parent; /* arena index, -1 for the empty set */
} hv_front_pt_t;

/* A frontier entry: its time and profit (net of the cut penalties it pays) where the merge
 * streams them, its arena point, and the cuts it holds exactly one item of / two or more. */
typedef struct hv_front_ref {
    double w, p;
    int32_t idx;
    uint64_t one, two;
} hv_front_ref_t;

/* One arm's points grouped by their cross-arm cuts, for the merge (milp_pricing.c). */
typedef struct hv_cross_scratch {
    uint64_t *mask;
    uint32_t *idx;
    size_t mask_cap, idx_cap;
} hv_cross_scratch_t;

/* Work space, reused across calls (grows as needed). */
typedef struct hv_pricer {
    hv_front_pt_t *arena;
    size_t arena_len, arena_cap;
    hv_front_ref_t *cur, *next; /* frontier: ascending w and strictly ascending p */
    size_t cur_cap, next_cap;
    hv_front_ref_t *left_front; /* the first arm's finished frontier */
    size_t left_cap;
    double *pw; /* that frontier's times, profits and suffix minima of time - profit */
    size_t pw_cap;
    size_t *parg;         /* per first-arm point: the point attaining the suffix minimum */
    hv_front_ref_t *pref; /* first-arm points (arena index, cut states) that bound g */
    size_t parg_cap, pref_cap;
    double rec_v;         /* the best whole pattern met while building the second arm ... */
    int32_t rec_a, rec_b; /* ... its two arena points (-1: none) ... */
    double rec_pen;       /* ... and the cross-arm penalty that pair pays */
    unsigned long long calls, points; /* statistics: pricings, frontier points made */
    hv_price_item_t *sorted;          /* both sides' items, sorted by profit density */
    size_t sorted_cap;
    double *brk; /* (breakpoint, slope change) pairs of the bound's weight (best_weight) */
    size_t brk_cap;
    hv_cross_scratch_t cross[2]; /* per arm, for the merge with cross-arm cuts */
    double t_deadline_s;         /* 0: none; else a call still building frontiers then (the clock,
                            CLOCK_MONOTONIC s, is read every 4096 points) stops with
                            HV_ERR_MILP_DEADLINE: bad duals can make frontiers huge */
    int timed_out;               /* scratch: the current call passed the deadline */
} hv_pricer_t;

void hv_pricer_init(hv_pricer_t *pr);
void hv_pricer_free(hv_pricer_t *pr);

/* The pattern of least reduced cost, if it is below v_bound (<= 0; the caller may know a
 * pattern that good, and a lower threshold prunes more). pen_ms: the cuts' penalties
 * (>= 0, indexed by the items' cut bits; NULL: no cuts, the bits are ignored). When one
 * is, *v_out is its exact v, its fruits are written to sel (room for nl + nr entries; none
 * for the empty pattern),
 * *n_sel, and *time_ms = max(W(L), W(R)) >= 0. Otherwise *v_out = v_bound, *n_sel = 0 and
 * *time_ms = -1 (v >= v_bound for every pattern). Items are not modified.
 * Returns HV_OK, HV_ERR_MILP_DEADLINE (the outputs then say nothing) or HV_ERR_PLAN_NOMEM. */
hv_status_t hv_pricer_best(hv_pricer_t *pr, const hv_price_item_t *left, size_t nl,
                           const hv_price_item_t *right, size_t nr, double offset_ms,
                           const double *pen_ms, double v_bound, double *v_out, uint32_t *sel,
                           size_t *n_sel, double *time_ms);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_PRICING_H */
