/* See fuzz_support.h. */
#include "fuzz_support.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "hv/file_io.h"

void hv_fuzz_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "fuzz: property broken: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    abort();
}

int hv_fuzz_next(hv_fuzz_reader_t *r)
{
    if (r->n == 0)
        return -1;
    r->n--;
    return *r->p++;
}

uint8_t hv_fuzz_byte(hv_fuzz_reader_t *r)
{
    int b = hv_fuzz_next(r);
    return b < 0 ? 0 : (uint8_t)b;
}

void hv_fuzz_source_path(const char *rel, char *buf, size_t len)
{
    snprintf(buf, len, "%s/%s", HV_SOURCE_DIR, rel);
}

const hv_config_t *hv_fuzz_config(void)
{
    static hv_config_t cfg;
    static int loaded;
    if (!loaded) {
        char path[1024], err[512];
        hv_fuzz_source_path("config/harvest.cfg", path, sizeof path);
        if (hv_config_load(path, &cfg, err, sizeof err) != HV_OK) {
            fprintf(stderr, "fuzz: %s\n", err);
            abort();
        }
        loaded = 1;
    }
    return &cfg;
}
