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
