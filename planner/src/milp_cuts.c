/* Stop-pattern cuts (milp_cuts.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_cuts.h"
#include "hv/plan_status.h"
#include "milp_tunables.h"

hv_status_t hv_cut_sep_init(hv_cut_sep_t *s, const hv_instance_t *inst,
                            const hv_milp_model_t *model)
{
    memset(s, 0, sizeof *s);
    s->inst = inst;
    s->model = model;
    size_t ns = inst->n_stops;
    s->stop_begin = calloc(ns + 2, sizeof *s->stop_begin);
    s->stop_pairs = malloc((inst->n_pairs + 1) * sizeof *s->stop_pairs);
    if (s->stop_begin == NULL || s->stop_pairs == NULL) {
        hv_cut_sep_free(s);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        s->stop_begin[inst->pairs[k].stop + 1]++;
    }
    for (size_t p = 0; p < ns; ++p) {
        s->stop_begin[p + 1] += s->stop_begin[p];
    }
    size_t *fill = calloc(ns + 1, sizeof *fill);
    if (fill == NULL) {
        hv_cut_sep_free(s);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t k = 0; k < inst->n_pairs; ++k) {
        uint32_t p = inst->pairs[k].stop;
        s->stop_pairs[s->stop_begin[p] + fill[p]++] = k;
    }
    free(fill);
    return HV_OK;
}

void hv_cut_sep_free(hv_cut_sep_t *s)
{
    free(s->stop_begin);
    free(s->stop_pairs);
    s->stop_begin = NULL;
    s->stop_pairs = NULL;
}

/* The most violated cut at one stop: K = pairs kk[0..n) with LP values av, stop value bv,
 * C value cv. Fills w[0..n) and *w0; returns the violation (s), <= 0 when none. */
static double separate_stop(const hv_instance_t *in, const size_t *kk, const double *av, int n,
                            double bv, double cv, double *w, double *w0)
{
    int n_sub = (1 << n) - 1;
    double *load = malloc(2 * (size_t)(n_sub + 1) * sizeof *load);
    int *ia = malloc(((size_t)n_sub * (size_t)(n + 1) + 1) * sizeof *ia);
    int *ja = malloc(((size_t)n_sub * (size_t)(n + 1) + 1) * sizeof *ja);
    double *ar = malloc(((size_t)n_sub * (size_t)(n + 1) + 1) * sizeof *ar);
    double viol = 0.0;
    if (load == NULL || ia == NULL || ja == NULL || ar == NULL) {
        goto done;
    }
    glp_prob *lp = glp_create_prob();
    glp_set_obj_dir(lp, GLP_MAX);
    glp_add_cols(lp, n + 1);
    for (int i = 0; i < n; ++i) {
        /* bounded so the LP stays bounded even at points with a_ip > b_p */
        glp_set_col_bnds(lp, i + 1, GLP_DB, -1e4, 1e4);
        glp_set_obj_coef(lp, i + 1, av[i]);
    }
    glp_set_col_bnds(lp, n + 1, GLP_DB, -1e4, 0.0); /* w0 <= 0: the empty pattern */
    glp_set_obj_coef(lp, n + 1, bv);
    glp_add_rows(lp, n_sub);
    load[0] = load[1] = 0.0;
    int ne = 0;
    for (int mask = 1; mask <= n_sub; ++mask) {
        int i = __builtin_ctz((unsigned)mask), rest = mask & (mask - 1);
        const hv_pair_t *pr = &in->pairs[kk[i]];
        int sd = in->fruits[pr->fruit].side == HV_SIDE_RIGHT;
        load[2 * mask] = load[2 * rest];
        load[2 * mask + 1] = load[2 * rest + 1];
        load[2 * mask + sd] += pr->cost_s;
        glp_set_row_bnds(lp, mask, GLP_UP, 0.0, fmax(load[2 * mask], load[2 * mask + 1]));
        for (int j = 0; j < n; ++j) {
            if (mask & (1 << j)) {
                ++ne;
                ia[ne] = mask;
                ja[ne] = j + 1;
                ar[ne] = 1.0;
            }
        }
        ++ne;
        ia[ne] = mask;
        ja[ne] = n + 1;
        ar[ne] = 1.0;
    }
    glp_load_matrix(lp, ne, ia, ja, ar);
    glp_smcp sp;
    glp_init_smcp(&sp);
    sp.msg_lev = GLP_MSG_OFF;
    if (glp_simplex(lp, &sp) == 0 && glp_get_status(lp) == GLP_OPT) {
        viol = glp_get_obj_val(lp) - cv;
        for (int i = 0; i < n; ++i) {
            w[i] = glp_get_col_prim(lp, i + 1);
        }
        *w0 = glp_get_col_prim(lp, n + 1);
    }
    glp_delete_prob(lp);
done:
    free(load);
    free(ia);
    free(ja);
    free(ar);
    return viol;
}

int hv_cut_separate(hv_cut_sep_t *s, glp_tree *tree)
{
    const hv_instance_t *in = s->inst;
    const hv_milp_model_t *m = s->model;
    glp_prob *lp = glp_ios_get_prob(tree);
    int added = 0;
    size_t kk[HV_CUT_MAX_ITEMS];
    double av[HV_CUT_MAX_ITEMS], w[HV_CUT_MAX_ITEMS], w0 = 0.0;
    int ind[HV_CUT_MAX_ITEMS + 3];
    double val[HV_CUT_MAX_ITEMS + 3];
    for (size_t p = 0; p < in->n_stops; ++p) {
        if (m->col_b[p] == 0) {
            continue;
        }
        double bv = glp_get_col_prim(lp, m->col_b[p]);
        double cv = glp_get_col_prim(lp, m->col_c[p]);
        if (bv < CUT_MIN_VALUE) {
            continue;
        }
        /* K: the fruits with the largest LP pick time a * G at this stop */
        int n = 0;
        int fractional = 0;
        for (size_t i = s->stop_begin[p]; i < s->stop_begin[p + 1]; ++i) {
            size_t k = s->stop_pairs[i];
            double a = glp_get_col_prim(lp, (int)k + 1);
            if (a < CUT_MIN_VALUE) {
                continue;
            }
            fractional |= a < 1.0 - CUT_MIN_VALUE;
            double score = a * in->pairs[k].cost_s;
            if (n < HV_CUT_MAX_ITEMS) {
                kk[n] = k;
                av[n] = a;
                ++n;
            } else {
                int worst = 0;
                for (int j = 1; j < n; ++j) {
                    if (av[j] * in->pairs[kk[j]].cost_s < av[worst] * in->pairs[kk[worst]].cost_s) {
                        worst = j;
                    }
                }
                if (score > av[worst] * in->pairs[kk[worst]].cost_s) {
                    kk[worst] = k;
                    av[worst] = a;
                }
            }
        }
        if (n < 2 || (!fractional && bv > 1.0 - CUT_MIN_VALUE)) {
            continue; /* one fruit, or an integral stop: the model's rows are exact there */
        }
        double viol = separate_stop(in, kk, av, n, bv, cv, w, &w0);
        if (viol < CUT_MIN_VIOLATION_S) {
            continue;
        }
        /* C_p - sum w_i a_i - w0 b_p >= 0 */
        int len = 0;
        ind[++len] = m->col_c[p];
        val[len] = 1.0;
        ind[++len] = m->col_b[p];
        val[len] = -w0;
        for (int i = 0; i < n; ++i) {
            if (fabs(w[i]) > 1e-9) {
                ind[++len] = (int)kk[i] + 1;
                val[len] = -w[i];
            }
        }
        glp_ios_add_row(tree, NULL, GLP_RF_CUT, 0, len, ind, val, GLP_LO, 0.0);
        ++added;
    }
    s->cuts_added += added;
    return added;
}
