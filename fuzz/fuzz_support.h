/* Shared by the fuzz targets: the project's config and a fixed plan, loaded once, and the
 * one way a target reports a broken property (a crash, so libFuzzer keeps the input).
 *
 * libFuzzer calls LLVMFuzzerTestOneInput once per input with no context argument, so what
 * every input shares (the config, the prepared plan) is built on first use and kept in
 * static storage: the harness's only state, never written after that first call. */
#ifndef HV_FUZZ_SUPPORT_H
#define HV_FUZZ_SUPPORT_H

#include <stddef.h>
#include <stdint.h>

#include "hv/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* libFuzzer's entry point, defined by each target. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* config/harvest.cfg of the source tree (aborts when it cannot be read). */
const hv_config_t *hv_fuzz_config(void);

/* "<source>/<rel>" into buf. */
void hv_fuzz_source_path(const char *rel, char *buf, size_t len);

/* An input read byte by byte. */
typedef struct hv_fuzz_reader {
    const uint8_t *p;
    size_t n;
} hv_fuzz_reader_t;

/* The next input byte, -1 at the end. */
int hv_fuzz_next(hv_fuzz_reader_t *r);
/* The next input byte, 0 at the end. */
uint8_t hv_fuzz_byte(hv_fuzz_reader_t *r);

/* A property the target checks does not hold: print why and abort. */
void hv_fuzz_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));

#ifdef __cplusplus
}
#endif
#endif /* HV_FUZZ_SUPPORT_H */
