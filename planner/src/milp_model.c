/* Building the stop-and-harvest MILP in a GLPK problem object (milp_model.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_model.h"
#include "hv/plan_status.h"

static int add_row(glp_prob *lp, int type, double lb, double ub)
{
    int i = glp_add_rows(lp, 1);
    glp_set_row_bnds(lp, i, type, lb, ub);
    return i;
}

void hv_milp_model_free(hv_milp_model_t *m)
{
    if (m->lp != NULL) {
        glp_delete_prob(m->lp);
    }
    free(m->col_b);
    free(m->col_c);
    free(m->ia);
    free(m->ja);
    free(m->ar);
    memset(m, 0, sizeof *m);
}

/* Append one coefficient to the triplet arrays (capacity checked by the caller). */
static void put(hv_milp_model_t *m, int i, int j, double v)
{
    m->ne++;
    m->ia[m->ne] = i;
    m->ja[m->ne] = j;
    m->ar[m->ne] = v;
}

hv_status_t hv_milp_model_build(const hv_instance_t *inst, const hv_milp_model_opts_t *mo,
                                int names, hv_milp_model_t *m)
{
    memset(m, 0, sizeof *m);
    size_t ns = inst->n_stops, np = inst->n_pairs;
    m->col_b = calloc(ns + 1, sizeof *m->col_b);
    m->col_c = calloc(ns + 1, sizeof *m->col_c);
    /* coefficients: assignment (1 per pair) + load rows (1 per pair) + linking (2 per pair,
     * or 1 per pair + 1 per stop) + C_p / b_p in load rows and side-bound rows */
    size_t cap = 4 * np + 12 * ns + 16;
    m->ia = malloc((cap + 1) * sizeof *m->ia);
    m->ja = malloc((cap + 1) * sizeof *m->ja);
    m->ar = malloc((cap + 1) * sizeof *m->ar);
    m->lp = glp_create_prob();
    if (!m->col_b || !m->col_c || !m->ia || !m->ja || !m->ar || !m->lp) {
        hv_milp_model_free(m);
        return HV_ERR_PLAN_NOMEM;
    }
    glp_prob *lp = m->lp;
    glp_set_prob_name(lp, "stop_and_harvest");
    glp_set_obj_name(lp, "makespan_s");
    glp_set_obj_dir(lp, GLP_MIN);
    char name[64];

    /* a_k: one binary per reachable (fruit, stop) pair, columns 1..n_pairs */
    if (np > 0) {
        glp_add_cols(lp, (int)np);
    }
    for (size_t k = 0; k < np; ++k) {
        int j = (int)k + 1;
        glp_set_col_kind(lp, j, GLP_BV);
        if (names) {
            snprintf(name, sizeof name, "a_%u_%u", inst->pairs[k].fruit, inst->pairs[k].stop);
            glp_set_col_name(lp, j, name);
        }
    }
    /* b_p and C_p only for stops some fruit can use */
    unsigned *per_stop = calloc(ns + 1, sizeof *per_stop);
    if (per_stop == NULL) {
        hv_milp_model_free(m);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t k = 0; k < np; ++k) {
        per_stop[inst->pairs[k].stop]++;
    }
    for (size_t p = 0; p < ns; ++p) {
        if (per_stop[p] == 0) {
            continue;
        }
        m->col_b[p] = glp_add_cols(lp, 2);
        m->col_c[p] = m->col_b[p] + 1;
        glp_set_col_kind(lp, m->col_b[p], GLP_BV);
        glp_set_obj_coef(lp, m->col_b[p], inst->stop_penalty_s);
        glp_set_col_bnds(lp, m->col_c[p], GLP_LO, 0.0, 0.0);
        glp_set_obj_coef(lp, m->col_c[p], 1.0);
        if (names) {
            snprintf(name, sizeof name, "b_%zu", p);
            glp_set_col_name(lp, m->col_b[p], name);
            snprintf(name, sizeof name, "C_%zu", p);
            glp_set_col_name(lp, m->col_c[p], name);
        }
    }
    /* T_travel as a column fixed at its value, not GLPK's objective constant: the CPLEX LP
     * format keeps a constant only as a comment, and an exported model must re-solve to
     * the same optimum elsewhere */
    m->col_travel = glp_add_cols(lp, 1);
    glp_set_col_bnds(lp, m->col_travel, GLP_FX, inst->travel_time_s, inst->travel_time_s);
    glp_set_obj_coef(lp, m->col_travel, 1.0);
    glp_set_col_name(lp, m->col_travel, "travel_s");
    m->n_cols = glp_get_num_cols(lp);

    /* each reachable fruit exactly once */
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        if (inst->fruit_begin[f] == inst->fruit_begin[f + 1]) {
            continue;
        }
        int i = add_row(lp, GLP_FX, 1.0, 1.0);
        if (names) {
            snprintf(name, sizeof name, "assign_%zu", f);
            glp_set_row_name(lp, i, name);
        }
        for (size_t k = inst->fruit_begin[f]; k < inst->fruit_begin[f + 1]; ++k) {
            put(m, i, (int)k + 1, 1.0);
        }
    }
    /* C_p >= C^L_p and C_p >= C^R_p: C_p - sum G a >= 0, one row per side present */
    int *row_load = calloc(2 * (ns + 1), sizeof *row_load);
    if (row_load == NULL) {
        free(per_stop);
        hv_milp_model_free(m);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t k = 0; k < np; ++k) {
        const hv_pair_t *pr = &inst->pairs[k];
        int sd = inst->fruits[pr->fruit].side == HV_SIDE_RIGHT;
        int *ri = &row_load[2 * pr->stop + (size_t)sd];
        if (*ri == 0) {
            *ri = add_row(lp, GLP_LO, 0.0, 0.0);
            put(m, *ri, m->col_c[pr->stop], 1.0);
            if (names) {
                snprintf(name, sizeof name, "load%c_%u", sd ? 'R' : 'L', pr->stop);
                glp_set_row_name(lp, *ri, name);
            }
        }
        put(m, *ri, (int)k + 1, -pr->cost_s);
    }
    free(row_load);
    /* linking: a fruit only at a used stop */
    if (mo->link_disaggregated) {
        for (size_t k = 0; k < np; ++k) {
            int i = add_row(lp, GLP_UP, 0.0, 0.0);
            if (names) {
                snprintf(name, sizeof name, "link_%zu", k);
                glp_set_row_name(lp, i, name);
            }
            put(m, i, (int)k + 1, 1.0);
            put(m, i, m->col_b[inst->pairs[k].stop], -1.0);
        }
    } else {
        int *row_link = calloc(ns + 1, sizeof *row_link);
        if (row_link == NULL) {
            free(per_stop);
            hv_milp_model_free(m);
            return HV_ERR_PLAN_NOMEM;
        }
        for (size_t k = 0; k < np; ++k) {
            uint32_t p = inst->pairs[k].stop;
            if (row_link[p] == 0) {
                row_link[p] = add_row(lp, GLP_UP, 0.0, 0.0);
                put(m, row_link[p], m->col_b[p], -(double)per_stop[p]);
                if (names) {
                    snprintf(name, sizeof name, "link_%u", p);
                    glp_set_row_name(lp, row_link[p], name);
                }
            }
            put(m, row_link[p], (int)k + 1, 1.0);
        }
        free(row_link);
    }

    m->n_cols = glp_get_num_cols(lp);
    free(per_stop);
    glp_load_matrix(lp, (int)m->ne, m->ia, m->ja, m->ar);
    return HV_OK;
}

hv_status_t hv_milp_model_point(const hv_instance_t *inst, const hv_milp_model_t *m,
                                const uint32_t *fruit_stop, double *x)
{
    size_t ns = inst->n_stops;
    double *load = calloc(2 * (ns + 1), sizeof *load); /* per stop: left, right (s) */
    if (load == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    for (int j = 0; j <= m->n_cols; ++j) {
        x[j] = 0.0;
    }
    for (size_t f = 0; f < inst->n_fruits; ++f) {
        for (size_t k = inst->fruit_begin[f]; k < inst->fruit_begin[f + 1]; ++k) {
            const hv_pair_t *pr = &inst->pairs[k];
            if (pr->stop == fruit_stop[f]) {
                x[k + 1] = 1.0;
                x[m->col_b[pr->stop]] = 1.0;
                load[2 * pr->stop + (inst->fruits[f].side == HV_SIDE_RIGHT)] += pr->cost_s;
            }
        }
    }
    for (size_t p = 0; p < ns; ++p) {
        if (m->col_c[p] != 0) {
            x[m->col_c[p]] = fmax(load[2 * p], load[2 * p + 1]);
        }
    }
    x[m->col_travel] = inst->travel_time_s;
    free(load);
    return HV_OK;
}
