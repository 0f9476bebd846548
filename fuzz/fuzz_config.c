/* Fuzz target: the configuration text (hv_config_parse, config/harvest.cfg).
 * Properties: no crash or undefined behaviour; a refusal names the key (or the line) and
 * says why; an accepted config gives arms and grids without any. (Not the stop margin:
 * it solves IK over the reach area at grid.step, seconds for a fine grid, which would
 * slow the fuzzer to a few inputs a second without exercising the parser.) */
#include <string.h>

#include "fuzz_support.h"
#include "hv/config.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hv_config_t cfg;
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    hv_status_t st = hv_config_parse((const char *)data, size, &cfg, &d);
    if (st != HV_OK) {
        if (d.message[0] == '\0' || (d.field[0] == '\0' && d.line == 0))
            hv_fuzz_fail("refused (%s) without naming the key or line", hv_status_name(st));
        return 0;
    }
    for (int s = 0; s < 2; s++) {
        hv_arm_t arm;
        hv_grid_t grid;
        hv_config_arm(&cfg, (hv_side_t)s, &arm);
        hv_config_grid(&cfg, (hv_side_t)s, &grid);
        (void)hv_grid_check(&grid, NULL);
    }
    (void)hv_config_stop_time_s(&cfg);
    return 0;
}
