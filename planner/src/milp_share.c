/* Work sharing between the tree workers of the branch-and-price (milp_share.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* clock_gettime, pthread_cond_timedwait */
#endif

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hv/grow_array.h"
#include "hv/milp_share.h"
#include "hv/plan_status.h"
#include "milp_tunables.h"

typedef struct queued {
    double lb_ms;
    size_t first, n;         /* its steps: steps[first .. first + n) */
    size_t warm_first, warm; /* its warm start: bytes[warm_first .. warm_first + warm) */
} queued_t;

struct hv_share {
    pthread_mutex_t mu; /* guards everything below */
    pthread_cond_t cv;  /* a node was queued, the search ended, or a worker failed */
    size_t n_workers, waiting;
    int done, failed;
    double *open_lb;      /* per worker: the best bound it holds open (hv_share_balance) */
    unsigned char *asked; /* per worker: it asked for a node without waiting */
    size_t nf;
    uint32_t *best;
    double best_ms;
    double floor_ms; /* hv_share_floor */
    queued_t *q;
    size_t n_q, q_cap;
    hv_share_step_t *steps; /* of the queued nodes; reset when the queue empties */
    size_t n_steps, steps_cap;
    unsigned char *bytes; /* their warm starts; reset likewise */
    size_t n_bytes, bytes_cap;
    hv_share_pc_t pc;
};

hv_status_t hv_share_create(size_t n_workers, size_t n_fruits, hv_share_t **out)
{
    hv_share_t *s = calloc(1, sizeof *s);
    if (s == NULL) {
        return HV_ERR_PLAN_NOMEM;
    }
    pthread_mutex_init(&s->mu, NULL);
    pthread_cond_init(&s->cv, NULL);
    s->best = malloc((n_fruits + 1) * sizeof *s->best);
    s->open_lb = malloc(n_workers * sizeof *s->open_lb);
    s->asked = calloc(n_workers, 1);
    int ok = s->best != NULL && s->open_lb != NULL && s->asked != NULL;
    for (int d = 0; d < 2; ++d) {
        s->pc.sum[d] = calloc(n_fruits + 1, sizeof *s->pc.sum[d]);
        s->pc.n[d] = calloc(n_fruits + 1, sizeof *s->pc.n[d]);
        ok &= s->pc.sum[d] != NULL && s->pc.n[d] != NULL;
    }
    if (!ok) {
        hv_share_destroy(s);
        return HV_ERR_PLAN_NOMEM;
    }
    for (size_t w = 0; w < n_workers; ++w) {
        s->open_lb[w] = INFINITY; /* not published yet: nothing to ask it for */
    }
    s->n_workers = n_workers;
    s->nf = n_fruits;
    s->best_ms = INFINITY;
    s->floor_ms = -INFINITY;
    *out = s;
    return HV_OK;
}

void hv_share_destroy(hv_share_t *s)
{
    if (s == NULL) {
        return;
    }
    pthread_cond_destroy(&s->cv);
    pthread_mutex_destroy(&s->mu);
    for (int d = 0; d < 2; ++d) {
        free(s->pc.sum[d]);
        free(s->pc.n[d]);
    }
    free(s->best);
    free(s->open_lb);
    free(s->asked);
    free(s->q);
    free(s->steps);
    free(s->bytes);
    free(s);
}

void hv_share_node_free(hv_share_node_t *node)
{
    free(node->path);
    free(node->warm);
    *node = (hv_share_node_t){0};
}

void hv_share_offer(hv_share_t *s, const uint32_t *fruit_stop, double ub_ms)
{
    pthread_mutex_lock(&s->mu);
    if (ub_ms < s->best_ms) {
        memcpy(s->best, fruit_stop, s->nf * sizeof *s->best);
        s->best_ms = ub_ms;
    }
    pthread_mutex_unlock(&s->mu);
}

int hv_share_take(hv_share_t *s, double ub_ms, uint32_t *fruit_stop, double *ub_out)
{
    pthread_mutex_lock(&s->mu);
    int better = s->best_ms < ub_ms;
    if (better) {
        memcpy(fruit_stop, s->best, s->nf * sizeof *s->best);
        *ub_out = s->best_ms;
    }
    pthread_mutex_unlock(&s->mu);
    return better;
}

int hv_share_hungry(hv_share_t *s, size_t worker)
{
    pthread_mutex_lock(&s->mu);
    size_t want = s->waiting;
    for (size_t w = 0; w < s->n_workers; ++w) {
        want += w != worker && s->asked[w];
    }
    int h = want > s->n_q;
    pthread_mutex_unlock(&s->mu);
    return h;
}

int hv_share_balance(hv_share_t *s, size_t worker, double lb_ms, double margin_ms)
{
    pthread_mutex_lock(&s->mu);
    s->open_lb[worker] = lb_ms;
    double other = INFINITY;
    for (size_t w = 0; w < s->n_workers; ++w) {
        if (w != worker) {
            other = fmin(other, s->open_lb[w]);
        }
    }
    if (!s->asked[worker] && lb_ms > other + margin_ms) {
        s->asked[worker] = 1;
    }
    int r = s->asked[worker];
    pthread_mutex_unlock(&s->mu);
    return r;
}

hv_status_t hv_share_give(hv_share_t *s, const hv_share_node_t *node)
{
    pthread_mutex_lock(&s->mu);
    hv_status_t st = HV_ERR_PLAN_NOMEM;
    size_t n = node->n, w = node->warm_len;
    if (hv_grow((void **)&s->q, &s->q_cap, s->n_q + 1, sizeof *s->q) &&
        hv_grow((void **)&s->steps, &s->steps_cap, s->n_steps + n + 1, sizeof *s->steps) &&
        hv_grow((void **)&s->bytes, &s->bytes_cap, s->n_bytes + w + 1, 1)) {
        if (n > 0) {
            memcpy(s->steps + s->n_steps, node->path, n * sizeof *node->path);
        }
        if (w > 0) {
            memcpy(s->bytes + s->n_bytes, node->warm, w);
        }
        s->q[s->n_q++] = (queued_t){node->lb_ms, s->n_steps, n, s->n_bytes, w};
        s->n_steps += n;
        s->n_bytes += w;
        pthread_cond_broadcast(&s->cv);
        st = HV_OK;
    }
    pthread_mutex_unlock(&s->mu);
    return st;
}

/* The newest queued node (the giver's best at the time) into *node: 1, or -2 when out of
 * memory. The caller holds the mutex and has seen n_q > 0. */
static int dequeue(hv_share_t *s, hv_share_node_t *node)
{
    const queued_t *t = &s->q[--s->n_q];
    int r = -2;
    if (hv_grow((void **)&node->path, &node->cap, t->n + 1, sizeof *node->path) &&
        hv_grow((void **)&node->warm, &node->warm_cap, t->warm + 1, 1)) {
        r = 1;
        memcpy(node->path, s->steps + t->first, t->n * sizeof *node->path);
        memcpy(node->warm, s->bytes + t->warm_first, t->warm);
        node->n = t->n;
        node->warm_len = t->warm;
        node->lb_ms = t->lb_ms;
    }
    if (s->n_q == 0) {
        s->n_steps = 0;
        s->n_bytes = 0;
    }
    return r;
}

int hv_share_poll(hv_share_t *s, size_t worker, hv_share_node_t *node)
{
    pthread_mutex_lock(&s->mu);
    int r = 0;
    if (s->asked[worker] && s->n_q > 0) {
        s->asked[worker] = 0;
        r = dequeue(s, node);
    }
    pthread_mutex_unlock(&s->mu);
    return r;
}

int hv_share_wait(hv_share_t *s, size_t worker, hv_share_node_t *node)
{
    pthread_mutex_lock(&s->mu);
    s->asked[worker] = 0; /* it waits now, which asks for a node anyway */
    s->waiting++;
    if (s->n_q == 0 && s->waiting == s->n_workers) {
        s->done = 1; /* nobody holds a node, so nobody can make one */
        pthread_cond_broadcast(&s->cv);
    }
    if (s->n_q == 0 && !s->done && !s->failed) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts); /* the condition variable's default clock */
        ts.tv_nsec += WAIT_SLICE_NS;
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&s->cv, &s->mu, &ts);
    }
    int r = s->done || s->failed ? 0 : -1;
    if (r != 0 && s->n_q > 0) {
        r = dequeue(s, node);
    }
    if (r != 0) {
        s->waiting--; /* it works again (or asks again) */
    }
    pthread_mutex_unlock(&s->mu);
    return r;
}

void hv_share_fail(hv_share_t *s)
{
    pthread_mutex_lock(&s->mu);
    s->failed = 1;
    pthread_cond_broadcast(&s->cv);
    pthread_mutex_unlock(&s->mu);
}

int hv_share_failed(hv_share_t *s)
{
    pthread_mutex_lock(&s->mu);
    int f = s->failed;
    pthread_mutex_unlock(&s->mu);
    return f;
}

void hv_share_pc_copy(hv_share_pc_t *dst, const hv_share_pc_t *src, size_t n)
{
    for (int d = 0; d < 2; ++d) {
        memcpy(dst->sum[d], src->sum[d], n * sizeof *dst->sum[d]);
        memcpy(dst->n[d], src->n[d], n * sizeof *dst->n[d]);
        dst->all[d] = src->all[d];
        dst->all_n[d] = src->all_n[d];
    }
}

void hv_share_pc_set(hv_share_t *s, const hv_share_pc_t *pc)
{
    pthread_mutex_lock(&s->mu);
    hv_share_pc_copy(&s->pc, pc, s->nf);
    pthread_mutex_unlock(&s->mu);
}

void hv_share_pc_add(hv_share_t *s, uint32_t fruit, int d, double g)
{
    pthread_mutex_lock(&s->mu);
    s->pc.sum[d][fruit] += g;
    s->pc.n[d][fruit]++;
    s->pc.all[d] += g;
    s->pc.all_n[d]++;
    pthread_mutex_unlock(&s->mu);
}

void hv_share_pc_get(hv_share_t *s, hv_share_pc_t *pc)
{
    pthread_mutex_lock(&s->mu);
    hv_share_pc_copy(pc, &s->pc, s->nf);
    pthread_mutex_unlock(&s->mu);
}

double hv_share_open_lb(hv_share_t *s, size_t *n)
{
    pthread_mutex_lock(&s->mu);
    double lb = INFINITY;
    for (size_t i = 0; i < s->n_q; ++i) {
        lb = fmin(lb, s->q[i].lb_ms);
    }
    *n = s->n_q;
    pthread_mutex_unlock(&s->mu);
    return lb;
}

void hv_share_floor(hv_share_t *s, double lb_ms)
{
    pthread_mutex_lock(&s->mu);
    s->floor_ms = lb_ms > s->floor_ms ? lb_ms : s->floor_ms;
    pthread_mutex_unlock(&s->mu);
}

double hv_share_floor_get(hv_share_t *s)
{
    pthread_mutex_lock(&s->mu);
    double lb = s->floor_ms;
    pthread_mutex_unlock(&s->mu);
    return lb;
}
