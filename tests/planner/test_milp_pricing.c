/* Exact per-stop pricing (milp_pricing.h) against brute force, hand-computed cases and
 * work space reuse.
 *
 * The brute force takes every subset pair (L, R) of the left and right items, so it is the
 * definition of the minimum itself. Times are whole ms; profits and offsets are either
 * multiples of 1/4 (every sum exact in double, so ties and v == v_bound are decided
 * exactly) or arbitrary doubles (checked within 1e-6, decisions skipped when that close).
 * Fruit ids are random and unique, never the item indices, so sel is checked for ids.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "hv/milp_clock.h"
#include "hv/milp_pricing.h"
#include "hv/milp_status.h"

#define MAXN       40 /* items per side */
#define BRUTE_SIDE 16 /* brute force subset tables per side */
#define SENT       0xdeadbeefu
#define TOL        1e-6

typedef struct inst {
    hv_price_item_t l[MAXN], r[MAXN];
    size_t nl, nr;
    double offset;
    const double *pen; /* subset-row cut penalties by cut bit, NULL: no cuts */
    double pen_store[64];
} inst_t;

typedef struct res {
    hv_status_t st;
    double v, time;
    size_t n_sel;
    uint32_t sel[2 * MAXN + 4]; /* + 4 sentinels past the nl + nr allowed entries */
} res_t;

/* item k of the left items followed by the right ones */
static const hv_price_item_t *item(const inst_t *in, size_t k)
{
    return k < in->nl ? &in->l[k] : &in->r[k - in->nl];
}

static uint64_t xs64(uint64_t *s) /* xorshift64 */
{
    uint64_t x = *s;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return *s = x;
}

static double unif(uint64_t *s) /* [0, 1) */
{
    return (double)(xs64(s) >> 11) * 0x1p-53;
}

/* w in [500, 9000] whole ms; profit in (0, 9000], some == w, some copies of the previous
 * item (ties between frontier points); offset in [-3000, 6000]. */
static void gen(uint64_t *s, inst_t *in, size_t nl, size_t nr, int quarter)
{
    memset(in, 0, sizeof *in);
    in->nl = nl;
    in->nr = nr;
    for (size_t k = 0; k < nl + nr; ++k) {
        hv_price_item_t *it = k < nl ? &in->l[k] : &in->r[k - nl];
        unsigned kind = (unsigned)(xs64(s) % 8);
        if (kind == 0 && k > 0 && k != nl) {
            *it = it[-1]; /* same side's previous item */
        } else {
            it->w_ms = 500.0 + (double)(xs64(s) % 8501);
            it->profit = kind == 1 ? it->w_ms
                         : quarter ? (double)(1 + xs64(s) % 36000) / 4.0
                                   : 9000.0 * (1.0 - unif(s));
        }
        it->fruit = (uint32_t)(xs64(s) % 100000) * 128 + (uint32_t)k; /* unique: k < 128 */
    }
    in->offset = quarter ? -3000.0 + (double)(xs64(s) % 36001) / 4.0 : -3000.0 + 9000.0 * unif(s);
}

/* The penalties the items it[0 .. n) pay together: pen[c] for every cut c holding two or
 * more of them. */
static double set_penalty(const double *pen, const hv_price_item_t *const *it, size_t n)
{
    double s = 0.0;
    for (int c = 0; c < 64 && pen != NULL; ++c) {
        int cnt = 0;
        for (size_t k = 0; k < n; ++k) {
            cnt += (int)((it[k]->cuts >> c) & 1u);
        }
        s += cnt >= 2 ? pen[c] : 0.0;
    }
    return s;
}

/* Time and profit (net of the penalties of the cuts it holds two of) of every subset m of
 * it[0 .. n), and the cuts it holds exactly one item of. */
static void subset_sums(const hv_price_item_t *it, size_t n, const double *pen, double *w,
                        double *p, uint64_t *one)
{
    w[0] = p[0] = 0.0;
    one[0] = 0;
    for (size_t m = 1; m < ((size_t)1 << n); ++m) {
        size_t low = (size_t)__builtin_ctzll(m);
        w[m] = w[m & (m - 1)] + it[low].w_ms;
        p[m] = p[m & (m - 1)] + it[low].profit;
    }
    if (pen == NULL) {
        return;
    }
    for (size_t m = 1; m < ((size_t)1 << n); ++m) {
        const hv_price_item_t *set[BRUTE_SIDE];
        size_t k = 0;
        for (size_t i = 0; i < n; ++i) {
            if ((m >> i) & 1u) {
                set[k++] = &it[i];
            }
        }
        p[m] -= set_penalty(pen, set, k);
        uint64_t once = 0, twice = 0;
        for (size_t i = 0; i < k; ++i) {
            twice |= once & set[i]->cuts;
            once ^= set[i]->cuts & ~twice;
        }
        one[m] = once & ~twice;
    }
}

/* min over all (L, R) of offset + max(W(L), W(R)) - P(L) - P(R); n per side <= 16 */
static double brute(const inst_t *in)
{
    static double wl[1 << BRUTE_SIDE], pl[1 << BRUTE_SIDE], wr[1 << BRUTE_SIDE],
        pr[1 << BRUTE_SIDE];
    static uint64_t ol[1 << BRUTE_SIDE], or_[1 << BRUTE_SIDE];
    assert_true(in->nl <= BRUTE_SIDE && in->nr <= BRUTE_SIDE);
    subset_sums(in->l, in->nl, in->pen, wl, pl, ol);
    subset_sums(in->r, in->nr, in->pen, wr, pr, or_);
    double best = INFINITY;
    for (size_t a = 0; a < ((size_t)1 << in->nl); ++a) {
        for (size_t b = 0; b < ((size_t)1 << in->nr); ++b) {
            double cross = 0.0; /* a cut with one item in each of L and R */
            for (uint64_t m = ol[a] & or_[b]; m != 0 && in->pen != NULL; m &= m - 1) {
                cross += in->pen[__builtin_ctzll(m)];
            }
            best = fmin(best, in->offset + fmax(wl[a], wr[b]) - (pl[a] + pr[b]) + cross);
        }
    }
    return best;
}

static void run(hv_pricer_t *pr, const inst_t *in, double vb, res_t *r)
{
    for (size_t i = 0; i < sizeof r->sel / sizeof r->sel[0]; ++i) {
        r->sel[i] = SENT;
    }
    r->n_sel = 12345;
    r->v = r->time = NAN;
    r->st = hv_pricer_best(pr, in->l, in->nl, in->r, in->nr, in->offset, in->pen, vb, &r->v, r->sel,
                           &r->n_sel, &r->time);
}

static void dump(const inst_t *in, double vb, double bmin, const res_t *r, const char *why)
{
    print_message("FAIL: %s\n  offset=%.17g v_bound=%.17g expected_min=%.17g\n", why, in->offset,
                  vb, bmin);
    for (size_t k = 0; k < in->nl + in->nr; ++k) {
        const hv_price_item_t *it = item(in, k);
        print_message("  %s fruit=%u w=%.17g p=%.17g\n", k < in->nl ? "L" : "R",
                      (unsigned)it->fruit, it->w_ms, it->profit);
    }
    print_message("  got st=%d v=%.17g time=%.17g n_sel=%zu sel:", (int)r->st, r->v, r->time,
                  r->n_sel);
    for (size_t i = 0; i < r->n_sel && i < in->nl + in->nr; ++i) {
        print_message(" %u", (unsigned)r->sel[i]);
    }
    print_message("\n");
}

#define REQUIRE(cond, why)                                                                         \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            return (why);                                                                          \
        }                                                                                          \
    } while (0)

/* The contract check. bmin: the true minimum, or NAN when unknown; exact: sums are exact,
 * so the found-or-not decision must hold even at bmin == v_bound. Returns the failure
 * reason, NULL when all holds. */
static const char *check(const inst_t *in, double vb, double bmin, int exact, const res_t *r)
{
    size_t n = in->nl + in->nr;
    REQUIRE(r->st == HV_OK, "status not HV_OK");
    for (size_t i = n; i < n + 4; ++i) {
        REQUIRE(r->sel[i] == SENT, "wrote past sel[nl + nr)");
    }
    int found = r->time >= 0.0;
    if (!isnan(bmin) && (exact || fabs(bmin - vb) > TOL)) {
        REQUIRE(!found || bmin < vb, "returned a pattern though min >= v_bound");
        REQUIRE(found || bmin >= vb, "missed a pattern < v_bound");
    }
    if (!found) {
        REQUIRE(r->time == -1.0 && r->v == vb && r->n_sel == 0,
                "not-found result is not (v_bound, n_sel 0, time -1)");
        return NULL;
    }
    REQUIRE(r->v < vb, "found v not below v_bound");
    REQUIRE(isnan(bmin) || fabs(r->v - bmin) <= TOL, "v is not the minimum");
    REQUIRE(r->n_sel <= n, "n_sel > nl + nr");
    double wl = 0.0, wr = 0.0, p = 0.0;
    const hv_price_item_t *set[2 * MAXN];
    for (size_t i = 0; i < r->n_sel; ++i) {
        for (size_t j = 0; j < i; ++j) {
            REQUIRE(r->sel[j] != r->sel[i], "fruit selected twice");
        }
        size_t k = 0;
        while (k < n && item(in, k)->fruit != r->sel[i]) {
            ++k;
        }
        REQUIRE(k < n, "unknown fruit id in sel");
        *(k < in->nl ? &wl : &wr) += item(in, k)->w_ms;
        p += item(in, k)->profit;
        set[i] = item(in, k);
    }
    p -= set_penalty(in->pen, set, r->n_sel);
    REQUIRE(r->time == fmax(wl, wr), "time_ms != max(W(L), W(R)) of sel");
    REQUIRE(fabs(in->offset + r->time - p - r->v) <= TOL,
            "v != offset + time - P(sel) + penalties(sel)");
    return NULL;
}

static int failures;

static void expect_ok(const inst_t *in, double vb, double bmin, int exact, const res_t *r)
{
    const char *why = check(in, vb, bmin, exact, r);
    if (why != NULL && failures++ < 5) {
        dump(in, vb, bmin, r, why);
    }
}

/* 1. 4000 random instances (half quarter-ms exact, half arbitrary doubles), 0..7 items per
 * side, each priced at v_bound 0, between the min and 0, just above the min, at the min
 * (exact half only) and below it. */
static void test_random_vs_brute_force(void **state)
{
    hv_pricer_t *pr = *state;
    uint64_t s = 0x243f6a8885a308d3ull;
    long found = 0, not_found = 0, calls = 0;
    failures = 0;
    for (int t = 0; t < 4000; ++t) {
        int exact = t % 2 == 0;
        inst_t in;
        gen(&s, &in, (size_t)(xs64(&s) % 8), (size_t)(xs64(&s) % 8), exact);
        double bmin = brute(&in), eps = exact ? 0.25 : 1e-3;
        /* 0, below the min, between it and 0, just above it, at it (exact sums only) */
        double vbs[5] = {0.0, fmin(bmin, 0.0) - eps, bmin / 2.0, bmin + eps, bmin};
        for (size_t i = 0; i < 5; ++i) {
            if (vbs[i] > 0.0 || (i >= 2 && bmin >= 0.0) || (i == 4 && !exact)) {
                continue;
            }
            res_t r;
            run(pr, &in, vbs[i], &r);
            ++calls;
            expect_ok(&in, vbs[i], bmin, exact, &r);
            *(r.time >= 0.0 ? &found : &not_found) += 1;
        }
    }
    print_message("random: 4000 instances, %ld calls, %ld found, %ld not found\n", calls, found,
                  not_found);
    assert_int_equal(failures, 0);
    assert_true(found > 4000 && not_found > 4000); /* both outcomes well exercised */
    assert_true(pr->calls == (unsigned long long)calls);
}

/* Random subset-row cuts on `in`: 1-8 cuts, each on 2-3 items, of one side or (cross) of
 * both; penalties in quarter ms up to 3000. */
static void gen_cuts(uint64_t *s, inst_t *in, int cross)
{
    in->pen = in->pen_store;
    int n_cut = 1 + (int)(xs64(s) % 8);
    for (int c = 0; c < n_cut; ++c) {
        int left = xs64(s) % 2 == 0;
        in->pen_store[c] = (double)(xs64(s) % 12001) / 4.0;
        for (int m = 2 + (int)(xs64(s) % 2); m > 0; --m) {
            if (cross) {
                left = xs64(s) % 2 == 0;
            }
            size_t n = left ? in->nl : in->nr;
            hv_price_item_t *it = left ? in->l : in->r;
            if (n > 0) {
                it[xs64(s) % n].cuts |= (uint64_t)1 << c;
            }
        }
    }
}

/* 1b. The same with subset-row cut penalties: 4000 random instances with 1-8 cuts each,
 * every other one with cuts on items of both arms. */
static void test_cuts_vs_brute_force(void **state)
{
    hv_pricer_t *pr = *state;
    uint64_t s = 0xa4093822299f31d0ull;
    long found = 0, calls = 0, cut_bites = 0, cross_bites = 0;
    failures = 0;
    for (int t = 0; t < 4000; ++t) {
        inst_t in;
        gen(&s, &in, (size_t)(xs64(&s) % 8), (size_t)(xs64(&s) % 8), 1);
        double plain = brute(&in);
        gen_cuts(&s, &in, t % 2);
        double bmin = brute(&in);
        cut_bites += bmin > plain; /* the cuts changed the minimum */
        cross_bites += t % 2 && bmin > plain;
        double vbs[3] = {0.0, bmin / 2.0, bmin};
        for (size_t i = 0; i < 3; ++i) {
            if (i >= 1 && bmin >= 0.0) {
                continue;
            }
            res_t r;
            run(pr, &in, vbs[i], &r);
            ++calls;
            expect_ok(&in, vbs[i], bmin, 1, &r);
            found += r.time >= 0.0;
        }
    }
    print_message("cuts: 4000 instances, %ld calls, %ld found, minimum raised by cuts on %ld "
                  "(%ld with cross-arm cuts)\n",
                  calls, found, cut_bites, cross_bites);
    assert_int_equal(failures, 0);
    assert_true(found > 2000 && cut_bites > 500 && cross_bites > 250); /* penalties matter */
}

static inst_t hand(double wl, double pl, double wr, double pr_, double offset)
{
    inst_t in;
    memset(&in, 0, sizeof in);
    in.l[0] = (hv_price_item_t){11, wl, pl, 0};
    in.r[0] = (hv_price_item_t){22, wr, pr_, 0};
    in.nl = in.nr = 1;
    in.offset = offset;
    return in;
}

/* Prices `in` at vb and wants exactly v, time and n fruits (n == 2: fruits 11 and 22). */
static void expect(hv_pricer_t *pr, const inst_t *in, double vb, double v, double time, size_t n)
{
    res_t r;
    run(pr, in, vb, &r);
    if (r.st != HV_OK || r.v != v || r.time != time || r.n_sel != n ||
        (n == 2 && !((r.sel[0] == 11 && r.sel[1] == 22) || (r.sel[0] == 22 && r.sel[1] == 11)))) {
        dump(in, vb, v, &r, "hand case (expected_min is the expected v)");
        fail();
    }
}

/* 2. Hand-computed cases (time -1: nothing found). */
static void test_hand_cases(void **state)
{
    hv_pricer_t *pr = *state;
    /* balanced: best is both, 5000 + 1000 - 3000 = 3000 > 0: nothing */
    inst_t in = hand(1000, 1500, 1000, 1500, 5000);
    expect(pr, &in, 0.0, 0.0, -1.0, 0);
    /* offset 500: both, 500 + 1000 - 3000 = -1500 (one alone: 500 + 1000 - 1500 = 0) */
    in.offset = 500;
    expect(pr, &in, 0.0, -1500.0, 1000.0, 2);
    expect(pr, &in, -1499.75, -1500.0, 1000.0, 2);
    expect(pr, &in, -1500.0, -1500.0, -1.0, 0); /* v == v_bound is not below it */
    /* the right item (p < w, worthless alone) rides free under the left arm's 4000 ms:
     * {} 500, {L} 500 + 4000 - 5000 = -500, {R} 1300, {L, R} 500 + 4000 - 5200 = -700 */
    in = hand(4000, 5000, 1000, 200, 500);
    expect(pr, &in, 0.0, -700.0, 4000.0, 2);
    expect(pr, &in, -600.0, -700.0, 4000.0, 2);
    in = hand(1000, 200, 4000, 5000, 500); /* mirrored: the pricer orders arms by size */
    expect(pr, &in, 0.0, -700.0, 4000.0, 2);
    /* the brief's variant, offset -1500 and p_L = 3000: the empty pattern (-1500) is best */
    in = hand(4000, 3000, 1000, 200, -1500);
    expect(pr, &in, 0.0, -1500.0, 0.0, 0);
    /* no items: the empty pattern, v = offset, time 0, when below v_bound */
    in.nl = in.nr = 0;
    in.offset = -250.0;
    expect(pr, &in, 0.0, -250.0, 0.0, 0);
    expect(pr, &in, -250.0, -250.0, -1.0, 0);
    in.offset = 0.0;
    expect(pr, &in, 0.0, 0.0, -1.0, 0);
}

static void sort_sel(res_t *r) /* insertion sort of sel[0 .. n_sel) */
{
    for (size_t i = 1; i < r->n_sel && i < 2 * MAXN; ++i) {
        for (size_t j = i; j > 0 && r->sel[j] < r->sel[j - 1]; --j) {
            uint32_t x = r->sel[j];
            r->sel[j] = r->sel[j - 1], r->sel[j - 1] = x;
        }
    }
}

/* 3. One pricer over calls of varying sizes (up to 40 items a side, arms swapped, bounds
 * varied) must agree with a fresh pricer per call: same v, time and selection; against
 * brute force where n <= 16, and the closed form offset + sum min(0, w - p) when one side
 * is empty. */
static void test_workspace_reuse(void **state)
{
    hv_pricer_t *pr = *state;
    static const size_t fixed[][2] = {{40, 0}, {2, 1},   {0, 40}, {40, 5}, {0, 0}, {5, 40},
                                      {8, 8},  {40, 40}, {1, 0},  {40, 2}, {3, 3}};
    size_t n_fixed = sizeof fixed / sizeof fixed[0];
    uint64_t s = 0x13198a2e03707344ull;
    failures = 0;
    unsigned long long calls = 0, found = 0, known = 0;
    for (size_t t = 0; t < 300; ++t) {
        size_t nl = t < n_fixed ? fixed[t][0] : xs64(&s) % 4 == 0 ? MAXN : xs64(&s) % 9;
        size_t nr = t < n_fixed ? fixed[t][1] : xs64(&s) % 4 == 0 ? MAXN : xs64(&s) % 9;
        inst_t in;
        gen(&s, &in, nl, nr, 1);
        double vb = t % 3 == 0 ? 0.0 : -(double)(xs64(&s) % 4000);
        double bmin = NAN;
        if (nl + nr <= 16) {
            bmin = brute(&in);
        } else if (nl == 0 || nr == 0) {
            const hv_price_item_t *it = nl ? in.l : in.r;
            bmin = in.offset;
            for (size_t k = 0; k < nl + nr; ++k) {
                bmin += fmin(0.0, it[k].w_ms - it[k].profit);
            }
        }
        res_t a, b;
        run(pr, &in, vb, &a);
        ++calls;
        hv_pricer_t fresh;
        hv_pricer_init(&fresh);
        run(&fresh, &in, vb, &b);
        hv_pricer_free(&fresh);
        expect_ok(&in, vb, bmin, 1, &a);
        expect_ok(&in, vb, bmin, 1, &b);
        found += a.time >= 0.0;
        known += !isnan(bmin);
        sort_sel(&a); /* same selection as a set */
        sort_sel(&b);
        if ((a.v != b.v || a.time != b.time || a.n_sel != b.n_sel ||
             (a.n_sel <= 2 * MAXN && memcmp(a.sel, b.sel, a.n_sel * sizeof a.sel[0]) != 0)) &&
            failures++ < 5) {
            dump(&in, vb, bmin, &a, "reused pricer differs from a fresh one (reused shown)");
            dump(&in, vb, bmin, &b, "... fresh pricer's result");
        }
    }
    print_message("reuse: %llu calls, %llu found, %llu with a known minimum\n", calls, found,
                  known);
    assert_int_equal(failures, 0);
    assert_true(pr->calls == calls);
    hv_pricer_free(pr);
    assert_null(pr->arena); /* free leaves it empty (teardown frees it again: harmless) */
}

/* Each test gets its own pricer, freed even when the test fails. */
/* A deadline already passed stops a call that must build frontiers, and says so; with
 * none (or a later one) the same call prices the stop exactly. */
static void test_deadline(void **state)
{
    hv_pricer_t *pr = *state;
    uint64_t s = 0x452821e638d01377ull;
    inst_t in;
    do {
        gen(&s, &in, 7, 7, 1);
    } while (brute(&in) >= -1.0); /* a stop worth pricing */
    res_t r;
    pr->t_deadline_s = hv_milp_now_s() - 1.0;
    run(pr, &in, 0.0, &r);
    assert_int_equal(r.st, HV_ERR_MILP_DEADLINE);
    pr->t_deadline_s = hv_milp_now_s() + 3600.0;
    run(pr, &in, 0.0, &r);
    assert_int_equal(r.st, HV_OK);
    assert_true(fabs(r.v - brute(&in)) < 1e-6);
    pr->t_deadline_s = 0.0;
    run(pr, &in, 0.0, &r);
    assert_int_equal(r.st, HV_OK);
    assert_true(fabs(r.v - brute(&in)) < 1e-6);
}

static int setup(void **state)
{
    hv_pricer_t *pr = *state = malloc(sizeof *pr);
    if (pr != NULL) {
        hv_pricer_init(pr);
    }
    return pr != NULL ? 0 : -1;
}

static int teardown(void **state)
{
    hv_pricer_free(*state);
    free(*state);
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_random_vs_brute_force, setup, teardown),
        cmocka_unit_test_setup_teardown(test_cuts_vs_brute_force, setup, teardown),
        cmocka_unit_test_setup_teardown(test_hand_cases, setup, teardown),
        cmocka_unit_test_setup_teardown(test_workspace_reuse, setup, teardown),
        cmocka_unit_test_setup_teardown(test_deadline, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
