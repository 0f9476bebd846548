/* lcm-version-probe: the LCM version the C side is built with (lcm_version.h, from the
 * same include directory as the generated harvest_lcm_*_t.h) and proof that the library
 * it links works: a memq:// instance publishes one generated message to itself.
 * tests/executor/test_lcm_version.py compares the version with lcm-gen's and Python's.
 * Usage: lcm-version-probe */
#include <lcm/lcm.h>
#include <lcm/lcm_version.h>
#include <stdio.h>
#include <string.h>

#include "harvest_lcm_can_stats_t.h"

static void on_stats(const lcm_recv_buf_t *rbuf, const char *channel,
                     const harvest_lcm_can_stats_t *m, void *user)
{
    (void)rbuf;
    (void)channel;
    *(int64_t *)user = m->tx_frames;
}

int main(int argc, char **argv)
{
    if (argc != 1) {
        fprintf(stderr, "usage: %s (prints LCM_VERSION_STRING of lcm_version.h)\n", argv[0]);
        return strcmp(argv[1], "--help") == 0 ? 0 : 2;
    }
    lcm_t *lcm = lcm_create("memq://");
    if (!lcm) {
        fprintf(stderr, "lcm-version-probe: lcm_create(memq://) failed\n");
        return 1;
    }
    int64_t got = -1;
    harvest_lcm_can_stats_t_subscription_t *sub =
        harvest_lcm_can_stats_t_subscribe(lcm, "PROBE", on_stats, &got);
    char bus[] = "probe";
    harvest_lcm_can_stats_t m;
    memset(&m, 0, sizeof m);
    m.bus = bus;
    m.tx_frames = 42;
    int rc = harvest_lcm_can_stats_t_publish(lcm, "PROBE", &m) == 0 && lcm_handle(lcm) == 0;
    harvest_lcm_can_stats_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    if (!rc || got != m.tx_frames) {
        fprintf(stderr, "lcm-version-probe: memq:// round trip failed (got %lld)\n",
                (long long)got);
        return 1;
    }
    printf("%s\n", LCM_VERSION_STRING);
    return 0;
}
