/* Weighted selection (weighted_select.h) against sorting and walking the pairs, on random
 * pairs with many equal keys and zero weights, and the edge cases: no pairs, a need above
 * the total, a need met exactly at a key. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "hv/weighted_select.h"

#define MAX_PAIRS 64

static int by_key(const void *x, const void *y)
{
    const double *u = x, *v = y;
    return u[0] < v[0] ? -1 : u[0] > v[0];
}

/* The definition: sort by key, add the weights of each key in turn. */
static double reference(const double *pairs, size_t n, double need)
{
    double s[2 * MAX_PAIRS];
    memcpy(s, pairs, 2 * n * sizeof *s);
    qsort(s, n, 2 * sizeof *s, by_key);
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        sum += s[2 * i + 1];
        if (sum >= need && (i + 1 == n || s[2 * i + 2] > s[2 * i])) {
            return s[2 * i];
        }
    }
    return INFINITY;
}

static uint32_t next_u32(uint64_t *state)
{
    *state = *state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(*state >> 33);
}

static void test_random_vs_sorting(void **state)
{
    (void)state;
    uint64_t rng = 12345;
    for (int trial = 0; trial < 20000; ++trial) {
        size_t n = next_u32(&rng) % (MAX_PAIRS + 1);
        unsigned n_keys = 1 + next_u32(&rng) % 12; /* few distinct keys: many ties */
        double pairs[2 * MAX_PAIRS], total = 0.0;
        for (size_t i = 0; i < n; ++i) {
            pairs[2 * i] = (double)(next_u32(&rng) % n_keys) / (double)n_keys;
            pairs[2 * i + 1] = (double)(next_u32(&rng) % 5); /* whole: sums are exact */
            total += pairs[2 * i + 1];
        }
        /* needs below, at and above the total, on and between the partial sums */
        double need = 0.5 + (double)(next_u32(&rng) % 8) * (total + 2.0) / 8.0;
        if (trial % 3 == 0) {
            need = floor(need) > 0.0 ? floor(need) : 1.0;
        }
        double want = reference(pairs, n, need), got = hv_weighted_select(pairs, n, need);
        if (isinf(want)) {
            assert_true(isinf(got));
        } else {
            assert_true(got == want);
        }
    }
}

static void test_edges(void **state)
{
    (void)state;
    assert_true(isinf(hv_weighted_select(NULL, 0, 1.0)));
    double one[] = {0.3, 2.0};
    assert_true(hv_weighted_select(one, 1, 2.0) == 0.3); /* met exactly */
    assert_true(isinf(hv_weighted_select(one, 1, 2.5)));
    double three[] = {0.9, 1.0, 0.1, 1.0, 0.5, 0.0};
    assert_true(hv_weighted_select(three, 3, 1.5) == 0.9); /* 0.5 weighs nothing */
    double again[] = {0.9, 1.0, 0.1, 1.0, 0.5, 0.0};
    assert_true(hv_weighted_select(again, 3, 1.0) == 0.1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_vs_sorting),
        cmocka_unit_test(test_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
