/* Fuzz target: the fruit map CSV reader (hv_fruitmap_parse, docs/FRAMES.md).
 * Properties: no crash, leak or undefined behaviour; a refusal names the file (and the
 * line and field); an accepted map holds finite poses inside the configured limits, each
 * id once. The input's first byte chooses with or without the range check. */
#include <math.h>
#include <string.h>

#include "fuzz_support.h"
#include "hv/fruit_map.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    const hv_config_t *cfg = hv_fuzz_config();
    hv_fruitmap_limits_t lim;
    hv_fruitmap_limits_from_config(cfg, 0.0, cfg->row_length_m, &lim);
    const hv_fruitmap_limits_t *use = (data[0] & 1) ? NULL : &lim;
    hv_fruitmap_t map;
    char err[512] = "";
    hv_status_t st =
        hv_fruitmap_parse((const char *)data + 1, size - 1, "in.csv", use, &map, err, sizeof err);
    if (st != HV_OK) {
        if (strncmp(err, "in.csv", 6) != 0 || map.n != 0)
            hv_fuzz_fail("refused (%s) without naming the file, or kept fruit: '%s'",
                         hv_status_name(st), err);
        return 0;
    }
    for (size_t i = 0; i < map.n; i++) {
        const hv_fruit_t *f = &map.fruits[i];
        if (!isfinite(f->x_m) || !isfinite(f->y_m) || !isfinite(f->z_m) || !isfinite(f->yaw_rad))
            hv_fuzz_fail("fruit %zu accepted with a non-finite pose", i);
        if (use && (f->y_m < lim.y_min_m || f->y_m > lim.y_max_m))
            hv_fuzz_fail("fruit %zu accepted at y = %g outside the row", i, f->y_m);
        for (size_t k = 0; k < i && map.n <= 4096; k++)
            if (strcmp(map.fruits[k].id, f->id) == 0)
                hv_fuzz_fail("fruit id '%s' accepted twice", f->id);
    }
    hv_fruitmap_free(&map);
    return 0;
}
