/* Local search for stop-and-harvest plans (milp_local_search.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_local_search.h"
#include "hv/plan_status.h"

#define LS_EPS  1e-9     /* s: smaller improvements are rounding noise */
#define LS_NONE SIZE_MAX /* no pair (unreachable fruit) */

typedef struct ls {
    const hv_instance_t *in;
    size_t *cur;     /* pair index of each fruit, LS_NONE for unreachable fruit */
    size_t *best;    /* best plan seen (pair indices) */
    double *load[2]; /* s, per stop: pick time of the left [0] and right [1] arm */
    uint32_t *cnt;   /* fruits per stop */
    size_t *list;    /* scratch: fruits of one stop */
    size_t *undo;    /* scratch: (fruit, old pair) pairs of a tentative compound move */
    size_t n_undo;
    uint64_t rng;
} ls_t;

void hv_ls_options_default(hv_ls_options_t *opt)
{
    opt->kicks = 60;
    opt->shift_max = 15;
    opt->seed = 0x9e3779b97f4a7c15ull;
}

static uint32_t rnd(ls_t *s, uint32_t n)
{
    /* xorshift64*: deterministic, state in the search, no global RNG */
    s->rng ^= s->rng >> 12;
    s->rng ^= s->rng << 25;
    s->rng ^= s->rng >> 27;
    return (uint32_t)(((s->rng * 0x2545f4914f6cdd1dull) >> 33) % n);
}

static uint32_t stop_of(const ls_t *s, size_t f)
{
    return s->in->pairs[s->cur[f]].stop;
}
static int side_of(const ls_t *s, size_t f)
{
    return s->in->fruits[f].side == HV_SIDE_RIGHT;
}

/* Pair index of (f, p), or LS_NONE. Pairs of a fruit are sorted by stop. */
static size_t find_pair(const hv_instance_t *in, size_t f, uint32_t p)
{
    size_t lo = in->fruit_begin[f], hi = in->fruit_begin[f + 1];
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (in->pairs[mid].stop < p) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return (lo < in->fruit_begin[f + 1] && in->pairs[lo].stop == p) ? lo : LS_NONE;
}

/* Time of stop p (s) after adding dl / dr to the arms' loads and dc to its fruit count. */
static double stop_time(const ls_t *s, uint32_t p, double dl, double dr, int dc)
{
    if ((int)s->cnt[p] + dc <= 0) {
        return 0.0;
    }
    return fmax(s->load[0][p] + dl, s->load[1][p] + dr) + s->in->stop_penalty_s;
}

static void recompute(ls_t *s)
{
    const hv_instance_t *in = s->in;
    for (size_t p = 0; p < in->n_stops; ++p) {
        s->load[0][p] = s->load[1][p] = 0.0;
        s->cnt[p] = 0;
    }
    for (size_t f = 0; f < in->n_fruits; ++f) {
        if (s->cur[f] != LS_NONE) {
            const hv_pair_t *pr = &in->pairs[s->cur[f]];
            s->load[side_of(s, f)][pr->stop] += pr->cost_s;
            s->cnt[pr->stop]++;
        }
    }
}

static double total(const ls_t *s)
{
    double t = s->in->travel_time_s;
    for (size_t p = 0; p < s->in->n_stops; ++p) {
        t += stop_time(s, (uint32_t)p, 0, 0, 0);
    }
    return t;
}

/* Change of T when fruit f moves to pair k. */
static double move_delta(const ls_t *s, size_t f, size_t k)
{
    const hv_pair_t *from = &s->in->pairs[s->cur[f]], *to = &s->in->pairs[k];
    if (from->stop == to->stop) {
        return 0.0;
    }
    int sd = side_of(s, f);
    double after = stop_time(s, from->stop, sd ? 0 : -from->cost_s, sd ? -from->cost_s : 0, -1) +
                   stop_time(s, to->stop, sd ? 0 : to->cost_s, sd ? to->cost_s : 0, +1);
    return after - stop_time(s, from->stop, 0, 0, 0) - stop_time(s, to->stop, 0, 0, 0);
}

static void move(ls_t *s, size_t f, size_t k, int record)
{
    const hv_pair_t *from = &s->in->pairs[s->cur[f]], *to = &s->in->pairs[k];
    int sd = side_of(s, f);
    if (record) {
        s->undo[2 * s->n_undo] = f;
        s->undo[2 * s->n_undo + 1] = s->cur[f];
        s->n_undo++;
    }
    s->load[sd][from->stop] -= from->cost_s;
    s->cnt[from->stop]--;
    s->load[sd][to->stop] += to->cost_s;
    s->cnt[to->stop]++;
    s->cur[f] = k;
}

static void undo_all(ls_t *s)
{
    while (s->n_undo > 0) {
        s->n_undo--;
        move(s, s->undo[2 * s->n_undo], s->undo[2 * s->n_undo + 1], 0);
    }
}

/* Best pair of f at an open stop other than `avoid` (LS_NONE if none); *delta its change. */
static size_t best_open(const ls_t *s, size_t f, uint32_t avoid, double *delta)
{
    size_t best = LS_NONE;
    double bd = INFINITY;
    for (size_t k = s->in->fruit_begin[f]; k < s->in->fruit_begin[f + 1]; ++k) {
        uint32_t p = s->in->pairs[k].stop;
        if (p == avoid || s->cnt[p] == 0) {
            continue;
        }
        double d = move_delta(s, f, k);
        if (d < bd) {
            bd = d;
            best = k;
        }
    }
    *delta = bd;
    return best;
}

static int relocate_pass(ls_t *s)
{
    int improved = 0;
    for (size_t f = 0; f < s->in->n_fruits; ++f) {
        if (s->cur[f] == LS_NONE) {
            continue;
        }
        size_t bk = LS_NONE;
        double bd = -LS_EPS;
        for (size_t k = s->in->fruit_begin[f]; k < s->in->fruit_begin[f + 1]; ++k) {
            double d = move_delta(s, f, k);
            if (d < bd) {
                bd = d;
                bk = k;
            }
        }
        if (bk != LS_NONE) {
            move(s, f, bk, 0);
            improved = 1;
        }
    }
    return improved;
}

/* f at p goes to q, g at q goes to p. */
static int exchange_pass(ls_t *s)
{
    const hv_instance_t *in = s->in;
    int improved = 0;
    for (size_t f = 0; f < in->n_fruits; ++f) {
        if (s->cur[f] == LS_NONE) {
            continue;
        }
        for (size_t g = f + 1; g < in->n_fruits; ++g) {
            if (s->cur[g] == LS_NONE) {
                continue;
            }
            uint32_t p = stop_of(s, f), q = stop_of(s, g);
            if (p == q || q < in->pairs[in->fruit_begin[f]].stop ||
                q > in->pairs[in->fruit_begin[f + 1] - 1].stop) {
                continue; /* q outside f's reach window: no binary searches */
            }
            size_t kf = find_pair(in, f, q), kg = find_pair(in, g, p);
            if (kf == LS_NONE || kg == LS_NONE) {
                continue;
            }
            double d[2][2] = {{0, 0}, {0, 0}}; /* [stop p / q][side] */
            int sf = side_of(s, f), sg = side_of(s, g);
            d[0][sf] -= in->pairs[s->cur[f]].cost_s;
            d[0][sg] += in->pairs[kg].cost_s;
            d[1][sg] -= in->pairs[s->cur[g]].cost_s;
            d[1][sf] += in->pairs[kf].cost_s;
            double delta = stop_time(s, p, d[0][0], d[0][1], 0) +
                           stop_time(s, q, d[1][0], d[1][1], 0) - stop_time(s, p, 0, 0, 0) -
                           stop_time(s, q, 0, 0, 0);
            if (delta < -LS_EPS) {
                move(s, f, kf, 0);
                move(s, g, kg, 0);
                improved = 1;
            }
        }
    }
    return improved;
}

static size_t fruits_at(ls_t *s, uint32_t p)
{
    size_t n = 0;
    for (size_t f = 0; f < s->in->n_fruits; ++f) {
        if (s->cur[f] != LS_NONE && stop_of(s, f) == p) {
            s->list[n++] = f;
        }
    }
    return n;
}

/* Empty stop p (its fruits in s->list[0..n)) into the other open stops; returns the change of T, or INFINITY (and
 * nothing changed) when a fruit has no other open stop. Moves are recorded for undo. */
static double close_stop(ls_t *s, uint32_t p, size_t n)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        double d;
        size_t k = best_open(s, s->list[i], p, &d);
        if (k == LS_NONE) {
            undo_all(s);
            return INFINITY;
        }
        move(s, s->list[i], k, 1);
        sum += d;
    }
    return sum;
}

/* Move stop p to the empty stop q: fruits q reaches go there, the others to their best
 * open stop. Change of T or INFINITY as close_stop. s->list[0..n) holds p's fruits. */
static double shift_stop(ls_t *s, uint32_t p, uint32_t q, size_t n)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        size_t f = s->list[i], k = find_pair(s->in, f, q);
        double d;
        if (k != LS_NONE) {
            d = move_delta(s, f, k);
        } else {
            k = best_open(s, f, p, &d);
            if (k == LS_NONE) {
                undo_all(s);
                return INFINITY;
            }
        }
        move(s, f, k, 1);
        sum += d;
    }
    return sum;
}

static int close_pass(ls_t *s)
{
    int improved = 0;
    for (uint32_t p = 0; p < s->in->n_stops; ++p) {
        if (s->cnt[p] == 0) {
            continue;
        }
        s->n_undo = 0;
        double d = close_stop(s, p, fruits_at(s, p));
        if (d < -LS_EPS) {
            improved = 1;
        } else if (isfinite(d)) {
            undo_all(s);
        }
    }
    s->n_undo = 0;
    return improved;
}

static int shift_pass(ls_t *s, unsigned shift_max)
{
    int improved = 0;
    long ns = (long)s->in->n_stops;
    for (uint32_t p = 0; p < s->in->n_stops; ++p) {
        if (s->cnt[p] == 0) {
            continue;
        }
        long best_q = -1;
        double best_d = -LS_EPS;
        size_t n = fruits_at(s, p);
        for (long d = -(long)shift_max; d <= (long)shift_max; ++d) {
            long q = (long)p + d;
            if (d == 0 || q < 0 || q >= ns || s->cnt[q] != 0) {
                continue;
            }
            s->n_undo = 0;
            double delta = shift_stop(s, p, (uint32_t)q, n);
            if (isfinite(delta)) {
                undo_all(s);
            }
            if (delta < best_d) {
                best_d = delta;
                best_q = q;
            }
        }
        if (best_q >= 0) {
            s->n_undo = 0;
            (void)shift_stop(s, p, (uint32_t)best_q, n);
            improved = 1;
        }
    }
    s->n_undo = 0;
    return improved;
}

static void descend(ls_t *s, unsigned shift_max)
{
    recompute(s);
    for (int round = 0; round < 1000; ++round) { /* each round strictly improves T */
        int imp = relocate_pass(s);
        if (!imp) {
            imp = exchange_pass(s);
        }
        if (!imp) {
            imp = close_pass(s);
        }
        if (!imp) {
            imp = shift_pass(s, shift_max);
        }
        if (!imp) {
            break;
        }
    }
    recompute(s); /* drop the rounding drift of incremental updates */
}

/* A random open stop, or UINT32_MAX when none. */
static uint32_t random_open(ls_t *s)
{
    uint32_t n_open = 0;
    for (size_t p = 0; p < s->in->n_stops; ++p) {
        n_open += s->cnt[p] != 0;
    }
    if (n_open == 0) {
        return UINT32_MAX;
    }
    uint32_t pick = rnd(s, n_open);
    for (uint32_t p = 0; p < s->in->n_stops; ++p) {
        if (s->cnt[p] != 0 && pick-- == 0) {
            return p;
        }
    }
    return UINT32_MAX;
}

/* Perturb the current plan: close a stop, shift one, or split one in two. */
static void kick(ls_t *s, unsigned shift_max)
{
    uint32_t p = random_open(s);
    if (p == UINT32_MAX) {
        return;
    }
    s->n_undo = 0;
    uint32_t kind = rnd(s, 3);
    long ns = (long)s->in->n_stops;
    if (kind == 0) {
        (void)close_stop(s, p, fruits_at(s, p));
    } else {
        long span = (long)(kind == 1 ? shift_max : 4 * shift_max);
        long q = (long)p + (long)rnd(s, (uint32_t)(2 * span + 1)) - span;
        if (q < 0 || q >= ns || q == (long)p) {
            return;
        }
        if (kind == 1 && s->cnt[q] == 0) {
            (void)shift_stop(s, p, (uint32_t)q, fruits_at(s, p));
        } else {
            /* split: the fruits of p that lie on q's side of the midpoint move to q */
            double mid = 0.5 * (s->in->stop_y_m[p] + s->in->stop_y_m[q]);
            size_t n = fruits_at(s, p);
            for (size_t i = 0; i < n; ++i) {
                size_t f = s->list[i], k = find_pair(s->in, f, (uint32_t)q);
                double y = s->in->fruits[f].y_m;
                if (k != LS_NONE && ((q > (long)p) == (y > mid))) {
                    move(s, f, k, 0);
                }
            }
        }
    }
    s->n_undo = 0;
}

hv_status_t hv_local_search(const hv_instance_t *inst, const hv_ls_options_t *opt,
                            hv_assignment_t *a, double *makespan_s)
{
    if (inst == NULL || opt == NULL || a == NULL || makespan_s == NULL ||
        a->n_fruits != inst->n_fruits || a->fruit_stop == NULL) {
        return HV_ERR_ARG;
    }
    size_t nf = inst->n_fruits, ns = inst->n_stops;
    ls_t s;
    memset(&s, 0, sizeof s);
    s.in = inst;
    s.rng = opt->seed ? opt->seed : 1;
    s.cur = malloc((nf + 1) * sizeof *s.cur);
    s.best = malloc((nf + 1) * sizeof *s.best);
    s.list = malloc((nf + 1) * sizeof *s.list);
    s.undo = malloc(2 * (nf + 1) * sizeof *s.undo);
    s.load[0] = malloc((ns + 1) * sizeof(double));
    s.load[1] = malloc((ns + 1) * sizeof(double));
    s.cnt = malloc((ns + 1) * sizeof *s.cnt);
    hv_status_t st = HV_OK;
    if (!s.cur || !s.best || !s.list || !s.undo || !s.load[0] || !s.load[1] || !s.cnt) {
        st = HV_ERR_PLAN_NOMEM;
    }
    for (size_t f = 0; f < nf && st == HV_OK; ++f) {
        uint32_t p = a->fruit_stop[f];
        if (inst->fruit_begin[f] == inst->fruit_begin[f + 1]) {
            s.cur[f] = LS_NONE;
            st = p == HV_NO_STOP ? HV_OK : HV_ERR_PLAN_BAD_PAIR;
        } else if (p == HV_NO_STOP) {
            st = HV_ERR_PLAN_UNASSIGNED;
        } else if ((s.cur[f] = find_pair(inst, f, p)) == LS_NONE) {
            st = HV_ERR_PLAN_BAD_PAIR;
        }
    }
    if (st == HV_OK) {
        descend(&s, opt->shift_max);
        double best_t = total(&s);
        memcpy(s.best, s.cur, nf * sizeof *s.cur);
        for (unsigned it = 0; it < opt->kicks; ++it) {
            kick(&s, opt->shift_max);
            descend(&s, opt->shift_max);
            double t = total(&s);
            if (t < best_t - LS_EPS) {
                best_t = t;
                memcpy(s.best, s.cur, nf * sizeof *s.cur);
            } else {
                memcpy(s.cur, s.best, nf * sizeof *s.cur);
                recompute(&s);
            }
        }
        memcpy(s.cur, s.best, nf * sizeof *s.cur);
        recompute(&s);
        for (size_t f = 0; f < nf; ++f) {
            a->fruit_stop[f] = s.cur[f] == LS_NONE ? HV_NO_STOP : stop_of(&s, f);
        }
        *makespan_s = total(&s);
    }
    free(s.cur);
    free(s.best);
    free(s.list);
    free(s.undo);
    free(s.load[0]);
    free(s.load[1]);
    free(s.cnt);
    return st;
}
