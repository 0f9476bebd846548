/* The tree workers' work sharing (milp_share.h): a node's path, bound and warm start arrive
 * intact, a hungry worker is seen, a worker far behind the other's bound asks for a node, the search
 * ends when every worker waits with nothing queued, a failure ends every wait, only a
 * better plan is handed over, and pseudocosts pool. */
#define _POSIX_C_SOURCE 200809L /* nanosleep */
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>

#include <cmocka.h>

#include "hv/milp_share.h"

/* A second worker (worker 1; the test's thread is worker 0) that waits until it gets a
 * node or the search ends. */
typedef struct waiter {
    hv_share_t *s;
    int got; /* 1 a node, 0 the end */
    hv_share_node_t node;
} waiter_t;

static void *wait_for_node(void *arg)
{
    waiter_t *w = arg;
    int r;
    while ((r = hv_share_wait(w->s, 1, &w->node)) == -1) {
    }
    w->got = r;
    return NULL;
}

/* A node of one restriction (from `step`) and bound lb, with no warm start. */
static hv_share_node_t one_step(hv_share_step_t *step, double lb)
{
    return (hv_share_node_t){step, 1, 1, NULL, 0, 0, lb};
}

static void test_node_travels_and_search_ends(void **state)
{
    (void)state;
    hv_share_t *s;
    assert_int_equal(hv_share_create(2, 4, &s), HV_OK);
    assert_false(hv_share_hungry(s, 0));
    waiter_t w = {s, -1, {0}};
    pthread_t t;
    assert_int_equal(pthread_create(&t, NULL, wait_for_node, &w), 0);
    while (!hv_share_hungry(s, 0)) { /* the waiter is seen as soon as it asks */
        struct timespec ms = {0, 1000000};
        nanosleep(&ms, NULL);
    }
    hv_share_step_t path[3] = {{1, 7, 0, 40, 0}, {2, 0, 10, 20, 3}, {1, 2, 41, 60, 1}};
    unsigned char warm[5] = {9, 0, 255, 17, 3};
    hv_share_node_t node = {path, 3, 3, warm, sizeof warm, sizeof warm, 1234.5};
    assert_int_equal(hv_share_give(s, &node), HV_OK);
    assert_int_equal(pthread_join(t, NULL), 0);
    assert_int_equal(w.got, 1);
    assert_int_equal(w.node.n, 3);
    assert_true(w.node.lb_ms == 1234.5);
    for (size_t i = 0; i < 3; ++i) {
        assert_int_equal(w.node.path[i].kind, path[i].kind);
        assert_int_equal(w.node.path[i].fruit, path[i].fruit);
        assert_int_equal(w.node.path[i].lo, path[i].lo);
        assert_int_equal(w.node.path[i].hi, path[i].hi);
        assert_int_equal(w.node.path[i].rhs, path[i].rhs);
    }
    assert_int_equal(w.node.warm_len, sizeof warm);
    assert_memory_equal(w.node.warm, warm, sizeof warm);
    size_t n_open;
    assert_true(isinf(hv_share_open_lb(s, &n_open)) && n_open == 0);
    /* both out of nodes: the waiter and then this worker see the end */
    w.got = -1;
    assert_int_equal(pthread_create(&t, NULL, wait_for_node, &w), 0);
    int r;
    hv_share_node_t mine = {0};
    while ((r = hv_share_wait(s, 0, &mine)) == -1) {
    }
    assert_int_equal(r, 0);
    assert_int_equal(pthread_join(t, NULL), 0);
    assert_int_equal(w.got, 0);
    hv_share_node_free(&mine);
    hv_share_node_free(&w.node);
    hv_share_destroy(s);
}

static void test_queue_bound_and_failure(void **state)
{
    (void)state;
    hv_share_t *s;
    assert_int_equal(hv_share_create(2, 4, &s), HV_OK);
    hv_share_step_t step = {1, 0, 0, 5, 0};
    unsigned char warm_a[3] = {1, 2, 3}, warm_b[2] = {7, 8};
    hv_share_node_t a = one_step(&step, 900.0), b = one_step(&step, 800.0);
    a.warm = warm_a;
    a.warm_len = sizeof warm_a;
    b.warm = warm_b;
    b.warm_len = sizeof warm_b;
    assert_int_equal(hv_share_give(s, &a), HV_OK);
    assert_int_equal(hv_share_give(s, &b), HV_OK);
    size_t n_open;
    assert_true(hv_share_open_lb(s, &n_open) == 800.0);
    assert_int_equal(n_open, 2);
    /* a worker that asks while nodes are queued gets one at once, not the end: the newest,
     * each with its own warm start */
    hv_share_node_t got = {0};
    assert_int_equal(hv_share_wait(s, 0, &got), 1);
    assert_int_equal(got.n, 1);
    assert_true(got.lb_ms == 800.0);
    assert_int_equal(got.warm_len, sizeof warm_b);
    assert_memory_equal(got.warm, warm_b, sizeof warm_b);
    assert_int_equal(hv_share_wait(s, 0, &got), 1);
    assert_true(got.lb_ms == 900.0);
    assert_int_equal(got.warm_len, sizeof warm_a);
    assert_memory_equal(got.warm, warm_a, sizeof warm_a);
    assert_int_equal(hv_share_give(s, &b), HV_OK);
    assert_false(hv_share_failed(s));
    hv_share_fail(s);
    assert_true(hv_share_failed(s));
    assert_int_equal(hv_share_wait(s, 0, &got), 0);
    hv_share_node_free(&got);
    hv_share_destroy(s);
}

/* A worker whose best open bound is well above the other's asks without waiting; the
 * other sees the ask (not its own), and the node given comes back by polling. */
static void test_balance_asks_when_behind(void **state)
{
    (void)state;
    hv_share_t *s;
    assert_int_equal(hv_share_create(2, 4, &s), HV_OK);
    assert_false(hv_share_balance(s, 1, 150.0, 10.0)); /* worker 0 has published nothing */
    assert_false(hv_share_balance(s, 0, 100.0, 10.0));
    assert_false(hv_share_balance(s, 1, 105.0, 10.0)); /* within the margin */
    assert_false(hv_share_hungry(s, 0));
    assert_true(hv_share_balance(s, 1, 150.0, 10.0));
    assert_true(hv_share_hungry(s, 0));
    assert_false(hv_share_hungry(s, 1)); /* its own ask is not a reason to give */
    hv_share_node_t got = {0};
    assert_int_equal(hv_share_poll(s, 1, &got), 0); /* nothing given yet */
    hv_share_step_t step = {2, 0, 3, 9, 1};
    hv_share_node_t node = one_step(&step, 100.0);
    assert_int_equal(hv_share_give(s, &node), HV_OK);
    assert_false(hv_share_hungry(s, 0));            /* the queue holds what was asked for */
    assert_int_equal(hv_share_poll(s, 0, &got), 0); /* worker 0 did not ask */
    assert_int_equal(hv_share_poll(s, 1, &got), 1);
    assert_int_equal(got.n, 1);
    assert_true(got.lb_ms == 100.0);
    assert_int_equal(got.path[0].hi, 9);
    assert_int_equal(got.warm_len, 0);
    assert_int_equal(hv_share_poll(s, 1, &got), 0); /* the ask is answered */
    assert_false(hv_share_hungry(s, 0));
    hv_share_node_free(&got);
    hv_share_destroy(s);
}

static void test_only_better_plans(void **state)
{
    (void)state;
    hv_share_t *s;
    assert_int_equal(hv_share_create(2, 3, &s), HV_OK);
    uint32_t got[3], a[3] = {4, 5, 6}, b[3] = {7, 8, 9};
    double ub;
    assert_false(hv_share_take(s, 1e9, got, &ub)); /* nothing offered yet */
    hv_share_offer(s, a, 500.0);
    hv_share_offer(s, b, 600.0); /* worse: ignored */
    assert_false(hv_share_take(s, 500.0, got, &ub));
    assert_true(hv_share_take(s, 550.0, got, &ub));
    assert_true(ub == 500.0);
    assert_int_equal(got[0], 4);
    assert_int_equal(got[2], 6);
    hv_share_destroy(s);
}

static void test_floor_only_rises(void **state)
{
    (void)state;
    hv_share_t *s;
    assert_int_equal(hv_share_create(2, 3, &s), HV_OK);
    assert_true(isinf(hv_share_floor_get(s)) && hv_share_floor_get(s) < 0.0); /* none yet */
    hv_share_floor(s, 803066.0);
    hv_share_floor(s, 802000.0); /* a lower bound from the other worker: kept out */
    assert_true(hv_share_floor_get(s) == 803066.0);
    hv_share_destroy(s);
}

static void test_pseudocosts_pooled(void **state)
{
    (void)state;
    hv_share_t *s;
    assert_int_equal(hv_share_create(2, 3, &s), HV_OK);
    double sum0[3] = {1.0, 2.0, 3.0}, sum1[3] = {0.5, 0.0, 0.0};
    long n0[3] = {1, 1, 1}, n1[3] = {1, 0, 0};
    hv_share_pc_t mine = {{sum0, sum1}, {n0, n1}, {6.0, 0.5}, {3, 1}};
    hv_share_pc_set(s, &mine);
    hv_share_pc_add(s, 1, 1, 4.0); /* the other worker learns */
    hv_share_pc_add(s, 1, 1, 2.0);
    double g0[3], g1[3];
    long m0[3], m1[3];
    hv_share_pc_t got = {{g0, g1}, {m0, m1}, {0.0, 0.0}, {0, 0}};
    hv_share_pc_get(s, &got);
    assert_true(g0[2] == 3.0 && m0[2] == 1);
    assert_true(g1[1] == 6.0 && m1[1] == 2);
    assert_true(got.all[1] == 6.5 && got.all_n[1] == 3);
    assert_true(got.all[0] == 6.0 && got.all_n[0] == 3);
    hv_share_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_node_travels_and_search_ends),
        cmocka_unit_test(test_queue_bound_and_failure),
        cmocka_unit_test(test_balance_asks_when_behind),
        cmocka_unit_test(test_only_better_plans),
        cmocka_unit_test(test_pseudocosts_pooled),
        cmocka_unit_test(test_floor_only_rises),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
