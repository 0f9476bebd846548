/* Cost table file: writer, validating loader and O(1) lookup (DESIGN §4).
 *
 * Header layout (little-endian, HV_COSTTAB_HEADER_BYTES = 512, zero-padded):
 *   0   char[8]  magic "HVCOSTTB"
 *   8   u32      format version (1)
 *   12  u32      header bytes (512)
 *   16  u32      cost encoding: 1 = uint16 milliseconds, 0xFFFF unreachable
 *   20  u32      side: 0 left, 1 right
 *   24  u32      elbow_free (0/1)
 *   28  u32      layout: 1 = [x][z][yaw][y], y innermost
 *   32  u32      generator version
 *   36  u32      reserved (0)
 *   40  4 x {f64 origin, f64 step, u32 count, u32 reserved}  axes x, y, z, yaw
 *   136 f64      seconds per cost unit (0.001)
 *   144 f64[4]   mount: base x, y, z (m), base yaw (rad), vehicle frame
 *   176 f64[15]  link origins at zero joints j1, j2, j3, j4, ee (x, y, z; m)
 *   296 f64[16]  joint limits, per joint: min, max, vmax, amax
 *   424 f64[4]   home pose
 *   456 u64      payload bytes (= 2 * cells)
 *   464 u32      CRC-32 of the payload
 *   468 u32      CRC-32 of header bytes [0, 468)
 */
#include <inttypes.h> /* PRIu32: uint32_t is unsigned long on arm-none-eabi */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hv/cost_table.h"

enum {
    OFF_MAGIC = 0,
    OFF_VERSION = 8,
    OFF_HEADER_BYTES = 12,
    OFF_ENCODING = 16,
    OFF_SIDE = 20,
    OFF_ELBOW = 24,
    OFF_LAYOUT = 28,
    OFF_GENERATOR = 32,
    OFF_GRID = 40,
    AXIS_BYTES = 24,
    OFF_COST_UNIT = 136,
    OFF_MOUNT = 144,
    OFF_ORIGINS = 176,
    OFF_LIMITS = 296,
    OFF_HOME = 424,
    OFF_PAYLOAD_BYTES = 456,
    OFF_PAYLOAD_CRC = 464,
    OFF_HEADER_CRC = 468
};
#define ENCODING_U16_MS 1u
#define LAYOUT_XZYAW_Y  1u
#define COST_UNIT_S     0.001

static const char *const axis_name[HV_NAXES] = {"x", "y", "z", "yaw"};

static void diag_set(hv_diag_t *d, const char *field, const char *message)
{
    if (d == NULL) {
        return;
    }
    snprintf(d->field, sizeof d->field, "%s", field);
    snprintf(d->message, sizeof d->message, "%s", message);
    d->line = 0;
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) {
        p[i] = (uint8_t)(v >> (8 * i));
    }
}

static void put_u64(uint8_t *p, uint64_t v)
{
    for (int i = 0; i < 8; i++) {
        p[i] = (uint8_t)(v >> (8 * i));
    }
}

static void put_f64(uint8_t *p, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    put_u64(p, u);
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t get_u64(const uint8_t *p)
{
    uint64_t v = 0;
    for (int i = 7; i >= 0; i--) {
        v = v << 8 | p[i];
    }
    return v;
}

static double get_f64(const uint8_t *p)
{
    uint64_t u = get_u64(p);
    double v;
    memcpy(&v, &u, sizeof v);
    return v;
}

size_t hv_grid_cells(const hv_grid_t *grid)
{
    size_t cells = 1;
    for (int a = 0; a < HV_NAXES; a++) {
        size_t n = grid->axis[a].count;
        if (n == 0 || cells > SIZE_MAX / n) {
            return 0;
        }
        cells *= n;
    }
    return cells;
}

hv_status_t hv_grid_check(const hv_grid_t *grid, hv_diag_t *diag)
{
    if (grid == NULL) {
        return HV_ERR_ARG;
    }
    char field[32];
    for (int a = 0; a < HV_NAXES; a++) {
        const hv_axis_t *ax = &grid->axis[a];
        if (!isfinite(ax->origin)) {
            snprintf(field, sizeof field, "grid.%s.origin", axis_name[a]);
            diag_set(diag, field, "not a finite number");
            return HV_ERR_TAB_GRID;
        }
        if (!isfinite(ax->step) || !(ax->step > 0.0)) {
            snprintf(field, sizeof field, "grid.%s.step", axis_name[a]);
            diag_set(diag, field, "must be a finite number > 0");
            return HV_ERR_TAB_GRID;
        }
        if (ax->count == 0) {
            snprintf(field, sizeof field, "grid.%s.count", axis_name[a]);
            diag_set(diag, field, "must be >= 1");
            return HV_ERR_TAB_GRID;
        }
    }
    size_t cells = hv_grid_cells(grid);
    if (cells == 0 || cells > UINT32_MAX) {
        diag_set(diag, "grid", "cell count does not fit 32 bits");
        return HV_ERR_TAB_GRID;
    }
    return HV_OK;
}

size_t hv_costtab_file_bytes(const hv_grid_t *grid)
{
    if (hv_grid_check(grid, NULL) != HV_OK) {
        return 0;
    }
    return HV_COSTTAB_HEADER_BYTES + 2u * hv_grid_cells(grid);
}

hv_status_t hv_costtab_write(const hv_grid_t *grid, const hv_arm_t *arm, uint32_t generator_version,
                             const uint16_t *costs_ms, uint8_t *out, size_t out_len,
                             hv_diag_t *diag)
{
    if (grid == NULL || arm == NULL || costs_ms == NULL || out == NULL) {
        return HV_ERR_ARG;
    }
    hv_status_t st = hv_grid_check(grid, diag);
    if (st != HV_OK) {
        return st;
    }
    size_t cells = hv_grid_cells(grid);
    size_t need = HV_COSTTAB_HEADER_BYTES + 2u * cells;
    if (out_len < need) {
        diag_set(diag, "buffer", "output buffer smaller than header + payload");
        return HV_ERR_NOMEM;
    }
    memset(out, 0, HV_COSTTAB_HEADER_BYTES);
    memcpy(out + OFF_MAGIC, HV_COSTTAB_MAGIC, 8);
    put_u32(out + OFF_VERSION, HV_COSTTAB_VERSION);
    put_u32(out + OFF_HEADER_BYTES, HV_COSTTAB_HEADER_BYTES);
    put_u32(out + OFF_ENCODING, ENCODING_U16_MS);
    put_u32(out + OFF_SIDE, arm->side == HV_SIDE_LEFT ? 0u : 1u);
    put_u32(out + OFF_ELBOW, arm->elbow_free ? 1u : 0u);
    put_u32(out + OFF_LAYOUT, LAYOUT_XZYAW_Y);
    put_u32(out + OFF_GENERATOR, generator_version);
    for (int a = 0; a < HV_NAXES; a++) {
        uint8_t *p = out + OFF_GRID + AXIS_BYTES * a;
        put_f64(p, grid->axis[a].origin);
        put_f64(p + 8, grid->axis[a].step);
        put_u32(p + 16, grid->axis[a].count);
    }
    put_f64(out + OFF_COST_UNIT, COST_UNIT_S);
    for (int i = 0; i < 3; i++) {
        put_f64(out + OFF_MOUNT + 8 * i, arm->base_m[i]);
    }
    put_f64(out + OFF_MOUNT + 24, arm->base_yaw_rad);
    for (int i = 0; i < 15; i++) {
        put_f64(out + OFF_ORIGINS + 8 * i, arm->origin_m[i / 3][i % 3]);
    }
    for (int j = 0; j < HV_NJOINTS; j++) {
        const hv_joint_limit_t *l = &arm->limit[j];
        put_f64(out + OFF_LIMITS + 32 * j, l->min);
        put_f64(out + OFF_LIMITS + 32 * j + 8, l->max);
        put_f64(out + OFF_LIMITS + 32 * j + 16, l->vmax);
        put_f64(out + OFF_LIMITS + 32 * j + 24, l->amax);
        put_f64(out + OFF_HOME + 8 * j, arm->home[j]);
    }
    uint8_t *payload = out + HV_COSTTAB_HEADER_BYTES;
    for (size_t i = 0; i < cells; i++) {
        payload[2 * i] = (uint8_t)(costs_ms[i] & 0xFFu);
        payload[2 * i + 1] = (uint8_t)(costs_ms[i] >> 8);
    }
    put_u64(out + OFF_PAYLOAD_BYTES, (uint64_t)(2u * cells));
    put_u32(out + OFF_PAYLOAD_CRC, hv_crc32(0, payload, 2u * cells));
    put_u32(out + OFF_HEADER_CRC, hv_crc32(0, out, OFF_HEADER_CRC));
    return HV_OK;
}

static hv_status_t fail(hv_diag_t *diag, hv_status_t code, const char *field, const char *msg)
{
    diag_set(diag, field, msg);
    return code;
}

hv_status_t hv_costtab_open(hv_costtab_t *tab, const void *buf, size_t len, hv_diag_t *diag)
{
    if (tab == NULL || buf == NULL) {
        return HV_ERR_ARG;
    }
    const uint8_t *h = (const uint8_t *)buf;
    char msg[160];
    if (len < HV_COSTTAB_HEADER_BYTES) {
        snprintf(msg, sizeof msg, "file has %zu bytes, the header alone needs %u", len,
                 HV_COSTTAB_HEADER_BYTES);
        return fail(diag, HV_ERR_TAB_TRUNCATED, "header", msg);
    }
    if (memcmp(h + OFF_MAGIC, HV_COSTTAB_MAGIC, 8) != 0) {
        return fail(diag, HV_ERR_TAB_MAGIC, "magic", "not a cost table (expected \"HVCOSTTB\")");
    }
    uint32_t version = get_u32(h + OFF_VERSION);
    if (version != HV_COSTTAB_VERSION) {
        snprintf(msg, sizeof msg, "format version %" PRIu32 ", this build reads %u", version,
                 HV_COSTTAB_VERSION);
        return fail(diag, HV_ERR_TAB_VERSION, "version", msg);
    }
    if (get_u32(h + OFF_HEADER_BYTES) != HV_COSTTAB_HEADER_BYTES) {
        snprintf(msg, sizeof msg, "header size %" PRIu32 ", expected %u",
                 get_u32(h + OFF_HEADER_BYTES), HV_COSTTAB_HEADER_BYTES);
        return fail(diag, HV_ERR_TAB_HEADER, "header_bytes", msg);
    }
    uint32_t hcrc = hv_crc32(0, h, OFF_HEADER_CRC);
    if (hcrc != get_u32(h + OFF_HEADER_CRC)) {
        snprintf(msg, sizeof msg,
                 "header CRC-32 is %08" PRIx32 ", stored %08" PRIx32 ": header corrupted", hcrc,
                 get_u32(h + OFF_HEADER_CRC));
        return fail(diag, HV_ERR_TAB_CRC, "header_crc32", msg);
    }
    if (get_u32(h + OFF_ENCODING) != ENCODING_U16_MS) {
        return fail(diag, HV_ERR_TAB_HEADER, "cost_encoding", "unknown cost encoding");
    }
    if (get_u32(h + OFF_LAYOUT) != LAYOUT_XZYAW_Y) {
        return fail(diag, HV_ERR_TAB_HEADER, "layout", "unknown cell layout");
    }
    uint32_t side = get_u32(h + OFF_SIDE);
    if (side > 1u) {
        return fail(diag, HV_ERR_TAB_HEADER, "side", "must be 0 (left) or 1 (right)");
    }
    if (get_f64(h + OFF_COST_UNIT) != COST_UNIT_S) {
        return fail(diag, HV_ERR_TAB_HEADER, "cost_unit", "cost unit must be 0.001 s");
    }

    hv_costtab_t t;
    memset(&t, 0, sizeof t);
    for (int a = 0; a < HV_NAXES; a++) {
        const uint8_t *p = h + OFF_GRID + AXIS_BYTES * a;
        t.grid.axis[a].origin = get_f64(p);
        t.grid.axis[a].step = get_f64(p + 8);
        t.grid.axis[a].count = get_u32(p + 16);
    }
    hv_status_t st = hv_grid_check(&t.grid, diag);
    if (st != HV_OK) {
        return st;
    }
    t.cells = hv_grid_cells(&t.grid);
    uint64_t payload_bytes = get_u64(h + OFF_PAYLOAD_BYTES);
    if (payload_bytes != 2u * (uint64_t)t.cells) {
        snprintf(msg, sizeof msg, "payload_bytes %llu, the grid has %zu cells * 2 bytes",
                 (unsigned long long)payload_bytes, t.cells);
        return fail(diag, HV_ERR_TAB_GRID, "payload_bytes", msg);
    }
    size_t want = HV_COSTTAB_HEADER_BYTES + 2u * t.cells;
    if (len < want) {
        snprintf(msg, sizeof msg, "file has %zu bytes, header + payload need %zu", len, want);
        return fail(diag, HV_ERR_TAB_TRUNCATED, "payload", msg);
    }
    if (len > want) {
        snprintf(msg, sizeof msg, "file has %zu bytes, %zu more than header + payload", len,
                 len - want);
        return fail(diag, HV_ERR_TAB_HEADER, "file_size", msg);
    }
    const uint8_t *payload = h + HV_COSTTAB_HEADER_BYTES;
    uint32_t pcrc = hv_crc32(0, payload, 2u * t.cells);
    if (pcrc != get_u32(h + OFF_PAYLOAD_CRC)) {
        snprintf(msg, sizeof msg,
                 "payload CRC-32 is %08" PRIx32 ", header says %08" PRIx32 ": payload corrupted",
                 pcrc, get_u32(h + OFF_PAYLOAD_CRC));
        return fail(diag, HV_ERR_TAB_CRC, "payload_crc32", msg);
    }

    hv_arm_t *arm = &t.arm;
    arm->side = side == 0u ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
    arm->elbow_free = get_u32(h + OFF_ELBOW) ? 1 : 0;
    for (int i = 0; i < 3; i++) {
        arm->base_m[i] = get_f64(h + OFF_MOUNT + 8 * i);
    }
    arm->base_yaw_rad = get_f64(h + OFF_MOUNT + 24);
    for (int i = 0; i < 15; i++) {
        arm->origin_m[i / 3][i % 3] = get_f64(h + OFF_ORIGINS + 8 * i);
    }
    for (int j = 0; j < HV_NJOINTS; j++) {
        hv_joint_limit_t *l = &arm->limit[j];
        l->min = get_f64(h + OFF_LIMITS + 32 * j);
        l->max = get_f64(h + OFF_LIMITS + 32 * j + 8);
        l->vmax = get_f64(h + OFF_LIMITS + 32 * j + 16);
        l->amax = get_f64(h + OFF_LIMITS + 32 * j + 24);
        arm->home[j] = get_f64(h + OFF_HOME + 8 * j);
        if (!isfinite(l->min) || !isfinite(l->max) || !(l->min <= l->max) || !isfinite(l->vmax) ||
            !(l->vmax > 0.0) || !isfinite(l->amax) || !(l->amax > 0.0) || !isfinite(arm->home[j])) {
            return fail(diag, HV_ERR_TAB_HEADER, "joint_limits", "invalid joint limit or home");
        }
    }
    t.generator_version = get_u32(h + OFF_GENERATOR);
    t.payload = payload;
    *tab = t;
    return HV_OK;
}

static int axis_equal(const hv_axis_t *a, const hv_axis_t *b)
{
    return a->count == b->count && fabs(a->origin - b->origin) <= 1e-9 &&
           fabs(a->step - b->step) <= 1e-12;
}

hv_status_t hv_costtab_expect(const hv_costtab_t *tab, hv_side_t side, const hv_grid_t *expected,
                              hv_diag_t *diag)
{
    if (tab == NULL) {
        return HV_ERR_ARG;
    }
    if (tab->arm.side != side) {
        return fail(diag, HV_ERR_TAB_MISMATCH, "side",
                    side == HV_SIDE_LEFT ? "table is for the right arm, expected the left"
                                         : "table is for the left arm, expected the right");
    }
    if (expected != NULL) {
        for (int a = 0; a < HV_NAXES; a++) {
            if (!axis_equal(&tab->grid.axis[a], &expected->axis[a])) {
                char field[32], msg[160];
                snprintf(field, sizeof field, "grid.%s", axis_name[a]);
                snprintf(msg, sizeof msg,
                         "table has origin %.6g step %.6g count %" PRIu32
                         ", expected %.6g %.6g %" PRIu32,
                         tab->grid.axis[a].origin, tab->grid.axis[a].step, tab->grid.axis[a].count,
                         expected->axis[a].origin, expected->axis[a].step, expected->axis[a].count);
                return fail(diag, HV_ERR_TAB_MISMATCH, field, msg);
            }
        }
    }
    return HV_OK;
}

/* The header and the config may compute the same mount in a different order of
 * operations: 1e-6 (um, urad) tells a rounding from another arm. */
static int near_1e6(double a, double b)
{
    return fabs(a - b) <= 1e-6;
}

/* The first field in which two arms differ, or NULL. */
static const char *arm_difference(const hv_arm_t *a, const hv_arm_t *b)
{
    if (a->elbow_free != b->elbow_free) {
        return "elbow_free";
    }
    for (int j = 0; j < HV_NJOINTS; j++) {
        if (!near_1e6(a->home[j], b->home[j])) {
            return "home";
        }
        if (!near_1e6(a->limit[j].min, b->limit[j].min) ||
            !near_1e6(a->limit[j].max, b->limit[j].max) ||
            !near_1e6(a->limit[j].vmax, b->limit[j].vmax) ||
            !near_1e6(a->limit[j].amax, b->limit[j].amax)) {
            return "joint_limits";
        }
    }
    for (int i = 0; i < 3; i++) {
        if (!near_1e6(a->base_m[i], b->base_m[i])) {
            return "mount.base";
        }
    }
    if (!near_1e6(a->base_yaw_rad, b->base_yaw_rad)) {
        return "mount.heading";
    }
    for (int l = 0; l < 5; l++) {
        for (int i = 0; i < 3; i++) {
            if (!near_1e6(a->origin_m[l][i], b->origin_m[l][i])) {
                return "link_origins";
            }
        }
    }
    return NULL;
}

hv_status_t hv_costtab_expect_arm(const hv_costtab_t *tab, const hv_arm_t *arm,
                                  const hv_grid_t *expected, hv_diag_t *diag)
{
    if (tab == NULL || arm == NULL) {
        return HV_ERR_ARG;
    }
    hv_status_t st = hv_costtab_expect(tab, arm->side, expected, diag);
    if (st != HV_OK) {
        return st;
    }
    const char *field = arm_difference(&tab->arm, arm);
    if (field != NULL) {
        return fail(diag, HV_ERR_TAB_MISMATCH, field,
                    "the table was built for another arm or mount than the configured one");
    }
    return HV_OK;
}

long hv_axis_index(const hv_axis_t *axis, double value)
{
    if (!isfinite(value)) {
        return -1;
    }
    double f = (value - axis->origin) / axis->step + 0.5;
    if (!(f >= 0.0) || f >= (double)axis->count) {
        return -1;
    }
    return (long)f;
}

static size_t cell_index(const hv_grid_t *g, size_t ix, size_t iy, size_t iz, size_t iyaw)
{
    return ((ix * g->axis[HV_AX_Z].count + iz) * g->axis[HV_AX_YAW].count + iyaw) *
               g->axis[HV_AX_Y].count +
           iy;
}

uint16_t hv_costtab_cell(const hv_costtab_t *tab, uint32_t ix, uint32_t iy, uint32_t iz,
                         uint32_t iyaw)
{
    size_t i = cell_index(&tab->grid, ix, iy, iz, iyaw);
    return (uint16_t)(tab->payload[2 * i] | (uint16_t)(tab->payload[2 * i + 1] << 8));
}

hv_status_t hv_costtab_row(const hv_costtab_t *tab, double x_m, double z_m, double yaw_rad,
                           const uint8_t **row)
{
    if (tab == NULL || row == NULL) {
        return HV_ERR_ARG;
    }
    if (!isfinite(x_m) || !isfinite(z_m) || !isfinite(yaw_rad)) {
        return HV_ERR_NAN;
    }
    long ix = hv_axis_index(&tab->grid.axis[HV_AX_X], x_m);
    long iz = hv_axis_index(&tab->grid.axis[HV_AX_Z], z_m);
    long iyaw = hv_axis_index(&tab->grid.axis[HV_AX_YAW], yaw_rad);
    if (ix < 0 || iz < 0 || iyaw < 0) {
        return HV_ERR_OUT_OF_GRID;
    }
    *row = tab->payload + 2u * cell_index(&tab->grid, (size_t)ix, 0, (size_t)iz, (size_t)iyaw);
    return HV_OK;
}

hv_status_t hv_costtab_lookup(const hv_costtab_t *tab, double x_m, double y_rel_m, double z_m,
                              double yaw_rad, uint16_t *cost_ms)
{
    if (cost_ms == NULL) {
        return HV_ERR_ARG;
    }
    const uint8_t *row;
    hv_status_t st = hv_costtab_row(tab, x_m, z_m, yaw_rad, &row);
    if (st != HV_OK) {
        return st;
    }
    if (!isfinite(y_rel_m)) {
        return HV_ERR_NAN;
    }
    long iy = hv_axis_index(&tab->grid.axis[HV_AX_Y], y_rel_m);
    if (iy < 0) {
        return HV_ERR_OUT_OF_GRID;
    }
    uint16_t c = hv_costtab_row_at(row, (uint32_t)iy);
    if (c == HV_COST_UNREACHABLE) {
        return HV_ERR_UNREACHABLE;
    }
    *cost_ms = c;
    return HV_OK;
}
