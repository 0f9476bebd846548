/* Parser of the harvest configuration text (config/harvest.cfg) and the derived arm and
 * cost-table grid. Every key is required; unknown or repeated keys are errors. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/config.h"

#define HV_PI 3.14159265358979323846
#define DEG   (HV_PI / 180.0)
#define POS   1e-12 /* smallest value accepted where a quantity must be > 0 */

typedef enum { K_REAL, K_DEG, K_BOOL } key_kind_t;

typedef struct key_spec {
    const char *name;
    size_t offset; /* of the first double (or the int for K_BOOL) in hv_config_t */
    int nvals;
    double min, max; /* per value, in the file's unit (deg for K_DEG) */
    key_kind_t kind;
} key_spec_t;

#define F(member) offsetof(hv_config_t, member)
#define JOINT(n, i)                                                                                \
    {"joint" #n ".min", F(limit[i].min), 1, -10.0, 10.0, K_REAL},                                  \
        {"joint" #n ".max", F(limit[i].max), 1, -10.0, 10.0, K_REAL},                              \
        {"joint" #n ".vmax", F(limit[i].vmax), 1, POS, 100.0, K_REAL},                             \
    {                                                                                              \
        "joint" #n ".amax", F(limit[i].amax), 1, POS, 1000.0, K_REAL                               \
    }

static const key_spec_t keys[] = {
    {"arm.origin.j1", F(origin_m[0]), 3, -2.0, 2.0, K_REAL},
    {"arm.origin.j2", F(origin_m[1]), 3, -2.0, 2.0, K_REAL},
    {"arm.origin.j3", F(origin_m[2]), 3, -2.0, 2.0, K_REAL},
    {"arm.origin.j4", F(origin_m[3]), 3, -2.0, 2.0, K_REAL},
    {"arm.origin.ee", F(origin_m[4]), 3, -2.0, 2.0, K_REAL},
    JOINT(1, 0),
    JOINT(2, 1),
    JOINT(3, 2),
    JOINT(4, 3),
    {"arm.home", F(home), 4, -10.0, 10.0, K_REAL},
    {"arm.elbow_free", F(elbow_free), 1, 0.0, 1.0, K_BOOL},
    {"mount.base_height", F(base_height_m), 1, 0.0, 3.0, K_REAL},
    {"mount.base_spacing", F(base_spacing_m), 1, 0.0, 3.0, K_REAL},
    {"mount.offset", F(offset_m), 1, 0.0, 2.0, K_REAL},
    {"mount.theta_left_deg", F(theta_rad[0]), 1, -180.0, 180.0, K_DEG},
    {"mount.theta_right_deg", F(theta_rad[1]), 1, -180.0, 180.0, K_DEG},
    {"row.length", F(row_length_m), 1, POS, 1000.0, K_REAL},
    {"row.aisle_width", F(aisle_width_m), 1, POS, 5.0, K_REAL},
    {"row.canopy_depth", F(canopy_depth_m), 1, POS, 2.0, K_REAL},
    {"row.canopy_z_min", F(canopy_z_min_m), 1, 0.0, 5.0, K_REAL},
    {"row.canopy_height", F(canopy_height_m), 1, POS, 5.0, K_REAL},
    {"row.pick_yaw_max_deg", F(pick_yaw_max_rad), 1, 0.0, 180.0, K_DEG},
    {"row.stops_beyond_ends", F(stops_beyond_ends), 1, 0.0, 1.0, K_BOOL},
    {"vehicle.speed", F(vehicle_speed_mps), 1, POS, 10.0, K_REAL},
    {"vehicle.accel", F(vehicle_accel_mps2), 1, POS, 10.0, K_REAL},
    {"vehicle.stop_penalty", F(stop_penalty_s), 1, 0.0, 1000.0, K_REAL},
    {"pick.cut_time", F(cut_s), 1, POS, 60.0, K_REAL},
    {"pick.release_time", F(release_s), 1, POS, 60.0, K_REAL},
    {"plan.pick_cycle", F(pick_cycle), 1, 0.0, 1.0, K_BOOL},
    {"plan.pick_cost_flat", F(pick_cost_flat), 1, 0.0, 1.0, K_BOOL},
    {"camera.lead", F(camera_lead_m), 1, 0.0, 100.0, K_REAL},
    {"camera.window", F(camera_window_m), 1, POS, 100.0, K_REAL},
    {"fov.width", F(fov_width_m), 1, POS, 2.0, K_REAL},
    {"fov.offset", F(fov_offset_m), 1, -1.0, 1.0, K_REAL},
    {"online.horizon_limit_min", F(online_limit_min_s), 1, 0.1, 3600.0, K_REAL},
    {"online.horizon_limit_max", F(online_limit_max_s), 1, 0.1, 3600.0, K_REAL},
    {"online.wait_plan_timeout", F(online_wait_plan_timeout_s), 1, 0.1, 86400.0, K_REAL},
    {"grid.step", F(grid_step_m), 1, 0.001, 1.0, K_REAL},
    {"grid.yaw_step_deg", F(grid_yaw_step_rad), 1, 0.1, 90.0, K_DEG},
    {"grid.y_half_span", F(grid_y_half_span_m), 1, POS, 10.0, K_REAL},
    {"search.offset_min", F(search_offset_min_m), 1, 0.0, 2.0, K_REAL},
    {"search.offset_max", F(search_offset_max_m), 1, 0.0, 2.0, K_REAL},
    {"search.offset_step", F(search_offset_step_m), 1, 0.001, 1.0, K_REAL},
    {"search.theta_min_deg", F(search_theta_min_rad), 1, -180.0, 180.0, K_DEG},
    {"search.theta_max_deg", F(search_theta_max_rad), 1, -180.0, 180.0, K_DEG},
    {"search.theta_step_deg", F(search_theta_step_rad), 1, 0.1, 90.0, K_DEG},
};
#define NKEYS (sizeof keys / sizeof keys[0])

static hv_status_t cfg_fail(hv_diag_t *d, hv_status_t code, const char *key, int line,
                            const char *msg)
{
    if (d != NULL) {
        snprintf(d->field, sizeof d->field, "%s", key);
        snprintf(d->message, sizeof d->message, "%s", msg);
        d->line = line;
    }
    return code;
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

static char *trim(char *s)
{
    while (is_space(*s)) {
        s++;
    }
    size_t n = strlen(s);
    while (n > 0 && is_space(s[n - 1])) {
        s[--n] = '\0';
    }
    return s;
}

/* Parse the values of one key into `cfg`. */
static hv_status_t parse_values(const key_spec_t *k, char *val, int line, hv_config_t *cfg,
                                hv_diag_t *diag)
{
    double v[4];
    int n = 0;
    char *p = val;
    char msg[160];
    while (*p != '\0') {
        char *end;
        double x = strtod(p, &end);
        if (end == p || (*end != '\0' && !is_space(*end))) {
            snprintf(msg, sizeof msg, "'%.40s' is not a number", p);
            return cfg_fail(diag, HV_ERR_CFG_SYNTAX, k->name, line, msg);
        }
        if (n == k->nvals) {
            snprintf(msg, sizeof msg, "expected %d value(s), got more", k->nvals);
            return cfg_fail(diag, HV_ERR_CFG_SYNTAX, k->name, line, msg);
        }
        v[n++] = x;
        p = end;
        while (is_space(*p)) {
            p++;
        }
    }
    if (n != k->nvals) {
        snprintf(msg, sizeof msg, "expected %d value(s), got %d", k->nvals, n);
        return cfg_fail(diag, HV_ERR_CFG_SYNTAX, k->name, line, msg);
    }
    for (int i = 0; i < n; i++) {
        if (!isfinite(v[i]) || v[i] < k->min || v[i] > k->max) {
            snprintf(msg, sizeof msg, "value %g outside [%g, %g]", v[i], k->min, k->max);
            return cfg_fail(diag, HV_ERR_CFG_RANGE, k->name, line, msg);
        }
    }
    char *base = (char *)cfg + k->offset;
    if (k->kind == K_BOOL) {
        if (v[0] != 0.0 && v[0] != 1.0) {
            return cfg_fail(diag, HV_ERR_CFG_RANGE, k->name, line, "must be 0 or 1");
        }
        *(int *)(void *)base = v[0] != 0.0;
        return HV_OK;
    }
    for (int i = 0; i < n; i++) {
        ((double *)(void *)base)[i] = k->kind == K_DEG ? v[i] * DEG : v[i];
    }
    return HV_OK;
}

/* Relations between keys that single ranges cannot express. */
static hv_status_t check_relations(const hv_config_t *c, hv_diag_t *diag)
{
    static const char *const jmax[HV_NJOINTS] = {"joint1.max", "joint2.max", "joint3.max",
                                                 "joint4.max"};
    for (int j = 0; j < HV_NJOINTS; j++) {
        if (!(c->limit[j].min < c->limit[j].max)) {
            return cfg_fail(diag, HV_ERR_CFG_RANGE, jmax[j], 0, "must be greater than min");
        }
        if (c->home[j] < c->limit[j].min || c->home[j] > c->limit[j].max) {
            return cfg_fail(diag, HV_ERR_CFG_RANGE, "arm.home", 0,
                            "home pose outside the joint limits");
        }
    }
    if (c->search_offset_min_m > c->search_offset_max_m) {
        return cfg_fail(diag, HV_ERR_CFG_RANGE, "search.offset_max", 0,
                        "must be >= search.offset_min");
    }
    if (c->online_limit_min_s > c->online_limit_max_s) {
        return cfg_fail(diag, HV_ERR_CFG_RANGE, "online.horizon_limit_max", 0,
                        "must be >= online.horizon_limit_min");
    }
    if (c->online_wait_plan_timeout_s < c->online_limit_max_s) {
        return cfg_fail(diag, HV_ERR_CFG_RANGE, "online.wait_plan_timeout", 0,
                        "must be >= online.horizon_limit_max (a horizon may take that long)");
    }
    if (c->search_theta_min_rad > c->search_theta_max_rad) {
        return cfg_fail(diag, HV_ERR_CFG_RANGE, "search.theta_max_deg", 0,
                        "must be >= search.theta_min_deg");
    }
    return HV_OK;
}

hv_status_t hv_config_parse(const char *text, size_t len, hv_config_t *cfg, hv_diag_t *diag)
{
    if (text == NULL || cfg == NULL) {
        return HV_ERR_ARG;
    }
    unsigned char seen[NKEYS];
    memset(seen, 0, sizeof seen);
    memset(cfg, 0, sizeof *cfg);
    size_t pos = 0;
    int line = 0;
    char buf[256];
    while (pos < len) {
        size_t start = pos;
        while (pos < len && text[pos] != '\n') {
            pos++;
        }
        size_t n = pos - start;
        pos++; /* past the newline */
        line++;
        if (n >= sizeof buf) {
            return cfg_fail(diag, HV_ERR_CFG_SYNTAX, "line", line, "line longer than 255 bytes");
        }
        memcpy(buf, text + start, n);
        buf[n] = '\0';
        if (memchr(buf, '\0', n) != NULL) {
            return cfg_fail(diag, HV_ERR_CFG_SYNTAX, "line", line, "NUL byte in text");
        }
        char *hash = strchr(buf, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        char *s = trim(buf);
        if (*s == '\0') {
            continue;
        }
        char *eq = strchr(s, '=');
        if (eq == NULL) {
            return cfg_fail(diag, HV_ERR_CFG_SYNTAX, s, line, "expected `key = value`");
        }
        *eq = '\0';
        char *key = trim(s);
        char *val = trim(eq + 1);
        size_t k = 0;
        while (k < NKEYS && strcmp(keys[k].name, key) != 0) {
            k++;
        }
        if (k == NKEYS) {
            return cfg_fail(diag, HV_ERR_CFG_UNKNOWN, key, line, "unknown key");
        }
        if (seen[k]) {
            return cfg_fail(diag, HV_ERR_CFG_DUPLICATE, key, line, "key given twice");
        }
        seen[k] = 1;
        hv_status_t st = parse_values(&keys[k], val, line, cfg, diag);
        if (st != HV_OK) {
            return st;
        }
    }
    for (size_t k = 0; k < NKEYS; k++) {
        if (!seen[k]) {
            return cfg_fail(diag, HV_ERR_CFG_MISSING, keys[k].name, 0, "required key missing");
        }
    }
    return check_relations(cfg, diag);
}

void hv_config_arm_mounted(const hv_config_t *cfg, hv_side_t side, double offset_m,
                           double theta_rad, hv_arm_t *arm)
{
    memset(arm, 0, sizeof *arm);
    memcpy(arm->origin_m, cfg->origin_m, sizeof arm->origin_m);
    memcpy(arm->limit, cfg->limit, sizeof arm->limit);
    memcpy(arm->home, cfg->home, sizeof arm->home);
    arm->elbow_free = cfg->elbow_free;
    arm->side = side;
    /* docs/FRAMES.md: bases 0.47 m apart along the row, left ahead; D is measured
     * laterally from the canopy's near face towards the aisle centre; theta turns the
     * base clockwise (seen from above) for the right arm, the left arm is the right one
     * turned half a turn about z. */
    double half = 0.5 * cfg->base_spacing_m;
    double lateral = 0.5 * cfg->aisle_width_m - offset_m;
    arm->base_m[0] = side == HV_SIDE_LEFT ? -lateral : lateral;
    arm->base_m[1] = side == HV_SIDE_LEFT ? half : -half;
    arm->base_m[2] = cfg->base_height_m;
    arm->base_yaw_rad = hv_side_normal_heading(side) - theta_rad;
}

void hv_config_arm(const hv_config_t *cfg, hv_side_t side, hv_arm_t *arm)
{
    hv_config_arm_mounted(cfg, side, cfg->offset_m, cfg->theta_rad[side], arm);
}

static uint32_t steps_in(double span, double step)
{
    return (uint32_t)floor(span / step + 0.5) + 1u;
}

void hv_config_grid(const hv_config_t *cfg, hv_side_t side, hv_grid_t *grid)
{
    double near = 0.5 * cfg->aisle_width_m;
    double far = near + cfg->canopy_depth_m;
    hv_axis_t *ax = grid->axis;
    ax[HV_AX_X].origin = side == HV_SIDE_LEFT ? -far : near;
    ax[HV_AX_X].step = cfg->grid_step_m;
    ax[HV_AX_X].count = steps_in(cfg->canopy_depth_m, cfg->grid_step_m);
    ax[HV_AX_Y].origin = -cfg->grid_y_half_span_m;
    ax[HV_AX_Y].step = cfg->grid_step_m;
    ax[HV_AX_Y].count = steps_in(2.0 * cfg->grid_y_half_span_m, cfg->grid_step_m);
    ax[HV_AX_Z].origin = cfg->canopy_z_min_m;
    ax[HV_AX_Z].step = cfg->grid_step_m;
    ax[HV_AX_Z].count = steps_in(cfg->canopy_height_m, cfg->grid_step_m);
    ax[HV_AX_YAW].origin = -cfg->pick_yaw_max_rad;
    ax[HV_AX_YAW].step = cfg->grid_yaw_step_rad;
    ax[HV_AX_YAW].count = steps_in(2.0 * cfg->pick_yaw_max_rad, cfg->grid_yaw_step_rad);
}

double hv_config_stop_time_s(const hv_config_t *cfg)
{
    /* a stop-to-stop move of d >= v^2/a takes d/v + v/a on the trapezoid: v/a is what
     * stopping there costs beyond driving through */
    return cfg->pick_cycle ? cfg->vehicle_speed_mps / cfg->vehicle_accel_mps2 : cfg->stop_penalty_s;
}
