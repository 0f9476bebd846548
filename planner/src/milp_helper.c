/* The helper thread of the branch-and-price (milp_helper.h). */
#include <glpk.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "hv/milp_clock.h"
#include "hv/milp_helper.h"
#include "hv/milp_local_search.h"
#include "hv/plan_status.h"
#include "milp_tunables.h"

/* 5 first: within a window's 0.5 s it leaves local optima of 4 (SOLVER.md's history) */
static const unsigned widths[] = {5, 4, 3, 6, 2};
#define N_WIDTHS (sizeof widths / sizeof widths[0])

struct hv_helper {
    const hv_instance_t *inst;
    hv_milp_options_t opt; /* for the window sub-solves: polls stop_requested() */
    const hv_milp_subsolver_t *sub;
    double t_deadline;
    unsigned polish_kicks;
    pthread_t thread;
    pthread_mutex_t mu; /* guards everything below */
    int stop;
    hv_assignment_t best; /* the best plan either side knows */
    double best_t;
    int best_is_new; /* best came from the helper and the search has not taken it */
    hv_status_t err;
    hv_window_stats_t stats;
};

static int stop_requested(void *ctx)
{
    hv_helper_t *h = ctx;
    pthread_mutex_lock(&h->mu);
    int s = h->stop;
    pthread_mutex_unlock(&h->mu);
    return s;
}

/* A plan becomes the best known when it beats it; from_helper: the search has not seen it. */
static void publish(hv_helper_t *h, const hv_assignment_t *a, double t, int from_helper)
{
    pthread_mutex_lock(&h->mu);
    if (t < h->best_t) {
        memcpy(h->best.fruit_stop, a->fruit_stop, h->inst->n_fruits * sizeof *a->fruit_stop);
        h->best_t = t;
        h->best_is_new = from_helper;
    }
    pthread_mutex_unlock(&h->mu);
}

/* hv_window_better_fn: each better window reaches the search at once, not after the pass */
static void publish_window(void *ctx, const hv_assignment_t *a, double t)
{
    publish(ctx, a, t, 1);
}

/* The first polish: a long local search from the starting plan, in chunks between which
 * the clock and the stop flag are read (the local search polls neither); each chunk's
 * plan is published, so the search has it at its next pricing round. */
static hv_status_t polish(hv_helper_t *h, hv_assignment_t *a)
{
    pthread_mutex_lock(&h->mu);
    memcpy(a->fruit_stop, h->best.fruit_stop, h->inst->n_fruits * sizeof *a->fruit_stop);
    double t = h->best_t;
    pthread_mutex_unlock(&h->mu);
    hv_ls_options_t lo;
    hv_ls_options_default(&lo);
    hv_status_t st = HV_OK;
    for (unsigned done = 0; done < h->polish_kicks && st == HV_OK && !stop_requested(h) &&
                            hv_milp_now_s() < h->t_deadline;
         done += POLISH_CHUNK) {
        lo.kicks = h->polish_kicks - done < POLISH_CHUNK ? h->polish_kicks - done : POLISH_CHUNK;
        lo.seed = 0x9e3779b97f4a7c15ull * (uint64_t)(done + 1u);
        st = hv_local_search(h->inst, &lo, a, &t);
        if (st == HV_OK) {
            publish(h, a, t, 1);
        }
    }
    return st;
}

static void *helper_main(void *arg)
{
    hv_helper_t *h = arg;
    size_t nf = h->inst->n_fruits;
    hv_assignment_t a;
    hv_window_memo_t memo;
    hv_status_t st = hv_window_memo_init(&memo, HELPER_MEMO); /* freeable even on failure */
    if (st == HV_OK) {
        st = hv_assignment_alloc(&a, nf);
    }
    int have_a = st == HV_OK;
    unsigned round = 0, idle = 0; /* widths tried since the last improvement */
    if (st == HV_OK) {
        st = polish(h, &a);
    }
    while (st == HV_OK && !stop_requested(h) && hv_milp_now_s() < h->t_deadline) {
        pthread_mutex_lock(&h->mu);
        memcpy(a.fruit_stop, h->best.fruit_stop, nf * sizeof *a.fruit_stop);
        double t = h->best_t, t0 = t;
        pthread_mutex_unlock(&h->mu);
        hv_window_stats_t ws;
        st = hv_window_improve(h->inst, &h->opt, h->sub, widths[round++ % N_WIDTHS],
                               HELPER_WINDOW_LIMIT_S, h->t_deadline, &a, &t, &ws, &memo,
                               publish_window, h);
        h->stats.windows += ws.windows; /* only this thread writes the counts */
        h->stats.improved += ws.improved;
        h->stats.proven += ws.proven;
        h->stats.repeats += ws.repeats;
        idle = t < t0 ? 0 : idle + 1;
        if (st == HV_OK && idle >= N_WIDTHS) {
            /* no width helps: move the plan by a kicked local search and start again */
            hv_ls_options_t lo;
            hv_ls_options_default(&lo);
            lo.kicks = HELPER_KICKS_CHUNK; /* in chunks: the local search does not poll */
            for (unsigned c = 0; c < HELPER_KICKS / HELPER_KICKS_CHUNK && st == HV_OK &&
                                 !stop_requested(h) && hv_milp_now_s() < h->t_deadline;
                 ++c) {
                lo.seed = 0x2545f4914f6cdd1dull * (uint64_t)(round * 64u + c + 1u);
                st = hv_local_search(h->inst, &lo, &a, &t);
            }
            idle = 0;
        }
        if (st == HV_OK) {
            publish(h, &a, t, 1);
        }
    }
    if (have_a) {
        hv_assignment_free(&a);
    }
    hv_window_memo_free(&memo);
    pthread_mutex_lock(&h->mu);
    h->err = st;
    pthread_mutex_unlock(&h->mu);
    glp_free_env(); /* this thread's GLPK environment */
    return NULL;
}

hv_status_t hv_helper_start(const hv_instance_t *inst, const hv_milp_options_t *opt,
                            const hv_milp_subsolver_t *sub, const hv_assignment_t *plan, double t_s,
                            double t_deadline_s, unsigned polish_kicks, hv_helper_t **out)
{
    *out = NULL;
    hv_helper_t *h = calloc(1, sizeof *h);
    if (h == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    if (hv_assignment_alloc(&h->best, inst->n_fruits) != HV_OK) {
        free(h);
        return HV_ERR_PLAN_NOMEM;
    }
    memcpy(h->best.fruit_stop, plan->fruit_stop, inst->n_fruits * sizeof *plan->fruit_stop);
    h->best_t = t_s;
    h->inst = inst;
    h->opt = *opt;
    h->sub = sub;
    h->opt.verbose = 0;
    h->opt.stop = stop_requested;
    h->opt.stop_ctx = h;
    h->t_deadline = t_deadline_s;
    h->polish_kicks = polish_kicks;
    if (pthread_mutex_init(&h->mu, NULL) != 0) {
        hv_assignment_free(&h->best);
        free(h);
        return HV_ERR_ARG;
    }
    if (pthread_create(&h->thread, NULL, helper_main, h) != 0) {
        pthread_mutex_destroy(&h->mu);
        hv_assignment_free(&h->best);
        free(h);
        return HV_ERR_ARG;
    }
    *out = h;
    return HV_OK;
}

void hv_helper_offer(hv_helper_t *h, const hv_assignment_t *plan, double t_s)
{
    publish(h, plan, t_s, 0);
}

int hv_helper_take(hv_helper_t *h, double t_s, hv_assignment_t *plan, double *t_out)
{
    pthread_mutex_lock(&h->mu);
    int take = h->best_is_new && h->best_t < t_s;
    if (take) {
        memcpy(plan->fruit_stop, h->best.fruit_stop, h->inst->n_fruits * sizeof *plan->fruit_stop);
        *t_out = h->best_t;
        h->best_is_new = 0;
    }
    pthread_mutex_unlock(&h->mu);
    return take;
}

hv_status_t hv_helper_stop(hv_helper_t *h, hv_window_stats_t *stats)
{
    pthread_mutex_lock(&h->mu);
    h->stop = 1;
    pthread_mutex_unlock(&h->mu);
    pthread_join(h->thread, NULL);
    hv_status_t st = h->err;
    if (stats != NULL) {
        *stats = h->stats;
    }
    pthread_mutex_destroy(&h->mu);
    hv_assignment_free(&h->best);
    free(h);
    return st;
}
