/* Work sharing between the tree workers of the branch-and-price (internal;
 * planner/src/price/).
 *
 * DESIGN §10 counts 2 cores. When the helper thread (milp_helper.h) is not running, a
 * second worker searches the tree beside the first, each with its own master LP. An open
 * node travels between them as the path of restrictions from the root to it, with a warm
 * start that names its columns by content (opaque here: price/workers.c packs and reads it),
 * because the two masters number their columns differently once they have split. A worker
 * takes a node when it has none of its own, or when the best
 * bound it holds is well above the other's (so that both search near the best bound); the
 * other gives its best one at its next node. The incumbent is shared, so either prunes by
 * it, and so are the pseudocosts of fruit splits, so either branches on what both learnt.
 *
 * All calls are thread-safe. Bounds and makespans are in ms, times in s (CLOCK_MONOTONIC).
 */
#ifndef HV_MILP_SHARE_H
#define HV_MILP_SHARE_H

#include <stddef.h>
#include <stdint.h>

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One restriction on the path to a node: price/bp.h's node kind and its fields. */
typedef struct hv_share_step {
    int kind;
    uint32_t fruit, lo, hi;
    int32_t rhs;
} hv_share_step_t;

/* A node in transit: its path from the root (n steps), its bound, and the giver's warm
 * start (warm_len bytes, 0: none). A receiver's arrays grow as needed (capacities cap and
 * warm_cap); hv_share_node_free releases them. */
typedef struct hv_share_node {
    hv_share_step_t *path;
    size_t n, cap;
    unsigned char *warm;
    size_t warm_len, warm_cap;
    double lb_ms;
} hv_share_node_t;

void hv_share_node_free(hv_share_node_t *node);

typedef struct hv_share hv_share_t;

/* For n_workers workers over plans of n_fruits fruits. Returns HV_OK or HV_ERR_PLAN_NOMEM. */
hv_status_t hv_share_create(size_t n_workers, size_t n_fruits, hv_share_t **out);
void hv_share_destroy(hv_share_t *s);

/* A worker's plan (the stop per fruit) of makespan ub_ms: kept when it beats the shared one. */
void hv_share_offer(hv_share_t *s, const uint32_t *fruit_stop, double ub_ms);

/* 1 when the shared plan beats ub_ms: copied into fruit_stop, its makespan into *ub_out. */
int hv_share_take(hv_share_t *s, double ub_ms, uint32_t *fruit_stop, double *ub_out);

/* 1 when a worker other than `worker` (0 .. n_workers - 1) waits for a node or asked for
 * one (hv_share_balance) and the queue does not hold enough for them. */
int hv_share_hungry(hv_share_t *s, size_t worker);

/* `worker` publishes lb_ms, the best bound of the nodes it holds open (INFINITY: none).
 * When that exceeds every other worker's by more than margin_ms, it asks for a node
 * without waiting: the others give their best at their next node, and it takes it with
 * hv_share_poll. Returns 1 while its ask is pending. */
int hv_share_balance(hv_share_t *s, size_t worker, double lb_ms, double margin_ms);

/* A node given for `worker`'s pending ask: 1 with it in *node (as hv_share_wait), 0 none
 * yet, -2 out of memory. Never blocks. */
int hv_share_poll(hv_share_t *s, size_t worker, hv_share_node_t *node);

/* Queue an open node (copied). Returns HV_OK or HV_ERR_PLAN_NOMEM. */
hv_status_t hv_share_give(hv_share_t *s, const hv_share_node_t *node);

/* A worker without nodes of its own asks for one and waits up to 20 ms. Returns 1 with a
 * node in *node, 0 when the search is over (every worker waits and none is queued, or a
 * worker failed), -1 when nothing came yet (the caller checks its clock and asks again),
 * or -2 when out of memory. */
int hv_share_wait(hv_share_t *s, size_t worker, hv_share_node_t *node);

/* A worker stopped on an error: the others stop too (hv_share_failed). */
void hv_share_fail(hv_share_t *s);
int hv_share_failed(hv_share_t *s);

/* Pseudocosts of fruit splits pooled over the workers: per direction d (0 the "<= stop"
 * child, 1 the "> stop" one) and fruit, the sum of the bound rises per unit of mass moved
 * and their number, and both over all fruits (all[d], all_n[d]). */
typedef struct hv_share_pc {
    double *sum[2];
    long *n[2];
    double all[2];
    long all_n[2];
} hv_share_pc_t;

/* The pool becomes a copy of pc (the first worker's, when the second starts). */
/* dst's first n entries per direction and its totals become src's (no lock). */
void hv_share_pc_copy(hv_share_pc_t *dst, const hv_share_pc_t *src, size_t n);

void hv_share_pc_set(hv_share_t *s, const hv_share_pc_t *pc);

/* One observation: rise g of fruit's child in direction d. */
void hv_share_pc_add(hv_share_t *s, uint32_t fruit, int d, double g);

/* pc (arrays of n_fruits entries) becomes a copy of the pool. */
void hv_share_pc_get(hv_share_t *s, hv_share_pc_t *pc);

/* A bound valid at every node (the regional bound, milp_region.h): raised to lb_ms when
 * that is higher; hv_share_floor_get reads it (-INFINITY until set). */
void hv_share_floor(hv_share_t *s, double lb_ms);
double hv_share_floor_get(hv_share_t *s);

/* The least bound of the nodes still queued (INFINITY when none); their number in *n. */
double hv_share_open_lb(hv_share_t *s, size_t *n);

#ifdef __cplusplus
}
#endif
#endif /* HV_MILP_SHARE_H */
