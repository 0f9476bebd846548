/* Subset-row cuts (milp_srcuts.h): which patterns a cut meets, and separation on hand-made
 * master points whose violated triples are known. That the cuts never cut off a plan is
 * checked end to end in test_milp.c (the same optima with cuts as without). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "hv/milp_srcuts.h"
#include "hv/plan_status.h"

#define NF 8

/* Each test's instance (fruits 0-4 on the left, 5-7 on the right) and cut set, freed
 * even when the test fails. */
typedef struct fixture {
    hv_fruit_t fr[NF];
    hv_instance_t in;
    hv_src_t s;
} fixture_t;

static int setup(void **state)
{
    fixture_t *x = calloc(1, sizeof *x);
    if (x == NULL) {
        return -1;
    }
    for (size_t i = 0; i < NF; ++i) {
        x->fr[i].side = i < 5 ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
    }
    x->in.n_fruits = NF;
    x->in.fruits = x->fr;
    *state = x;
    return hv_src_init(&x->s, NF) == HV_OK ? 0 : -1;
}

static int teardown(void **state)
{
    fixture_t *x = *state;
    hv_src_free(&x->s);
    free(x);
    return 0;
}

/* The odd cycle {0, 1}, {1, 2}, {0, 2} at 1/2 each: the cut on {0, 1, 2} has lhs 3/2. */
static void test_odd_cycle_is_cut(void **state)
{
    fixture_t *x = *state;
    hv_src_t *s = &x->s;
    const hv_instance_t *in = &x->in;
    static const uint32_t a[] = {0, 1, 3}, b[] = {1, 2}, c[] = {0, 2, 4}, d[] = {3, 4};
    hv_src_col_t cols[] = {{a, 3, 0.5}, {b, 2, 0.5}, {c, 3, 0.5}, {d, 2, 0.5}};
    size_t added;
    assert_int_equal(hv_src_separate(s, in, cols, 4, 10, 10, 0.05, &added), HV_OK);
    assert_int_equal(added, s->n);
    int found = 0;
    for (size_t k = 0; k < s->n; ++k) {
        found |= s->tri[k][0] == 0 && s->tri[k][1] == 1 && s->tri[k][2] == 2;
        assert_true(s->tri[k][0] < s->tri[k][1] && s->tri[k][1] < s->tri[k][2]);
    }
    assert_true(found);
    /* a known cut is not added again */
    size_t before = s->n;
    assert_int_equal(hv_src_separate(s, in, cols, 4, 10, 10, 0.05, &added), HV_OK);
    assert_int_equal(s->n, before + added);
    for (size_t k = before; k < s->n; ++k) {
        for (size_t j = 0; j < before; ++j) {
            assert_false(memcmp(s->tri[k], s->tri[j], sizeof s->tri[k]) == 0);
        }
    }
}

/* No cut on a point that satisfies them all, on mixed sides, or beyond the limits. */
static void test_no_cut_where_none_holds(void **state)
{
    fixture_t *x = *state;
    hv_src_t *s = &x->s;
    const hv_instance_t *in = &x->in;
    size_t added;
    /* two patterns at 1/2 sharing {0, 1}, the rest of 0 and 1 alone: lhs 1 */
    static const uint32_t a[] = {0, 1, 2}, b[] = {0, 1}, c[] = {2};
    hv_src_col_t sat[] = {{a, 3, 0.5}, {b, 2, 0.5}, {c, 1, 0.5}};
    assert_int_equal(hv_src_separate(s, in, sat, 3, 10, 10, 0.05, &added), HV_OK);
    assert_int_equal(added, 0);
    /* the odd cycle over sides: fruits 3, 4 left and 5 right */
    static const uint32_t m1[] = {3, 4}, m2[] = {4, 5}, m3[] = {3, 5};
    hv_src_col_t mixed[] = {{m1, 2, 0.5}, {m2, 2, 0.5}, {m3, 2, 0.5}};
    assert_int_equal(hv_src_separate(s, in, mixed, 3, 10, 10, 0.05, &added), HV_OK);
    assert_int_equal(added, 0);
    /* a violation of 0.5 is not above min_viol 0.5; columns at 1 never form one */
    static const uint32_t o1[] = {0, 1}, o2[] = {1, 2}, o3[] = {0, 2};
    hv_src_col_t odd[] = {{o1, 2, 0.5}, {o2, 2, 0.5}, {o3, 2, 0.5}};
    assert_int_equal(hv_src_separate(s, in, odd, 3, 10, 10, 0.5, &added), HV_OK);
    assert_int_equal(added, 0);
    odd[0].x = odd[1].x = odd[2].x = 1.0;
    assert_int_equal(hv_src_separate(s, in, odd, 3, 10, 10, 0.05, &added), HV_OK);
    assert_int_equal(added, 0);
    /* max_new 0 */
    odd[0].x = odd[1].x = odd[2].x = 0.5;
    assert_int_equal(hv_src_separate(s, in, odd, 3, 0, 10, 0.05, &added), HV_OK);
    assert_int_equal(added, 0);
    assert_int_equal(s->n, 0);
}

/* Two odd cycles as six pair columns: {a, b}, {b, c} and {a, c} of each triple t, at x. */
typedef struct cycles {
    uint32_t f[6][2];
    hv_src_col_t col[6];
} cycles_t;

static void two_cycles(cycles_t *c, const uint32_t *t1, double x1, const uint32_t *t2, double x2)
{
    for (int k = 0; k < 6; ++k) {
        const uint32_t *t = k < 3 ? t1 : t2;
        c->f[k][0] = t[k % 3 == 1 ? 1 : 0];
        c->f[k][1] = t[k % 3 == 0 ? 1 : 2];
        c->col[k] = (hv_src_col_t){c->f[k], 2, k < 3 ? x1 : x2};
    }
}

/* Separates the fixture's cuts from the two odd cycles t1 at x1 and t2 at x2 (at most
 * per_fruit new cuts per fruit); returns how many were added. */
static size_t separate_cycles(fixture_t *x, const uint32_t *t1, double x1, const uint32_t *t2,
                              double x2, size_t per_fruit)
{
    cycles_t cy;
    two_cycles(&cy, t1, x1, t2, x2);
    size_t added;
    assert_int_equal(hv_src_separate(&x->s, &x->in, cy.col, 6, 10, per_fruit, 0.05, &added), HV_OK);
    return added;
}

/* Two odd cycles sharing fruit 0: with one new cut per fruit only the more violated one
 * enters. */
static void test_per_fruit_limit(void **state)
{
    fixture_t *x = *state;
    hv_src_t *s = &x->s;
    static const uint32_t t1[] = {0, 1, 2}, t2[] = {0, 3, 4};
    assert_int_equal(separate_cycles(x, t1, 0.5, t2, 0.4, 1), 1);
    assert_int_equal(s->tri[0][0], 0);
    assert_int_equal(s->tri[0][1], 1);
    assert_int_equal(s->tri[0][2], 2);
    assert_int_equal(separate_cycles(x, t1, 0.5, t2, 0.4, 3), 1); /* now {0, 3, 4} (lhs 1.2) */
    assert_int_equal(s->tri[1][1], 3);
}

/* hits: a pattern meets a cut when it holds two or three of its fruits. */
static void test_hits(void **state)
{
    fixture_t *x = *state;
    hv_src_t *s = &x->s;
    static const uint32_t t1[] = {0, 1, 2}, t2[] = {5, 6, 7};
    assert_int_equal(separate_cycles(x, t1, 0.5, t2, 0.5, 10), 2); /* {0, 1, 2}, {5, 6, 7} */
    uint32_t out[4];
    static const uint32_t p1[] = {0, 3}, p2[] = {1, 2, 3}, p3[] = {0, 1, 2, 5, 7}, p4[] = {6};
    assert_int_equal(hv_src_hits(s, p1, 2, out), 0);
    assert_int_equal(hv_src_hits(s, p2, 3, out), 1);
    assert_int_equal(s->tri[out[0]][0], 0);
    assert_int_equal(hv_src_hits(s, p3, 5, out), 2);
    assert_int_equal(hv_src_hits(s, p4, 1, out), 0);
    assert_int_equal(hv_src_hits(s, p2, 3, out), 1); /* scratch counters were reset */
}

/* keep: the cuts left keep their order, and hits and separation see only them. */
static void test_keep(void **state)
{
    fixture_t *x = *state;
    hv_src_t *s = &x->s;
    static const uint32_t t1[] = {0, 1, 2}, t2[] = {5, 6, 7};
    assert_int_equal(separate_cycles(x, t1, 0.5, t2, 0.5, 10), 2);
    const unsigned char keep[] = {s->tri[0][0] == 5, s->tri[1][0] == 5}; /* {5, 6, 7} */
    assert_int_equal(hv_src_keep(s, keep), HV_OK);
    assert_int_equal(s->n, 1);
    assert_int_equal(s->tri[0][0], 5);
    assert_int_equal(s->tri[0][2], 7);
    uint32_t out[2];
    static const uint32_t gone[] = {0, 1}, left[] = {6, 7};
    assert_int_equal(hv_src_hits(s, gone, 2, out), 0);
    assert_int_equal(hv_src_hits(s, left, 2, out), 1);
    assert_int_equal(out[0], 0);
    /* the deleted triple is no longer known: the same point cuts it again */
    assert_int_equal(separate_cycles(x, t1, 0.5, t2, 0.5, 10), 1);
    assert_int_equal(s->tri[1][0], 0);
}

/* A whole row's fruits (50,000): separation follows the fractional columns, not the
 * square of the fruit count (20 GB as a dense pair table). */
static void test_many_fruits(void **state)
{
    (void)state;
    const size_t nf = 50000;
    hv_fruit_t *fr = calloc(nf, sizeof *fr); /* all on the left */
    assert_non_null(fr);
    hv_instance_t in;
    memset(&in, 0, sizeof in);
    in.n_fruits = nf;
    in.fruits = fr;
    hv_src_t s;
    assert_int_equal(hv_src_init(&s, nf), HV_OK);
    static const uint32_t t1[] = {10, 20000, 49999}, t2[] = {3, 4, 5};
    cycles_t cy;
    two_cycles(&cy, t1, 0.5, t2, 0.3); /* the second is no cut: lhs 0.9 */
    size_t added;
    assert_int_equal(hv_src_separate(&s, &in, cy.col, 6, 10, 10, 0.05, &added), HV_OK);
    assert_int_equal(added, 1);
    assert_int_equal(s.tri[0][0], 10);
    assert_int_equal(s.tri[0][2], 49999);
    static const uint32_t pat[] = {20000, 49999};
    uint32_t out[1];
    assert_int_equal(hv_src_hits(&s, pat, 2, out), 1);
    hv_src_free(&s);
    free(fr);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_odd_cycle_is_cut, setup, teardown),
        cmocka_unit_test_setup_teardown(test_no_cut_where_none_holds, setup, teardown),
        cmocka_unit_test_setup_teardown(test_per_fruit_limit, setup, teardown),
        cmocka_unit_test_setup_teardown(test_hits, setup, teardown),
        cmocka_unit_test_setup_teardown(test_keep, setup, teardown),
        cmocka_unit_test(test_many_fruits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
