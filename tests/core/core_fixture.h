/* The paper's arm for core tests, from the project's config file (no second copy of the
 * numbers): HV_TEST_CONFIG is set by tests/core/CMakeLists.txt. */
#ifndef CORE_FIXTURE_H
#define CORE_FIXTURE_H

#include <stdio.h>
#include <stdlib.h>

#include "hv/config.h"
#include "hv/file_io.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static inline void fixture_config(hv_config_t *cfg)
{
    char err[256];
    if (hv_config_load(HV_TEST_CONFIG, cfg, err, sizeof err) != HV_OK) {
        fprintf(stderr, "fixture: %s\n", err);
        abort();
    }
}

static inline void fixture_arm(hv_arm_t *arm, hv_side_t side, int elbow_free)
{
    hv_config_t cfg;
    fixture_config(&cfg);
    cfg.elbow_free = elbow_free;
    hv_config_arm(&cfg, side, arm);
}

#endif
