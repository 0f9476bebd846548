/* Fruit map CSV reader and writer (fruit_map.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/file_io.h"
#include "hv/fruit_id.h"
#include "hv/fruit_map.h"

#define MAP_FIELDS 6

/* an id that passes hv_fruit_id_check() fits hv_fruit_t.id with its NUL */
typedef char hv_fruit_id_fits[HV_FRUIT_ID_LEN > HV_FRUIT_ID_MAX_CHARS ? 1 : -1];

static const char *const k_field_names[MAP_FIELDS] = {"id", "side", "x", "y", "z", "yaw"};

static hv_status_t map_fail(char *err, size_t errlen, hv_status_t code, const char *name, int line,
                            const char *field, const char *fmt, ...)
{
    if (err != NULL && errlen > 0) {
        char msg[200];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        if (line > 0) {
            snprintf(err, errlen, "%s:%d: %s: %s", name, line, field, msg);
        } else {
            snprintf(err, errlen, "%s: %s: %s", name, field, msg);
        }
    }
    return code;
}

void hv_fruitmap_limits_from_config(const hv_config_t *cfg, double row_start_m, double row_length_m,
                                    hv_fruitmap_limits_t *lim)
{
    hv_config_grid(cfg, HV_SIDE_LEFT, &lim->grid[HV_SIDE_LEFT]);
    hv_config_grid(cfg, HV_SIDE_RIGHT, &lim->grid[HV_SIDE_RIGHT]);
    lim->y_min_m = row_start_m;
    lim->y_max_m = row_start_m + row_length_m;
}

void hv_fruitmap_free(hv_fruitmap_t *map)
{
    if (map != NULL) {
        free(map->fruits);
        map->fruits = NULL;
        map->n = 0;
    }
}

/* Trim spaces and a trailing CR in place: [*b, *e). */
static void trim(const char **b, const char **e)
{
    while (*b < *e && (**b == ' ' || **b == '\t')) {
        ++*b;
    }
    while (*e > *b && ((*e)[-1] == ' ' || (*e)[-1] == '\t' || (*e)[-1] == '\r')) {
        --*e;
    }
}

typedef struct id_line {
    const char *id;
    int line;
} id_line_t;

static int cmp_id_line(const void *a, const void *b)
{
    const id_line_t *x = a, *y = b;
    int c = strcmp(x->id, y->id);
    return c != 0 ? c : (x->line > y->line) - (x->line < y->line);
}

static hv_status_t parse_line(const char *b, const char *e, const char *name, int line,
                              const hv_fruitmap_limits_t *lim, hv_fruit_t *f, char *err,
                              size_t errlen)
{
    const char *fb[MAP_FIELDS], *fe[MAP_FIELDS];
    int nf = 0;
    const char *p = b;
    for (;;) {
        const char *c = memchr(p, ',', (size_t)(e - p));
        const char *end = c ? c : e;
        if (nf < MAP_FIELDS) {
            fb[nf] = p;
            fe[nf] = end;
        }
        ++nf;
        if (c == NULL) {
            break;
        }
        p = c + 1;
    }
    if (nf != MAP_FIELDS) {
        return map_fail(err, errlen, HV_ERR_PLAN_MAP_SYNTAX, name, line, "line",
                        "expected 6 fields (id,side,x,y,z,yaw), found %d", nf);
    }
    for (int i = 0; i < MAP_FIELDS; ++i) {
        trim(&fb[i], &fe[i]);
    }
    size_t idlen = (size_t)(fe[0] - fb[0]);
    hv_diag_t d;
    if (hv_fruit_id_check(fb[0], idlen, &d) != HV_OK) {
        return map_fail(err, errlen, HV_ERR_PLAN_MAP_ID, name, line, d.field, "%s", d.message);
    }
    memcpy(f->id, fb[0], idlen);
    f->id[idlen] = '\0';

    size_t slen = (size_t)(fe[1] - fb[1]);
    if (slen == 1 && (fb[1][0] == 'L' || fb[1][0] == 'R')) {
        f->side = fb[1][0] == 'L' ? HV_SIDE_LEFT : HV_SIDE_RIGHT;
    } else {
        return map_fail(err, errlen, HV_ERR_PLAN_MAP_SIDE, name, line, "side",
                        "expected L or R, got \"%.*s\"", (int)(slen > 20 ? 20 : slen), fb[1]);
    }

    double v[4];
    for (int i = 0; i < 4; ++i) {
        const char *nb = fb[2 + i], *ne = fe[2 + i];
        char tmp[64];
        size_t n = (size_t)(ne - nb);
        if (n == 0 || n >= sizeof tmp) {
            return map_fail(err, errlen, HV_ERR_PLAN_MAP_SYNTAX, name, line, k_field_names[2 + i],
                            n == 0 ? "empty" : "too long");
        }
        memcpy(tmp, nb, n);
        tmp[n] = '\0';
        char *endp = NULL;
        v[i] = strtod(tmp, &endp);
        if (endp != tmp + n) {
            return map_fail(err, errlen, HV_ERR_PLAN_MAP_SYNTAX, name, line, k_field_names[2 + i],
                            "not a number: \"%s\"", tmp);
        }
        if (!isfinite(v[i])) {
            return map_fail(err, errlen, HV_ERR_PLAN_MAP_NAN, name, line, k_field_names[2 + i],
                            "not finite: \"%s\"", tmp);
        }
    }
    f->x_m = v[0];
    f->y_m = v[1];
    f->z_m = v[2];
    f->yaw_rad = v[3];

    if (lim != NULL) {
        const hv_grid_t *g = &lim->grid[f->side];
        const char *sname = f->side == HV_SIDE_LEFT ? "left" : "right";
        static const int axes[3] = {HV_AX_X, HV_AX_Z, HV_AX_YAW};
        const double vals[3] = {f->x_m, f->z_m, f->yaw_rad};
        const char *names[3] = {"x", "z", "yaw"};
        for (int a = 0; a < 3; ++a) {
            const hv_axis_t *ax = &g->axis[axes[a]];
            if (hv_axis_index(ax, vals[a]) < 0) {
                double lo = ax->origin, hi = ax->origin + ax->step * (ax->count - 1);
                return map_fail(err, errlen, HV_ERR_PLAN_MAP_RANGE, name, line, names[a],
                                "%g outside the %s table grid [%g, %g]", vals[a], sname, lo, hi);
            }
        }
        if (f->y_m < lim->y_min_m || f->y_m > lim->y_max_m) {
            return map_fail(err, errlen, HV_ERR_PLAN_MAP_RANGE, name, line, "y",
                            "%g outside the row [%g, %g]", f->y_m, lim->y_min_m, lim->y_max_m);
        }
    }
    return HV_OK;
}

hv_status_t hv_fruitmap_parse(const char *text, size_t len, const char *name,
                              const hv_fruitmap_limits_t *lim, hv_fruitmap_t *map, char *err,
                              size_t errlen)
{
    if (text == NULL || map == NULL) {
        return HV_ERR_ARG;
    }
    if (name == NULL) {
        name = "(fruit map)";
    }
    map->n = 0;
    map->fruits = NULL;

    /* Upper bound on fruit lines: newlines + 1. */
    size_t cap = 1;
    for (size_t i = 0; i < len; ++i) {
        cap += text[i] == '\n';
    }
    hv_fruit_t *fruits = calloc(cap, sizeof *fruits);
    id_line_t *ids = calloc(cap, sizeof *ids);
    if (fruits == NULL || ids == NULL) {
        free(fruits);
        free(ids);
        return map_fail(err, errlen, HV_ERR_PLAN_NOMEM, name, 0, "map", "out of memory");
    }

    hv_status_t st = HV_OK;
    size_t n = 0;
    int line = 0, header_seen = 0;
    const char *p = text, *end = text + len;
    while (p < end && st == HV_OK) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        const char *b = p, *e = le;
        ++line;
        p = nl ? nl + 1 : end;
        if (memchr(b, '\0', (size_t)(e - b)) != NULL) {
            st = map_fail(err, errlen, HV_ERR_PLAN_MAP_SYNTAX, name, line, "line",
                          "NUL byte (not a text file?)");
            break;
        }
        trim(&b, &e);
        if (!header_seen) {
            /* a UTF-8 byte-order mark is tolerated before the header */
            if (e - b >= 3 && memcmp(b, "\xEF\xBB\xBF", 3) == 0) {
                b += 3;
            }
            if ((size_t)(e - b) != strlen("id,side,x,y,z,yaw") ||
                memcmp(b, "id,side,x,y,z,yaw", (size_t)(e - b)) != 0) {
                st = map_fail(err, errlen, HV_ERR_PLAN_MAP_HEADER, name, line, "header",
                              "expected \"id,side,x,y,z,yaw\", got \"%.*s\"",
                              (int)(e - b > 60 ? 60 : e - b), b);
                break;
            }
            header_seen = 1;
            continue;
        }
        if (b == e) {
            continue;
        }
        st = parse_line(b, e, name, line, lim, &fruits[n], err, errlen);
        if (st == HV_OK) {
            ids[n].id = fruits[n].id;
            ids[n].line = line;
            ++n;
        }
    }
    if (st == HV_OK && !header_seen) {
        st = map_fail(err, errlen, HV_ERR_PLAN_MAP_EMPTY, name, 0, "map",
                      "empty file (no header, no fruit)");
    } else if (st == HV_OK && n == 0) {
        st = map_fail(err, errlen, HV_ERR_PLAN_MAP_EMPTY, name, 0, "map",
                      "no fruit after the header");
    }
    if (st == HV_OK) {
        qsort(ids, n, sizeof *ids, cmp_id_line);
        for (size_t i = 1; i < n; ++i) {
            if (strcmp(ids[i - 1].id, ids[i].id) == 0) {
                st = map_fail(err, errlen, HV_ERR_PLAN_MAP_DUPLICATE, name, ids[i].line, "id",
                              "duplicate id \"%s\" (first on line %d)", ids[i].id, ids[i - 1].line);
                break;
            }
        }
    }
    free(ids);
    if (st != HV_OK) {
        free(fruits);
        return st;
    }
    map->n = n;
    map->fruits = fruits;
    return HV_OK;
}

hv_status_t hv_fruitmap_load(const char *path, const hv_fruitmap_limits_t *lim, hv_fruitmap_t *map,
                             char *err, size_t errlen)
{
    if (path == NULL || map == NULL) {
        return HV_ERR_ARG;
    }
    map->n = 0;
    map->fruits = NULL;
    void *data = NULL;
    size_t len = 0;
    hv_status_t st = hv_file_read_all(path, &data, &len, err, errlen);
    if (st != HV_OK) {
        return st;
    }
    st = hv_fruitmap_parse(data, len, path, lim, map, err, errlen);
    free(data);
    return st;
}

hv_status_t hv_fruitmap_save(const char *path, const hv_fruit_t *fruits, size_t n, char *err,
                             size_t errlen)
{
    if (path == NULL || (fruits == NULL && n > 0)) {
        return HV_ERR_ARG;
    }
    /* a line: an id of at most 31 characters, the side and four %.17g numbers */
    const size_t line_max = HV_FRUIT_ID_LEN + 4 + 4 * 26;
    const char header[] = "id,side,x,y,z,yaw\n";
    size_t cap = sizeof header + n * line_max;
    char *buf = malloc(cap);
    if (buf == NULL) {
        return map_fail(err, errlen, HV_ERR_PLAN_NOMEM, path, 0, "map", "out of memory");
    }
    size_t len = (size_t)snprintf(buf, cap, "%s", header);
    for (size_t i = 0; i < n; ++i) {
        const hv_fruit_t *f = &fruits[i];
        len += (size_t)snprintf(buf + len, cap - len, "%s,%c,%.17g,%.17g,%.17g,%.17g\n", f->id,
                                f->side == HV_SIDE_LEFT ? 'L' : 'R', f->x_m, f->y_m, f->z_m,
                                f->yaw_rad);
    }
    hv_status_t st = hv_file_write_atomic(path, buf, len, err, errlen);
    free(buf);
    return st;
}
