/* Subset-row cuts on fruit triples: separation and the cuts a pattern meets
 * (milp_srcuts.h). */
#include <stdlib.h>
#include <string.h>

#include "hv/grow_array.h"
#include "hv/milp_srcuts.h"
#include "hv/plan_status.h"

#define FRAC_EPS 1e-6 /* a column this close to 0 or 1 is not fractional */

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

static int by_violation(const void *a, const void *b)
{
    double x = ((const viol_t *)a)->v, y = ((const viol_t *)b)->v;
    return x > y ? -1 : x < y;
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

/* The lhs of triple (i, j, k) is w_ij + w_ik + w_jk - 2 t_ijk with w the fractional
 * weight of the columns holding a pair and t that of those holding all three; only pairs
 * of one column can reach lhs > 1, so triples are grown from pairs with w_ij > 0. */
hv_status_t hv_src_separate(hv_src_t *s, const hv_instance_t *inst, const hv_src_col_t *cols,
                            size_t n, size_t max_new, size_t per_fruit, double min_viol,
                            size_t *added)
{
    *added = 0;
    size_t nf = s->nf;
    double *w = calloc(nf * nf, sizeof *w);
    size_t *cbeg = calloc(nf + 1, sizeof *cbeg);
    size_t n_items = 0;
    for (size_t c = 0; c < n; ++c) {
        n_items += cols[c].n;
    }
    size_t *citem = malloc((n_items + 1) * sizeof *citem);
    size_t *fill = calloc(nf + 1, sizeof *fill);
    uint32_t *used = calloc(nf + 1, sizeof *used);
    viol_t *cand = NULL;
    size_t n_cand = 0, cand_cap = 0;
    hv_status_t st = HV_ERR_PLAN_NOMEM;
    if (w == NULL || cbeg == NULL || citem == NULL || fill == NULL || used == NULL) {
        goto out;
    }
    for (size_t c = 0; c < n; ++c) {
        if (cols[c].x <= FRAC_EPS || cols[c].x >= 1.0 - FRAC_EPS) {
            continue; /* a column at 1 holding two of S leaves the cut at exactly 1 */
        }
        for (uint32_t a = 0; a < cols[c].n; ++a) {
            cbeg[cols[c].fruit[a] + 1]++;
            for (uint32_t b = a + 1; b < cols[c].n; ++b) {
                w[(size_t)cols[c].fruit[a] * nf + cols[c].fruit[b]] += cols[c].x;
            }
        }
    }
    for (size_t f = 0; f < nf; ++f) {
        cbeg[f + 1] += cbeg[f];
    }
    for (size_t c = 0; c < n; ++c) {
        if (cols[c].x > FRAC_EPS && cols[c].x < 1.0 - FRAC_EPS) {
            for (uint32_t a = 0; a < cols[c].n; ++a) {
                citem[cbeg[cols[c].fruit[a]] + fill[cols[c].fruit[a]]++] = c;
            }
        }
    }
    for (uint32_t i = 0; i < nf; ++i) {
        for (uint32_t j = i + 1; j < nf; ++j) {
            double wij = w[(size_t)i * nf + j];
            if (wij <= FRAC_EPS || inst->fruits[i].side != inst->fruits[j].side) {
                continue;
            }
            for (uint32_t k = j + 1; k < nf; ++k) {
                double sum = wij + w[(size_t)i * nf + k] + w[(size_t)j * nf + k];
                if (sum <= 1.0 + min_viol || inst->fruits[k].side != inst->fruits[i].side) {
                    continue;
                }
                double t = 0.0;
                for (size_t q = cbeg[i]; q < cbeg[i + 1]; ++q) {
                    const hv_src_col_t *c = &cols[citem[q]];
                    t += has(c, j) && has(c, k) ? c->x : 0.0;
                }
                double v = sum - 2.0 * t - 1.0;
                uint32_t tri[3] = {i, j, k};
                if (v > min_viol && !known(s, tri)) {
                    if (!hv_grow((void **)&cand, &cand_cap, n_cand + 1, sizeof *cand)) {
                        goto out;
                    }
                    cand[n_cand++] = (viol_t){{i, j, k}, v};
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
    free(w);
    free(cbeg);
    free(citem);
    free(fill);
    free(used);
    free(cand);
    return st;
}
