// costtab_spotcheck: an independent check of a cost table written by costgen. Loads the
// table with the core loader, rebuilds the arm and grid from the configuration, and
// compares N random cells (by index, poses computed here, not with the tools' helpers)
// with a direct hv_scara_pick_cost. Prints the table's reachable fraction.
//
// usage: costtab_spotcheck CONFIG TABLE left|right N SEED [--elbow-free]
// exit 0: all agree; 1: a mismatch or a load error (one line naming the file); 2: usage.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>

extern "C" {
#include "hv/config.h"
#include "hv/file_io.h"
}

int main(int argc, char **argv)
{
    if (argc < 6 || argc > 7 || (argc == 7 && std::strcmp(argv[6], "--elbow-free") != 0)) {
        std::fprintf(stderr, "usage: costtab_spotcheck CONFIG TABLE left|right N SEED "
                             "[--elbow-free]\n");
        return 2;
    }
    const char *cfg_path = argv[1], *tab_path = argv[2];
    hv_side_t side = std::strcmp(argv[3], "left") == 0 ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
    long n = std::atol(argv[4]);
    std::mt19937_64 rng(std::strtoull(argv[5], nullptr, 10));

    hv_config_t cfg;
    char err[512] = {0};
    if (hv_config_load(cfg_path, &cfg, err, sizeof err) != HV_OK) {
        std::fprintf(stderr, "%s\n", err);
        return 1;
    }
    cfg.elbow_free = argc == 7 ? 1 : cfg.elbow_free;
    hv_arm_t arm;
    hv_grid_t grid;
    hv_config_arm(&cfg, side, &arm);
    hv_config_grid(&cfg, side, &grid);

    hv_costtab_file_t f;
    if (hv_costtab_load(tab_path, &f, err, sizeof err) != HV_OK) {
        std::fprintf(stderr, "%s\n", err);
        return 1;
    }
    hv_diag_t diag;
    std::memset(&diag, 0, sizeof diag);
    if (hv_costtab_expect(&f.tab, side, &grid, &diag) != HV_OK) {
        std::fprintf(stderr, "%s: %s: %s\n", tab_path, diag.field, diag.message);
        hv_costtab_unload(&f);
        return 1;
    }
    if (f.tab.arm.elbow_free != arm.elbow_free) {
        std::fprintf(stderr, "%s: elbow_free: table %d, expected %d\n", tab_path,
                     f.tab.arm.elbow_free, arm.elbow_free);
        hv_costtab_unload(&f);
        return 1;
    }

    const hv_axis_t *a = grid.axis;
    long bad = 0;
    for (long i = 0; i < n; i++) {
        uint32_t idx[HV_NAXES];
        double v[HV_NAXES];
        for (int k = 0; k < HV_NAXES; k++) {
            idx[k] = static_cast<uint32_t>(rng() % a[k].count);
            v[k] = a[k].origin + a[k].step * idx[k];
        }
        // Table yaw is relative to the side's inward normal: left normal is +pi.
        double normal = side == HV_SIDE_LEFT ? 3.14159265358979323846 : 0.0;
        hv_pose_t p = {v[HV_AX_X], v[HV_AX_Y], v[HV_AX_Z], normal + v[HV_AX_YAW]};
        double cost_s = 0.0;
        hv_status_t st = hv_scara_pick_cost(&arm, &p, &cost_s, nullptr);
        unsigned want =
            st == HV_OK ? static_cast<unsigned>(std::lround(cost_s * 1000.0)) : HV_COST_UNREACHABLE;
        unsigned got =
            hv_costtab_cell(&f.tab, idx[HV_AX_X], idx[HV_AX_Y], idx[HV_AX_Z], idx[HV_AX_YAW]);
        if (got != want) {
            if (bad < 5) {
                std::fprintf(stderr, "%s: cell (%u,%u,%u,%u) = %u, direct %u (%s)\n", tab_path,
                             idx[0], idx[1], idx[2], idx[3], got, want, hv_status_name(st));
            }
            bad++;
        }
    }
    size_t reachable = 0;
    for (size_t c = 0; c < f.tab.cells; c++) {
        reachable += (f.tab.payload[2 * c] | f.tab.payload[2 * c + 1] << 8) != HV_COST_UNREACHABLE;
    }
    std::printf("cells %zu reachable %zu fraction %.6f checked %ld mismatches %ld\n", f.tab.cells,
                reachable, static_cast<double>(reachable) / static_cast<double>(f.tab.cells), n,
                bad);
    hv_costtab_unload(&f);
    return bad == 0 ? 0 : 1;
}
