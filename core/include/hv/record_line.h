/* Checksummed text records for append-only journals (library hv_core_io): the executor's
 * harvest journal and the online planner's journal share this framing.
 *
 * A record is one line: its text, " *", the CRC-32 (hv_crc32, 8 hex digits) of the text,
 * and a newline. It is written with one write() (the loop only continues a short write),
 * so a crash leaves at most the last line torn (no newline), which a reader cuts off.
 */
#ifndef HV_RECORD_LINE_H
#define HV_RECORD_LINE_H

#include <stddef.h>

#include "hv/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bytes the framing adds to a record's text: " *" + 8 hex digits + newline (and a NUL). */
#define HV_RECORD_FRAMING 12u

/* Frame the `len` bytes of text in `line` (capacity `cap` bytes, at least len +
 * HV_RECORD_FRAMING) and write them to `fd`; fdatasync() too when `sync` (else the caller
 * syncs a batch once). HV_ERR_IO on a failed write or sync (errno says why), HV_ERR_ARG
 * when the framing does not fit. */
hv_status_t hv_record_write(int fd, char *line, size_t len, size_t cap, int sync);

typedef enum hv_record_check {
    HV_RECORD_OK = 0,    /* the checksum matches: the text ends where " *" was */
    HV_RECORD_NO_SUM,    /* no " *" in the line */
    HV_RECORD_BAD_FIELD, /* what follows " *" is not 8 lowercase hex digits */
    HV_RECORD_MISMATCH   /* the text is not what was written (corrupt record) */
} hv_record_check_t;

/* Check one complete line (`len` bytes, without its newline, NUL-terminated at len); on
 * HV_RECORD_OK the line is cut to its text (a NUL where " *" began). */
hv_record_check_t hv_record_check(char *line, size_t len);

/* What a check result means, for an error message ("no checksum", ...). */
const char *hv_record_check_name(hv_record_check_t c);

#ifdef __cplusplus
}
#endif
#endif /* HV_RECORD_LINE_H */
