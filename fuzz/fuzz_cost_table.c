/* Fuzz target: the cost-table file (hv_costtab_open, docs/COST_TABLE_FORMAT.md).
 * Properties: no crash or undefined behaviour; a refusal names the field; an accepted
 * table answers lookups anywhere (in the grid, beyond it, NaN) without reading outside its
 * buffer (ASan sees the input's exact bounds), and the check against the configured arm
 * either accepts or names the field that differs. */
#include <math.h>
#include <string.h>

#include "fuzz_support.h"
#include "hv/cost_table.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hv_costtab_t tab;
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    hv_status_t st = hv_costtab_open(&tab, data, size, &d);
    if (st != HV_OK) {
        if (d.field[0] == '\0' || d.message[0] == '\0')
            hv_fuzz_fail("refused (%s) without naming the field", hv_status_name(st));
        return 0;
    }
    /* every corner of the grid, one step beyond each, the centre, and NaN */
    const hv_grid_t *g = &tab.grid;
    for (int k = -1; k <= 3; k++) {
        double v[HV_NAXES];
        for (int a = 0; a < HV_NAXES; a++) {
            const hv_axis_t *ax = &g->axis[a];
            double last = ax->origin + ax->step * (double)(ax->count - 1);
            v[a] = k == -1  ? ax->origin - ax->step
                   : k == 0 ? ax->origin
                   : k == 1 ? last
                   : k == 2 ? last + ax->step
                            : (ax->origin + last) / 2;
        }
        uint16_t ms;
        (void)hv_costtab_lookup(&tab, v[HV_AX_X], v[HV_AX_Y], v[HV_AX_Z], v[HV_AX_YAW], &ms);
        const uint8_t *row;
        if (hv_costtab_row(&tab, v[HV_AX_X], v[HV_AX_Z], v[HV_AX_YAW], &row) == HV_OK) {
            uint32_t ny = g->axis[HV_AX_Y].count;
            (void)hv_costtab_row_at(row, ny - 1);
        }
    }
    uint16_t ms;
    if (hv_costtab_lookup(&tab, NAN, 0, 0, 0, &ms) == HV_OK)
        hv_fuzz_fail("a NaN pose got a cost");
    const hv_config_t *cfg = hv_fuzz_config();
    hv_arm_t arm;
    hv_grid_t grid;
    hv_config_arm(cfg, tab.arm.side, &arm);
    hv_config_grid(cfg, tab.arm.side, &grid);
    memset(&d, 0, sizeof d);
    st = hv_costtab_expect_arm(&tab, &arm, &grid, &d);
    if (st != HV_OK && d.field[0] == '\0')
        hv_fuzz_fail("mismatch (%s) without naming the field", hv_status_name(st));
    return 0;
}
