/* Subset-row cuts on fruit triples: separation and the cuts a pattern meets
 * (milp_srcuts.h). */
#include <stdlib.h>
#include <string.h>

#include "hv/grow_array.h"
#include "hv/milp_srcuts.h"
#include "hv/plan_status.h"
#include "milp_tunables.h"

hv_status_t hv_src_init(hv_src_t *s, size_t n_fruits)
{
    memset(s, 0, sizeof *s);
    s->nf = n_fruits;
    s->fbeg = calloc(n_fruits + 1, sizeof *s->fbeg);
    return s->fbeg != NULL ? HV_OK : HV_ERR_PLAN_NOMEM;
}

void hv_src_free(hv_src_t *s)
{
    free(s->tri);
    free(s->fbeg);
    free(s->fcut);
    free(s->cnt);
    memset(s, 0, sizeof *s);
}

void hv_src_clear(hv_src_t *s)
{
    s->n = 0;
    memset(s->fbeg, 0, (s->nf + 1) * sizeof *s->fbeg);
}

/* The per-fruit index of the cuts (fbeg, fcut) after cuts were appended. */
static int index_cuts(hv_src_t *s)
{
    if (!hv_grow((void **)&s->fcut, &s->fcut_cap, 3 * s->n + 1, sizeof *s->fcut)) {
        return 0;
    }
    free(s->cnt); /* per cut, and first per fruit while filling */
    s->cnt = calloc((s->n > s->nf ? s->n : s->nf) + 1, sizeof *s->cnt);
    if (s->cnt == NULL) {
        return 0;
    }
    memset(s->fbeg, 0, (s->nf + 1) * sizeof *s->fbeg);
    for (size_t c = 0; c < s->n; ++c) {
        for (int q = 0; q < 3; ++q) {
            s->fbeg[s->tri[c][q] + 1]++;
        }
    }
    for (size_t f = 0; f < s->nf; ++f) {
        s->fbeg[f + 1] += s->fbeg[f];
    }
    for (size_t c = 0; c < s->n; ++c) {
        for (int q = 0; q < 3; ++q) {
            s->fcut[s->fbeg[s->tri[c][q]] + s->cnt[s->tri[c][q]]++] = (uint32_t)c;
        }
    }
    memset(s->cnt, 0, (s->n > s->nf ? s->n : s->nf) * sizeof *s->cnt);
    return 1;
}

hv_status_t hv_src_keep(hv_src_t *s, const unsigned char *keep)
{
    size_t m = 0;
    for (size_t c = 0; c < s->n; ++c) {
        if (keep[c]) {
            memmove(s->tri[m++], s->tri[c], sizeof s->tri[c]);
        }
    }
    s->n = m;
    return index_cuts(s) ? HV_OK : HV_ERR_PLAN_NOMEM;
}

hv_status_t hv_src_copy(hv_src_t *dst, const hv_src_t *src)
{
    if (dst->nf != src->nf) {
        return HV_ERR_ARG;
    }
    if (!hv_grow((void **)&dst->tri, &dst->cap, src->n + 1, sizeof *dst->tri)) {
        return HV_ERR_PLAN_NOMEM;
    }
    if (src->n > 0) { /* src->tri is NULL until the first cut */
        memcpy(dst->tri, src->tri, src->n * sizeof *dst->tri);
    }
    dst->n = src->n;
    return index_cuts(dst) ? HV_OK : HV_ERR_PLAN_NOMEM;
}

size_t hv_src_hits(hv_src_t *s, const uint32_t *f, size_t n, uint32_t *out)
{
    size_t m = 0;
    for (size_t i = 0; i < n; ++i) {
        for (size_t q = s->fbeg[f[i]]; q < s->fbeg[f[i] + 1]; ++q) {
            if (++s->cnt[s->fcut[q]] == 2) {
                out[m++] = s->fcut[q];
            }
        }
    }
    for (size_t i = 0; i < n; ++i) {
        for (size_t q = s->fbeg[f[i]]; q < s->fbeg[f[i] + 1]; ++q) {
            s->cnt[s->fcut[q]] = 0;
        }
    }
    return m;
}

typedef struct viol {
    uint32_t f[3];
    double v;
} viol_t;

/* Most violated first; ties by the triple, so the order never depends on the enumeration. */
static int by_violation(const void *a, const void *b)
{
    const viol_t *x = a, *y = b;
    if (x->v != y->v) {
        return x->v > y->v ? -1 : 1;
    }
    int c = memcmp(x->f, y->f, sizeof x->f);
    return (c > 0) - (c < 0);
}

/* A pair of fruits of one side and the fractional weight of the columns holding both. */
typedef struct pair_w {
    uint32_t a, b;
    double w;
} pair_w_t;

static int by_pair(const void *x, const void *y)
{
    const pair_w_t *p = x, *q = y;
    if (p->a != q->a) {
        return p->a < q->a ? -1 : 1;
    }
    return p->b < q->b ? -1 : p->b > q->b;
}

/* w of the pair (a, b) in a's slice of the merged, sorted pair list; 0 when absent. */
static double pair_weight(const pair_w_t *pw, const size_t *beg, uint32_t a, uint32_t b)
{
    size_t lo = beg[a], hi = beg[a + 1];
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (pw[mid].b < b) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo < beg[a + 1] && pw[lo].b == b ? pw[lo].w : 0.0;
}

static int known(const hv_src_t *s, const uint32_t *t)
{
    for (size_t q = s->fbeg[t[0]]; q < s->fbeg[t[0] + 1]; ++q) {
        const uint32_t *u = s->tri[s->fcut[q]];
        if (u[0] == t[0] && u[1] == t[1] && u[2] == t[2]) {
            return 1;
        }
    }
    return 0;
}

static int has(const hv_src_col_t *c, uint32_t f)
{
    size_t lo = 0, hi = c->n; /* fruits ascending */
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (c->fruit[mid] < f) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo < c->n && c->fruit[lo] == f;
}

static int fractional(const hv_src_col_t *c)
{
    return c->x > FRAC_EPS && c->x < 1.0 - FRAC_EPS; /* a column at 1 holding two of S
                                                       leaves the cut at exactly 1 */
}

/* The lhs of triple (i, j, k) is w_ij + w_ik + w_jk - 2 t_ijk with w the fractional
 * weight of the columns holding a pair and t that of those holding all three. lhs > 1
 * needs two of the three pairs in some column, so every such triple has a fruit sharing a
 * column with both others: triples are grown from each fruit's pairs (sparse: memory and
 * time follow the fractional columns, not the number of fruits squared). */
hv_status_t hv_src_separate(hv_src_t *s, const hv_instance_t *inst, const hv_src_col_t *cols,
                            size_t n, size_t max_new, size_t per_fruit, double min_viol,
                            size_t *added)
{
    *added = 0;
    size_t nf = s->nf, n_items = 0, n_pw = 0;
    for (size_t c = 0; c < n; ++c) {
        n_items += cols[c].n;
        n_pw += fractional(&cols[c]) ? (size_t)cols[c].n * (cols[c].n - 1) : 0;
    }
    pair_w_t *pw = malloc((n_pw + 1) * sizeof *pw);
    size_t *pbeg = calloc(nf + 1, sizeof *pbeg);
    size_t *cbeg = calloc(nf + 1, sizeof *cbeg);
    size_t *citem = malloc((n_items + 1) * sizeof *citem);
    size_t *fill = calloc(nf + 1, sizeof *fill);
    uint32_t *used = calloc(nf + 1, sizeof *used);
    viol_t *cand = NULL;
    size_t n_cand = 0, cand_cap = 0;
    hv_status_t st = HV_ERR_PLAN_NOMEM;
    if (pw == NULL || pbeg == NULL || cbeg == NULL || citem == NULL || fill == NULL ||
        used == NULL) {
        goto out;
    }
    /* both directions of every (same-side) pair of a fractional column, merged per pair */
    n_pw = 0;
    for (size_t c = 0; c < n; ++c) {
        if (!fractional(&cols[c])) {
            continue;
        }
        for (uint32_t a = 0; a < cols[c].n; ++a) {
            uint32_t fa = cols[c].fruit[a];
            cbeg[fa + 1]++;
            for (uint32_t b = 0; b < cols[c].n; ++b) {
                uint32_t fb = cols[c].fruit[b];
                if (b != a && inst->fruits[fa].side == inst->fruits[fb].side) {
                    pw[n_pw++] = (pair_w_t){fa, fb, cols[c].x};
                }
            }
        }
    }
    if (n_pw > 1) {
        qsort(pw, n_pw, sizeof *pw, by_pair);
    }
    size_t m = 0;
    for (size_t q = 0; q < n_pw; ++q) {
        if (m > 0 && pw[m - 1].a == pw[q].a && pw[m - 1].b == pw[q].b) {
            pw[m - 1].w += pw[q].w;
        } else {
            pw[m++] = pw[q];
            pbeg[pw[q].a + 1]++;
        }
    }
    for (size_t f = 0; f < nf; ++f) {
        pbeg[f + 1] += pbeg[f];
        cbeg[f + 1] += cbeg[f];
    }
    for (size_t c = 0; c < n; ++c) {
        for (uint32_t a = 0; fractional(&cols[c]) && a < cols[c].n; ++a) {
            citem[cbeg[cols[c].fruit[a]] + fill[cols[c].fruit[a]]++] = c;
        }
    }
    for (uint32_t v = 0; v < nf; ++v) {
        for (size_t p = pbeg[v]; p < pbeg[v + 1]; ++p) {
            for (size_t q = p + 1; q < pbeg[v + 1]; ++q) {
                uint32_t a = pw[p].b, b = pw[q].b; /* a < b: the slice is sorted */
                double wab = pair_weight(pw, pbeg, a, b);
                if (wab > 0.0 && (a < v || b < v)) {
                    continue; /* a and b also share columns: grown from the least fruit */
                }
                double sum = pw[p].w + pw[q].w + wab;
                if (sum <= 1.0 + min_viol) {
                    continue;
                }
                uint32_t t3[3] = {a, b, v}; /* ascending: v goes where it belongs */
                if (v < a) {
                    t3[0] = v, t3[1] = a, t3[2] = b;
                } else if (v < b) {
                    t3[1] = v, t3[2] = b;
                }
                double t = 0.0;
                for (size_t r = cbeg[t3[0]]; r < cbeg[t3[0] + 1]; ++r) {
                    const hv_src_col_t *c = &cols[citem[r]];
                    t += has(c, t3[1]) && has(c, t3[2]) ? c->x : 0.0;
                }
                double viol = sum - 2.0 * t - 1.0;
                if (viol > min_viol && !known(s, t3)) {
                    if (!hv_grow((void **)&cand, &cand_cap, n_cand + 1, sizeof *cand)) {
                        goto out;
                    }
                    cand[n_cand++] = (viol_t){{t3[0], t3[1], t3[2]}, viol};
                }
            }
        }
    }
    if (n_cand > 1) {
        qsort(cand, n_cand, sizeof *cand, by_violation);
    }
    for (size_t c = 0; c < n_cand && *added < max_new; ++c) {
        const uint32_t *t = cand[c].f;
        if (used[t[0]] >= per_fruit || used[t[1]] >= per_fruit || used[t[2]] >= per_fruit) {
            continue;
        }
        if (!hv_grow((void **)&s->tri, &s->cap, s->n + 1, sizeof *s->tri)) {
            goto out;
        }
        memcpy(s->tri[s->n++], t, sizeof s->tri[0]);
        used[t[0]]++, used[t[1]]++, used[t[2]]++;
        ++*added;
    }
    st = index_cuts(s) ? HV_OK : HV_ERR_PLAN_NOMEM;
out:
    free(pw);
    free(pbeg);
    free(cbeg);
    free(citem);
    free(fill);
    free(used);
    free(cand);
    return st;
}
