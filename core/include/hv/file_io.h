/* File helpers for hosted programs (library hv_core_io; core itself makes no OS calls).
 *
 * Messages are one line: "<path>: <field>: <message>", ready for stderr.
 */
#ifndef HV_FILE_IO_H
#define HV_FILE_IO_H

#include <stddef.h>

#include "hv/config.h"
#include "hv/cost_table.h"
#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Read a whole file into a malloc'd buffer (*data, *len; one extra NUL byte after it).
 * HV_ERR_IO with `err` (errlen bytes) describing the failure. Free with free(). */
hv_status_t hv_file_read_all(const char *path, void **data, size_t *len, char *err, size_t errlen);

/* Write `len` bytes to `path` atomically: a temporary file in the same folder, fsync,
 * rename. A failure never leaves a half-written file at `path`. */
hv_status_t hv_file_write_atomic(const char *path, const void *data, size_t len, char *err,
                                 size_t errlen);

/* Load and parse a configuration file. */
hv_status_t hv_config_load(const char *path, hv_config_t *cfg, char *err, size_t errlen);

/* A loaded cost table: owns its buffer. */
typedef struct hv_costtab_file {
    hv_costtab_t tab;
    void *buffer;
    size_t size;
} hv_costtab_file_t;

/* Read and validate a cost table file. On error nothing is kept allocated. */
hv_status_t hv_costtab_load(const char *path, hv_costtab_file_t *file, char *err, size_t errlen);
void hv_costtab_unload(hv_costtab_file_t *file);

/* Read a table (hv_costtab_load) and check it against the configuration's `side` arm and
 * grid (hv_costtab_expect_arm); nothing is kept. HV_ERR_TAB_MISMATCH with "<path>:
 * <field>: <why> (HV_ERR_TAB_MISMATCH)" in err when it was built for another mount, joint
 * limits, home pose, elbow mode or grid. Every program that takes a table checks it so. */
hv_status_t hv_costtab_check_for(const char *path, const hv_config_t *cfg, hv_side_t side,
                                 char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* HV_FILE_IO_H */
