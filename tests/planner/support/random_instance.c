/* Random tiny instances for the MILP tests (random_instance.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "random_instance.h"

uint64_t hv_test_rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

void hv_test_random_instance(hv_instance_t *in, size_t nf, size_t ns, size_t window,
                             size_t unreachable, uint64_t seed, uint64_t cost_lo_ms,
                             uint64_t cost_span_ms)
{
    memset(in, 0, sizeof *in);
    in->n_fruits = nf;
    in->n_stops = ns;
    in->fruits = calloc(nf + 1, sizeof *in->fruits);
    in->stop_y_m = calloc(ns + 1, sizeof *in->stop_y_m);
    in->pairs = calloc(nf * ns + 1, sizeof *in->pairs);
    in->fruit_begin = calloc(nf + 1, sizeof *in->fruit_begin);
    in->stop_penalty_s = 5.0;
    in->travel_time_s = 20.0;
    for (size_t p = 0; p < ns; ++p) {
        in->stop_y_m[p] = 0.01 * (double)p;
    }
    uint64_t s = seed;
    for (size_t f = 0; f < nf; ++f) {
        hv_fruit_t *fr = &in->fruits[f];
        snprintf(fr->id, sizeof fr->id, "f%zu", f);
        fr->side = (hv_test_rng_next(&s) & 1) ? HV_SIDE_RIGHT : HV_SIDE_LEFT;
        size_t centre = (size_t)(hv_test_rng_next(&s) % ns);
        fr->y_m = 0.01 * (double)centre;
        in->fruit_begin[f] = in->n_pairs;
        if (f >= nf - unreachable) {
            continue;
        }
        size_t lo = centre >= window / 2 ? centre - window / 2 : 0;
        size_t hi = lo + window > ns ? ns : lo + window;
        size_t first = in->n_pairs;
        for (size_t p = lo; p < hi; ++p) {
            if (hv_test_rng_next(&s) % 4 != 0 || (p + 1 == hi && in->n_pairs == first)) {
                hv_pair_t *pr = &in->pairs[in->n_pairs++];
                pr->fruit = (uint32_t)f;
                pr->stop = (uint32_t)p;
                pr->cost_s = (double)(cost_lo_ms + hv_test_rng_next(&s) % cost_span_ms) / 1000.0;
            }
        }
    }
    in->fruit_begin[nf] = in->n_pairs;
}

double hv_test_value_ms(const hv_instance_t *in, const uint32_t *stop, const double *skip_ms)
{
    double *arm = calloc(2 * in->n_stops, sizeof *arm);
    unsigned char *used = calloc(in->n_stops, 1);
    if (arm == NULL || used == NULL) {
        abort();
    }
    double v = 1000.0 * in->travel_time_s;
    for (size_t f = 0; f < in->n_fruits; ++f) {
        if (stop[f] == HV_NO_STOP) {
            if (in->fruit_begin[f] < in->fruit_begin[f + 1]) {
                v += skip_ms != NULL ? skip_ms[f] : INFINITY;
            }
            continue;
        }
        for (size_t k = in->fruit_begin[f]; k < in->fruit_begin[f + 1]; ++k) {
            if (in->pairs[k].stop == stop[f]) {
                arm[2 * stop[f] + (in->fruits[f].side == HV_SIDE_LEFT ? 0 : 1)] +=
                    1000.0 * in->pairs[k].cost_s;
            }
        }
        used[stop[f]] = 1;
    }
    for (size_t p = 0; p < in->n_stops; ++p) {
        v += used[p] ? 1000.0 * in->stop_penalty_s + fmax(arm[2 * p], arm[2 * p + 1]) : 0.0;
    }
    free(arm);
    free(used);
    return v;
}

double hv_test_brute_force_ms(const hv_instance_t *in, const double *skip_ms, uint32_t *best_stop)
{
    size_t nf = in->n_fruits;
    size_t *idx = calloc(nf + 1, sizeof *idx);
    uint32_t *stop = calloc(nf + 1, sizeof *stop);
    if (idx == NULL || stop == NULL) {
        abort();
    }
    double best = INFINITY;
    for (;;) {
        for (size_t f = 0; f < nf; ++f) {
            size_t b = in->fruit_begin[f], n = in->fruit_begin[f + 1] - b;
            stop[f] = idx[f] < n ? in->pairs[b + idx[f]].stop : HV_NO_STOP;
        }
        double v = hv_test_value_ms(in, stop, skip_ms);
        if (v < best) {
            best = v;
            if (best_stop != NULL) {
                memcpy(best_stop, stop, nf * sizeof *best_stop);
            }
        }
        size_t f = 0; /* odometer over the choices */
        while (f < nf) {
            size_t n = in->fruit_begin[f + 1] - in->fruit_begin[f];
            size_t choices = n + (n > 0 && skip_ms != NULL && isfinite(skip_ms[f]) ? 1 : 0);
            if (++idx[f] < choices) {
                break;
            }
            idx[f] = 0;
            ++f;
        }
        if (f == nf) {
            break;
        }
    }
    free(idx);
    free(stop);
    return best;
}
