/* Exact per-stop pricing: two Pareto knapsack frontiers merged on the stop time
 * (milp_pricing.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/grow_array.h"
#include "hv/milp_clock.h"
#include "hv/milp_pricing.h"
#include "hv/milp_status.h"
#include "hv/plan_status.h"
#include "hv/weighted_select.h"
#include "milp_tunables.h"

void hv_pricer_init(hv_pricer_t *pr)
{
    memset(pr, 0, sizeof *pr);
}

void hv_pricer_free(hv_pricer_t *pr)
{
    free(pr->arena);
    free(pr->cur);
    free(pr->next);
    free(pr->left_front);
    free(pr->sorted);
    free(pr->brk);
    free(pr->pw);
    free(pr->parg);
    free(pr->pref);
    for (int a = 0; a < 2; ++a) {
        free(pr->cross[a].mask);
        free(pr->cross[a].idx);
    }
    memset(pr, 0, sizeof *pr);
}

/* Appends a frontier point; 0 when out of memory or past the deadline (pr->timed_out). */
static int push_pt(hv_pricer_t *pr, double w, double p, int32_t item, int32_t parent, int32_t *idx)
{
    if (pr->t_deadline_s > 0.0 && (pr->points % CLOCK_EVERY_POINTS) == 0 &&
        hv_milp_now_s() >= pr->t_deadline_s) {
        pr->timed_out = 1;
        return 0;
    }
    if (!hv_grow((void **)&pr->arena, &pr->arena_cap, pr->arena_len + 1, sizeof *pr->arena)) {
        return 0;
    }
    pr->arena[pr->arena_len] = (hv_front_pt_t){w, p, item, parent};
    pr->points++;
    *idx = (int32_t)pr->arena_len++;
    return 1;
}

/* Profit density, highest first: good sets are found early and pruning bites sooner.
 * Insertion sort: a stop has a few dozen items at most. */
static void sort_by_density(hv_price_item_t *it, size_t n)
{
    for (size_t i = 1; i < n; ++i) {
        hv_price_item_t x = it[i];
        double dx = x.profit / x.w_ms;
        size_t j = i;
        while (j > 0 && it[j - 1].profit / it[j - 1].w_ms < dx) {
            it[j] = it[j - 1];
            --j;
        }
        it[j] = x;
    }
}

/* Bounds for pruning a frontier point: with max(W_A, W_B) >= l W_A + (1 - l) W_B for any
 * l in [0, 1], a point (W, P) of arm A whose remaining items are k.. gives patterns with
 *     v >= offset + l W - P + sum_{j >= k} min(0, l w_j - p_j) + other_l,
 * other_l = sum over arm B of min(0, (1 - l) w - p); l = 0, 1 and lam are checked, lam the
 * weight that gives the empty pattern its best bound (best_weight()). When arm
 * B's frontier is known (the partner), g(W) = min over its points of max(W_B, W) - P_B is
 * the best arm B can add to a stop time W, and v >= offset + g(W) - P - (profit left). */
typedef struct front_bound {
    double lam; /* the weight l of this arm in the third bound */
    double other0, other_mid, other1;
    const double *pw, *pp, *psuf; /* partner frontier: time, profit, suffix min of w - p */
    const size_t *parg;           /* the partner point attaining psuf[i] */
    const hv_front_ref_t *pref;   /* partner points (arena index, cross-arm cuts held once) */
    size_t pn;                    /* 0: no partner */
} front_bound_t;

/* g(w) (see above) and the partner point attaining it. */
static double partner_best(const front_bound_t *fb, size_t gi, double w, size_t *arg)
{
    double g = INFINITY;
    if (gi < fb->pn) {
        g = fb->psuf[gi];
        *arg = fb->parg[gi];
    }
    if (gi > 0 && w - fb->pp[gi - 1] < g) {
        g = w - fb->pp[gi - 1];
        *arg = gi - 1;
    }
    return g;
}

/* The penalties of the cuts in mask m. */
static double cut_penalty(const double *pen, uint64_t m)
{
    double s = 0.0;
    for (; m != 0; m &= m - 1) {
        s += pen[__builtin_ctzll(m)];
    }
    return s;
}

/* The frontier of one arm's items into pr->cur[0 .. *len), without the points that cannot
 * lead to v < 0. `cross`: the cuts with items on both arms; a point keeps the ones it holds
 * once to the end, since the other arm may complete them (milp_pricing.h). */
static int build_front(hv_pricer_t *pr, const hv_price_item_t *items, size_t n, const double *pen,
                       uint64_t cross, const front_bound_t *fb, double offset, size_t *len)
{
    int cuts = 0; /* some item is in a cut: points carry cut states */
    for (size_t k = 0; k < n && pen != NULL; ++k) {
        cuts |= items[k].cuts != 0;
    }
    double suf0 = 0.0, suf_mid = 0.0, suf1 = 0.0; /* over the items not yet added */
    double lam = fb->lam;
    for (size_t k = 0; k < n; ++k) {
        suf0 -= items[k].profit;
        suf_mid += fmin(0.0, lam * items[k].w_ms - items[k].profit);
        suf1 += fmin(0.0, items[k].w_ms - items[k].profit);
    }
    int32_t e;
    if (!push_pt(pr, 0.0, 0.0, -1, -1, &e) ||
        !hv_grow((void **)&pr->cur, &pr->cur_cap, 1, sizeof *pr->cur)) {
        return 0;
    }
    /* with a partner every point is a whole pattern (with the partner's best point): the
     * best one so far, thr, prunes harder than 0 (both in the caller's shifted terms) */
    double thr = fb->pn > 0 ? pr->rec_v : 0.0;
    size_t ncur = 0, gi = 0, arg = 0;
    while (gi < fb->pn && fb->pw[gi] <= 0.0) {
        ++gi;
    }
    double g0 = fb->pn > 0 ? partner_best(fb, gi, 0.0, &arg) : 0.0;
    if (offset + suf0 + fb->other0 < thr && offset + suf_mid + fb->other_mid < thr &&
        offset + suf1 + fb->other1 < thr && (fb->pn == 0 || offset + g0 + suf0 < thr)) {
        pr->cur[ncur++] = (hv_front_ref_t){0.0, 0.0, e, 0, 0};
        if (fb->pn > 0 && offset + g0 < thr) {
            thr = offset + g0;
            pr->rec_a = fb->pref[arg].idx;
            pr->rec_b = e;
        }
    }
    for (size_t k = 0; k < n && ncur > 0; ++k) {
        suf0 += items[k].profit;
        suf_mid -= fmin(0.0, lam * items[k].w_ms - items[k].profit);
        suf1 -= fmin(0.0, items[k].w_ms - items[k].profit);
        double c0 = offset + suf0 + fb->other0, c_mid = offset + suf_mid + fb->other_mid,
               c1 = offset + suf1 + fb->other1, cg = offset + suf0;
        if (!hv_grow((void **)&pr->next, &pr->next_cap, 2 * ncur, sizeof *pr->next)) {
            return 0;
        }
        double wk = items[k].w_ms, pk = items[k].profit;
        uint64_t mk = cuts ? items[k].cuts : 0;
        uint64_t live = cross; /* the cuts of the items still to come (or of the other arm):
                                  only they can charge */
        for (size_t q = k + 1; q < n && cuts; ++q) {
            live |= items[q].cuts;
        }
        size_t i = 0, j = 0, nn = 0;
        gi = 0;                    /* the first partner point with time > w */
        double last_p = -INFINITY; /* the best profit so far less all penalties it may pay */
        while (i < ncur || j < ncur) {
            double wa = i < ncur ? pr->cur[i].w : INFINITY;
            double pa = i < ncur ? pr->cur[i].p : -INFINITY;
            double wb = INFINITY, pb = -INFINITY;
            uint64_t one = 0, two = 0;
            if (j < ncur) {
                const hv_front_ref_t *c = &pr->cur[j];
                wb = c->w + wk;
                pb = c->p + pk - (mk & c->one ? cut_penalty(pen, mk & c->one) : 0.0);
                two = c->two | (c->one & mk);
                one = (c->one | mk) & ~two;
            }
            int take_a = wa < wb || (wa == wb && pa >= pb);
            double w = take_a ? wa : wb, p = take_a ? pa : pb;
            if (take_a) {
                one = pr->cur[i].one;
                two = pr->cur[i].two;
            }
            one &= live;
            two &= live;
            int32_t from = take_a ? pr->cur[i++].idx : pr->cur[j++].idx;
            if (p <= last_p) {
                continue; /* dominated: no more profit for at least as much time */
            }
            /* a point holding cuts once may still pay them: it dominates later points only
             * by its profit less those penalties (an exact pairwise check cost more time
             * than the points it saved: SOLVER.md's history) */
            double p_safe = one != 0 ? p - cut_penalty(pen, one) : p;
            last_p = p_safe > last_p ? p_safe : last_p;
            if (c0 - p >= thr || c_mid + lam * w - p >= thr || c1 + w - p >= thr) {
                continue;
            }
            double g = 0.0;
            if (fb->pn > 0) { /* w only grows along the merge: walk the partner along */
                while (gi < fb->pn && fb->pw[gi] <= w) {
                    ++gi;
                }
                g = partner_best(fb, gi, w, &arg);
                if (cg + g - p >= thr) {
                    continue;
                }
            }
            int32_t idx = from;
            if (!take_a && !push_pt(pr, w, p, (int32_t)k, from, &idx)) {
                return 0;
            }
            /* thr is a pattern's exact v: with the cross-arm cuts this pair holds once each */
            double vp = offset + g - p, vpen = 0.0;
            if (fb->pn > 0 && cross != 0 && vp < thr) {
                vpen = cut_penalty(pen, fb->pref[arg].one & one);
            }
            if (fb->pn > 0 && vp + vpen < thr) {
                thr = vp + vpen;
                pr->rec_a = fb->pref[arg].idx;
                pr->rec_b = idx;
                pr->rec_pen = vpen;
            }
            pr->next[nn++] = (hv_front_ref_t){w, p, idx, one, two};
        }
        hv_front_ref_t *t = pr->cur;
        size_t tc = pr->cur_cap;
        pr->cur = pr->next;
        pr->cur_cap = pr->next_cap;
        pr->next = t;
        pr->next_cap = tc;
        ncur = nn;
    }
    if (cuts) { /* all items added: only the cross-arm cuts held once still matter */
        size_t nn = 0;
        double last_p = -INFINITY;
        for (size_t i = 0; i < ncur; ++i) {
            hv_front_ref_t c = pr->cur[i];
            c.one &= cross;
            c.two = 0;
            if (c.p <= last_p) {
                continue;
            }
            pr->cur[nn++] = c;
            double p_safe = c.one != 0 ? c.p - cut_penalty(pen, c.one) : c.p;
            last_p = p_safe > last_p ? p_safe : last_p;
        }
        ncur = nn;
    }
    *len = ncur;
    if (fb->pn > 0) {
        pr->rec_v = thr;
    }
    return 1;
}

/* The crude bounds' sums of arm B (see front_bound_t), the arm being built weighing lam. */
static void other_sums(const hv_price_item_t *it, size_t n, double lam, front_bound_t *fb)
{
    memset(fb, 0, sizeof *fb);
    fb->lam = lam;
    for (size_t k = 0; k < n; ++k) {
        fb->other0 += fmin(0.0, it[k].w_ms - it[k].profit);
        fb->other_mid += fmin(0.0, (1.0 - lam) * it[k].w_ms - it[k].profit);
        fb->other1 -= it[k].profit;
    }
}

/* The weight l of arm A that maximises the bound of the empty pattern,
 *     F(l) = sum_A min(0, l w - p) + sum_B min(0, (1 - l) w - p),
 * concave and piecewise linear: its slope falls from F'(0) by w at each breakpoint, and l
 * is the first breakpoint where it is no longer positive (1 if none, 0 if F'(0) <= 0). */
static int best_weight(hv_pricer_t *pr, const hv_price_item_t *a, size_t na,
                       const hv_price_item_t *b, size_t nb, double *lam)
{
    if (!hv_grow((void **)&pr->brk, &pr->brk_cap, 2 * (na + nb) + 2, sizeof *pr->brk)) {
        return 0;
    }
    double slope = 0.0;
    size_t n = 0;
    for (size_t k = 0; k < na; ++k) { /* slope w while l < p / w */
        double r = a[k].profit / a[k].w_ms;
        slope += a[k].w_ms;
        if (r < 1.0) {
            pr->brk[2 * n] = r;
            pr->brk[2 * n++ + 1] = a[k].w_ms;
        }
    }
    for (size_t k = 0; k < nb; ++k) { /* slope -w once l > 1 - p / w */
        double r = 1.0 - b[k].profit / b[k].w_ms;
        if (r <= 0.0) {
            slope -= b[k].w_ms;
        } else {
            pr->brk[2 * n] = r;
            pr->brk[2 * n++ + 1] = b[k].w_ms;
        }
    }
    if (slope <= 0.0) {
        *lam = 0.0;
        return 1;
    }
    double r = hv_weighted_select(pr->brk, n, slope);
    *lam = isfinite(r) ? r : 1.0; /* still rising at the last breakpoint */
    return 1;
}

/* Points pt[0 .. n) grouped by their cross-arm cuts held once: *k classes, class c holds
 * ord[beg[c] .. beg[c + 1]) in frontier (time) order, its cuts in mask[c]. Returns 0 when
 * out of memory. */
static int classify(hv_pricer_t *pr, int arm, const hv_front_ref_t *pt, size_t n, uint64_t cross,
                    size_t *k_out, uint64_t **mask_out, uint32_t **ord_out, uint32_t **beg_out)
{
    hv_cross_scratch_t *cs = &pr->cross[arm];
    if (!hv_grow((void **)&cs->mask, &cs->mask_cap, n + 1, sizeof *cs->mask) ||
        !hv_grow((void **)&cs->idx, &cs->idx_cap, 3 * n + 2, sizeof *cs->idx)) {
        return 0;
    }
    uint32_t *cls = cs->idx, *ord = cs->idx + n, *beg = cs->idx + 2 * n;
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        uint64_t m = pt[i].one & cross;
        size_t c = 0;
        while (c < k && cs->mask[c] != m) {
            ++c;
        }
        if (c == k) {
            cs->mask[k++] = m;
        }
        cls[i] = (uint32_t)c;
    }
    memset(beg, 0, (k + 1) * sizeof *beg);
    for (size_t i = 0; i < n; ++i) {
        beg[cls[i] + 1]++;
    }
    for (size_t c = 0; c < k; ++c) {
        beg[c + 1] += beg[c];
    }
    for (size_t i = 0; i < n; ++i) { /* stable: time order within a class */
        ord[beg[cls[i]]++] = (uint32_t)i;
    }
    for (size_t c = k; c > 0; --c) {
        beg[c] = beg[c - 1];
    }
    beg[0] = 0;
    *k_out = k;
    *mask_out = cs->mask;
    *ord_out = ord;
    *beg_out = beg;
    return 1;
}

/* The merge with cross-arm cuts: a pair pays the cuts both its points hold once, so each
 * pair of classes (classify()) is walked on its own, in time order, with the most
 * profitable point of each class that fits within the time M (profit need not rise with
 * time within a class). Improves *best (and its penalty and points). Returns 0 when out
 * of memory. */
static int cross_merge(hv_pricer_t *pr, const hv_front_ref_t *fa, size_t n_a,
                       const hv_front_ref_t *fb, size_t n_b, uint64_t cross, double offset,
                       const double *pen, double *best, double *best_pen, int32_t *ba, int32_t *bb)
{
    uint64_t *ma, *mb;
    uint32_t *oa, *ob, *ga, *gb;
    size_t ka, kb;
    if (!classify(pr, 0, fa, n_a, cross, &ka, &ma, &oa, &ga) ||
        !classify(pr, 1, fb, n_b, cross, &kb, &mb, &ob, &gb)) {
        return 0;
    }
    for (size_t ca = 0; ca < ka; ++ca) {
        for (size_t cb = 0; cb < kb; ++cb) {
            double pn = cut_penalty(pen, ma[ca] & mb[cb]);
            size_t i = ga[ca], j = gb[cb];
            double pa = -INFINITY, pb = -INFINITY;
            int32_t xa = -1, xb = -1;
            while (i < ga[ca + 1] || j < gb[cb + 1]) {
                double wa = i < ga[ca + 1] ? fa[oa[i]].w : INFINITY;
                double wb = j < gb[cb + 1] ? fb[ob[j]].w : INFINITY;
                double m;
                if (wa <= wb) {
                    const hv_front_ref_t *q = &fa[oa[i++]];
                    m = wa;
                    if (q->p > pa) {
                        pa = q->p;
                        xa = q->idx;
                    }
                } else {
                    const hv_front_ref_t *q = &fb[ob[j++]];
                    m = wb;
                    if (q->p > pb) {
                        pb = q->p;
                        xb = q->idx;
                    }
                }
                double v = offset + m - pa - pb + pn;
                if (xa >= 0 && xb >= 0 && v < *best) {
                    *best = v;
                    *best_pen = pn;
                    *ba = xa;
                    *bb = xb;
                }
            }
        }
    }
    return 1;
}

static size_t collect(const hv_pricer_t *pr, int32_t pt, const hv_price_item_t *items,
                      uint32_t *sel)
{
    size_t n = 0;
    for (; pt >= 0 && pr->arena[pt].item >= 0; pt = pr->arena[pt].parent) {
        sel[n++] = items[pr->arena[pt].item].fruit;
    }
    return n;
}

hv_status_t hv_pricer_best(hv_pricer_t *pr, const hv_price_item_t *left, size_t nl,
                           const hv_price_item_t *right, size_t nr, double offset_ms,
                           const double *pen_ms, double v_bound, double *v_out, uint32_t *sel,
                           size_t *n_sel, double *time_ms)
{
    *v_out = v_bound;
    /* pruning against v_bound instead of 0 is pruning against 0 with the offset raised */
    double off_p = offset_ms - v_bound;
    *n_sel = 0;
    *time_ms = -1.0;
    pr->calls++;
    pr->timed_out = 0;
    /* arm A, the one with fewer items, first: its small frontier then bounds arm B's */
    const hv_price_item_t *ia = nl <= nr ? left : right, *ib = nl <= nr ? right : left;
    size_t na = nl <= nr ? nl : nr, nb = nl <= nr ? nr : nl;
    if (!hv_grow((void **)&pr->sorted, &pr->sorted_cap, na + nb + 1, sizeof *pr->sorted)) {
        return HV_ERR_PLAN_NOMEM;
    }
    hv_price_item_t *sa = pr->sorted, *sb = pr->sorted + na;
    if (na) {
        memcpy(sa, ia, na * sizeof *sa);
    }
    if (nb) {
        memcpy(sb, ib, nb * sizeof *sb);
    }
    double lam;
    if (!best_weight(pr, sa, na, sb, nb, &lam)) {
        return HV_ERR_PLAN_NOMEM;
    }
    front_bound_t fa, fb;
    other_sums(sb, nb, lam, &fa);
    other_sums(sa, na, 1.0 - lam, &fb);
    /* the empty point of arm A bounds every pattern: most stops end here */
    if (off_p + fb.other1 + fa.other0 >= 0.0 || off_p + fb.other0 + fa.other1 >= 0.0 ||
        off_p + fb.other_mid + fa.other_mid >= 0.0) {
        return HV_OK;
    }
    sort_by_density(sa, na);
    sort_by_density(sb, nb);
    uint64_t cut_a = 0, cut_b = 0; /* the cuts of each arm's items */
    for (size_t k = 0; k < na && pen_ms != NULL; ++k) {
        cut_a |= sa[k].cuts;
    }
    for (size_t k = 0; k < nb && pen_ms != NULL; ++k) {
        cut_b |= sb[k].cuts;
    }
    uint64_t cross = cut_a & cut_b;
    pr->arena_len = 0;
    size_t n_a = 0, n_b = 0;
    if (!build_front(pr, sa, na, pen_ms, cross, &fa, off_p, &n_a)) {
        return pr->timed_out ? HV_ERR_MILP_DEADLINE : HV_ERR_PLAN_NOMEM;
    }
    if (n_a == 0) {
        return HV_OK; /* no point of arm A can be part of a pattern with v < 0 */
    }
    if (!hv_grow((void **)&pr->left_front, &pr->left_cap, n_a, sizeof *pr->left_front) ||
        !hv_grow((void **)&pr->pw, &pr->pw_cap, 3 * n_a, sizeof *pr->pw)) {
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(pr->left_front, pr->cur, n_a * sizeof *pr->cur);
    if (!hv_grow((void **)&pr->parg, &pr->parg_cap, n_a, sizeof *pr->parg) ||
        !hv_grow((void **)&pr->pref, &pr->pref_cap, n_a, sizeof *pr->pref)) {
        return HV_ERR_PLAN_NOMEM;
    }
    /* the partner bound g needs profit rising with time: with cross-arm cuts the frontier
     * keeps points an earlier one beats on profit alone, which g can leave out */
    double *pw = pr->pw, *pp = pr->pw + n_a, *psuf = pr->pw + 2 * n_a;
    size_t n_g = 0;
    for (size_t i = 0; i < n_a; ++i) {
        if (n_g > 0 && pr->left_front[i].p <= pp[n_g - 1]) {
            continue;
        }
        pw[n_g] = pr->left_front[i].w;
        pp[n_g] = pr->left_front[i].p;
        pr->pref[n_g++] = pr->left_front[i];
    }
    for (size_t i = n_g; i-- > 0;) {
        int later = i + 1 < n_g && psuf[i + 1] < pw[i] - pp[i];
        psuf[i] = later ? psuf[i + 1] : pw[i] - pp[i];
        pr->parg[i] = later ? pr->parg[i + 1] : i;
    }
    fb.pw = pw;
    fb.pp = pp;
    fb.psuf = psuf;
    fb.parg = pr->parg;
    fb.pref = pr->pref;
    fb.pn = n_g;
    pr->rec_v = 0.0;
    pr->rec_a = pr->rec_b = -1;
    pr->rec_pen = 0.0;
    if (!build_front(pr, sb, nb, pen_ms, cross, &fb, off_p, &n_b)) {
        return pr->timed_out ? HV_ERR_MILP_DEADLINE : HV_ERR_PLAN_NOMEM;
    }
    const hv_front_ref_t *fa_pts = pr->left_front, *fb_pts = pr->cur;
    double best = v_bound, best_pen = 0.0;
    int32_t ba = -1, bb = -1;
    if (cross != 0 && !cross_merge(pr, fa_pts, n_a, fb_pts, n_b, cross, offset_ms, pen_ms, &best,
                                   &best_pen, &ba, &bb)) {
        return HV_ERR_PLAN_NOMEM;
    }
    /* walk both frontiers in time order: at each time M the most profitable point of each
     * arm that fits within M */
    size_t i = 0, j = 0;
    long ia_pt = -1, ib_pt = -1;
    while (cross == 0 && (i < n_a || j < n_b)) {
        double wa = i < n_a ? fa_pts[i].w : INFINITY;
        double wb = j < n_b ? fb_pts[j].w : INFINITY;
        double m;
        if (wa <= wb) {
            m = wa;
            ia_pt = (long)i++;
        } else {
            m = wb;
            ib_pt = (long)j++;
        }
        if (ia_pt < 0 || ib_pt < 0) {
            continue;
        }
        double v = offset_ms + m - fa_pts[ia_pt].p - fb_pts[ib_pt].p;
        if (v < best) {
            best = v;
            ba = fa_pts[ia_pt].idx;
            bb = fb_pts[ib_pt].idx;
        }
    }
    if (pr->rec_b >= 0) { /* the best pattern seen while building, maybe pruned since */
        const hv_front_pt_t *a = &pr->arena[pr->rec_a], *c = &pr->arena[pr->rec_b];
        double v = offset_ms + fmax(a->w, c->w) - a->p - c->p + pr->rec_pen;
        if (v < best) {
            best = v;
            best_pen = pr->rec_pen;
            ba = pr->rec_a;
            bb = pr->rec_b;
        }
    }
    if (ba < 0) {
        return HV_OK;
    }
    size_t n = collect(pr, ba, sa, sel);
    n += collect(pr, bb, sb, sel + n);
    double w = fmax(pr->arena[ba].w, pr->arena[bb].w);
    *time_ms = w;
    *v_out = offset_ms + w - pr->arena[ba].p - pr->arena[bb].p + best_pen;
    *n_sel = n;
    return HV_OK;
}
