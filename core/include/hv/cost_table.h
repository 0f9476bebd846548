/* The precomputed pick-cost table G(x, y, z, yaw) of one arm (docs/COST_TABLE_FORMAT.md).
 *
 * File layout (little-endian):
 *   [0, HV_COSTTAB_HEADER_BYTES)  fixed header, see hv_costtab_header_t and cost_table.c
 *   [header, header + 2*cells)    payload: one uint16 per cell, milliseconds,
 *                                 HV_COST_UNREACHABLE for poses the arm cannot pick.
 * Cell order: index = ((ix * nz + iz) * nyaw + iyaw) * ny + iy  (y innermost), so one
 * fruit seen from many stops (many y) reads contiguous memory.
 *
 * Axes are in the vehicle frame relative to the stop position: x lateral (m, negative for
 * the left arm), y along the row (m, fruit y minus stop y), z height (m), and yaw = the
 * pick heading relative to the side's inward row normal (rad; 0 = straight into the row).
 *
 * The loader works on a caller-supplied buffer (no OS calls, no allocation): read the file
 * into memory or mmap it, then hv_costtab_open(); hosted programs use hv_costtab_load() /
 * hv_costtab_check_for() of hv/file_io.h. Files are named *.bin (costgen writes
 * costtab_left.bin and costtab_right.bin).
 *
 * The planner and the executor do not take their pick costs from the table: both solve
 * each pick's exact IK (hv/pick.h), because the nearest cell disagrees with it at the edge
 * of the workspace (docs/PLAN_FORMAT.md). The table is the paper's G for the coverage
 * maps, the mount search and the experiments; a table given to a program is checked
 * against the configured arm (hv_costtab_expect_arm).
 */
#ifndef HV_COST_TABLE_H
#define HV_COST_TABLE_H

#include <stddef.h>
#include <stdint.h>

#include "hv/scara.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HV_COSTTAB_MAGIC        "HVCOSTTB" /* 8 bytes, no terminator in the file */
#define HV_COSTTAB_VERSION      1u
#define HV_COSTTAB_HEADER_BYTES 512u
#define HV_COST_UNREACHABLE     0xFFFFu /* sentinel cell value */
#define HV_COST_MAX_MS          0xFFFEu /* largest representable cost (65.534 s) */

enum { HV_AX_X = 0, HV_AX_Y = 1, HV_AX_Z = 2, HV_AX_YAW = 3, HV_NAXES = 4 };

typedef struct hv_axis {
    double origin;  /* value at index 0 (m or rad) */
    double step;    /* > 0 (m or rad) */
    uint32_t count; /* >= 1 */
} hv_axis_t;

typedef struct hv_grid {
    hv_axis_t axis[HV_NAXES]; /* indexed by HV_AX_* */
} hv_grid_t;

/* A validated table. Points into the caller's buffer; valid as long as the buffer is. */
typedef struct hv_costtab {
    hv_grid_t grid;
    hv_arm_t arm; /* the arm (geometry, limits, home, mount) the table was built for */
    uint32_t generator_version;
    const uint8_t *payload; /* 2 * cells bytes, little-endian uint16 */
    size_t cells;
} hv_costtab_t;

/* Number of cells of a grid (0 if any count is 0 or the product overflows size_t). */
size_t hv_grid_cells(const hv_grid_t *grid);

/* Validate the grid: finite origins, steps > 0, counts >= 1, cell count fits 32 bits. */
hv_status_t hv_grid_check(const hv_grid_t *grid, hv_diag_t *diag);

/* Bytes of a whole table file for this grid (header + payload). 0 on an invalid grid. */
size_t hv_costtab_file_bytes(const hv_grid_t *grid);

/* Serialise the header for `arm`/`grid` and a payload of `cells` uint16 costs (host order)
 * into `out` (at least hv_costtab_file_bytes(grid) bytes). Computes both CRCs. */
hv_status_t hv_costtab_write(const hv_grid_t *grid, const hv_arm_t *arm, uint32_t generator_version,
                             const uint16_t *costs_ms, uint8_t *out, size_t out_len,
                             hv_diag_t *diag);

/* Validate a table in `buf` and fill `tab`. Errors (each with diag->field set):
 * HV_ERR_TAB_TRUNCATED, HV_ERR_TAB_MAGIC, HV_ERR_TAB_VERSION, HV_ERR_TAB_HEADER,
 * HV_ERR_TAB_GRID, HV_ERR_TAB_CRC. */
hv_status_t hv_costtab_open(hv_costtab_t *tab, const void *buf, size_t len, hv_diag_t *diag);

/* Check that a loaded table fits what the caller expects (side, and the same grid as
 * `expected` when not NULL). HV_ERR_TAB_MISMATCH with diag naming the field. */
hv_status_t hv_costtab_expect(const hv_costtab_t *tab, hv_side_t side, const hv_grid_t *expected,
                              hv_diag_t *diag);

/* hv_costtab_expect() for arm->side and `expected`, then the arm the table was built for
 * against `arm`: elbow mode, home pose, joint limits, mount (base position and heading)
 * and link origins, each to 1e-6 (m, rad, m/s, ...). HV_ERR_TAB_MISMATCH with diag->field
 * naming the first that differs ("mount.base", "joint_limits", "grid.y", ...). */
hv_status_t hv_costtab_expect_arm(const hv_costtab_t *tab, const hv_arm_t *arm,
                                  const hv_grid_t *expected, hv_diag_t *diag);

/* Nearest-cell index of a value on one axis; -1 when outside the grid or non-finite. */
long hv_axis_index(const hv_axis_t *axis, double value);

/* Raw cell value (ms or HV_COST_UNREACHABLE) by indices; indices must be in range. */
uint16_t hv_costtab_cell(const hv_costtab_t *tab, uint32_t ix, uint32_t iy, uint32_t iz,
                         uint32_t iyaw);

/* Cost (ms) of picking the fruit at (x, y_rel, z, yaw) from the current stop: nearest cell.
 * HV_OK with *cost_ms, HV_ERR_NAN, HV_ERR_OUT_OF_GRID, or HV_ERR_UNREACHABLE. O(1). */
hv_status_t hv_costtab_lookup(const hv_costtab_t *tab, double x_m, double y_rel_m, double z_m,
                              double yaw_rad, uint16_t *cost_ms);

/* For the planner's hot loop: the contiguous y-row of cells at the nearest (x, z, yaw).
 * *row points at ny = grid.axis[HV_AX_Y].count little-endian uint16 values (read them with
 * hv_costtab_row_at()). HV_ERR_OUT_OF_GRID / HV_ERR_NAN as above. */
hv_status_t hv_costtab_row(const hv_costtab_t *tab, double x_m, double z_m, double yaw_rad,
                           const uint8_t **row);

static inline uint16_t hv_costtab_row_at(const uint8_t *row, uint32_t iy)
{
    return (uint16_t)(row[2u * iy] | (uint16_t)(row[2u * iy + 1u] << 8));
}

/* CRC-32 (IEEE 802.3, reflected, as zlib's crc32). Start with crc = 0. */
uint32_t hv_crc32(uint32_t crc, const void *data, size_t len);

#ifdef __cplusplus
}
#endif
#endif /* HV_COST_TABLE_H */
