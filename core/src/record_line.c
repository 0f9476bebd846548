/* Checksummed journal records (see hv/record_line.h). */
#define _POSIX_C_SOURCE 200809L
#include "hv/record_line.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <unistd.h>

#include "hv/cost_table.h" /* hv_crc32 */

hv_status_t hv_record_write(int fd, char *line, size_t len, size_t cap, int sync)
{
    if (fd < 0 || line == NULL || cap < len + HV_RECORD_FRAMING) {
        return HV_ERR_ARG;
    }
    uint32_t crc = hv_crc32(0, line, len);
    int n = snprintf(line + len, cap - len, " *%08x\n", (unsigned)crc);
    if (n < 0 || (size_t)n >= cap - len) {
        return HV_ERR_ARG;
    }
    len += (size_t)n;
    size_t off = 0;
    while (off < len) {
        ssize_t w = write(fd, line + off, len - off);
        if (w < 0) {
            if (errno == EINTR) {
                continue;
            }
            return HV_ERR_IO;
        }
        off += (size_t)w;
    }
    if (sync && fdatasync(fd) != 0) {
        return HV_ERR_IO;
    }
    return HV_OK;
}

/* The checksum field exactly as written ("%08x": 8 lowercase hex digits, nothing after).
 * strtoul would also take a sign, spaces, "0x" and upper case, so a damaged field could
 * still read as the right value and the damage go unseen. */
static int crc_field(const char *s, uint32_t *out)
{
    uint32_t v = 0;
    for (int i = 0; i < 8; i++) {
        char ch = s[i];
        if (ch >= '0' && ch <= '9') {
            v = (v << 4) | (uint32_t)(ch - '0');
        } else if (ch >= 'a' && ch <= 'f') {
            v = (v << 4) | (uint32_t)(ch - 'a' + 10);
        } else {
            return -1;
        }
    }
    if (s[8] != '\0') {
        return -1;
    }
    *out = v;
    return 0;
}

hv_record_check_t hv_record_check(char *line, size_t len)
{
    char *star = NULL;
    for (size_t i = len; i >= 2; i--) {
        if (line[i - 2] == ' ' && line[i - 1] == '*') {
            star = line + i - 2;
            break;
        }
    }
    if (star == NULL) {
        return HV_RECORD_NO_SUM;
    }
    uint32_t want;
    if (crc_field(star + 2, &want) != 0) {
        return HV_RECORD_BAD_FIELD;
    }
    if (hv_crc32(0, line, (size_t)(star - line)) != want) {
        return HV_RECORD_MISMATCH;
    }
    *star = '\0';
    return HV_RECORD_OK;
}

const char *hv_record_check_name(hv_record_check_t c)
{
    switch (c) {
    case HV_RECORD_OK: return "ok";
    case HV_RECORD_NO_SUM: return "no checksum";
    case HV_RECORD_BAD_FIELD: return "bad checksum field";
    case HV_RECORD_MISMATCH: return "checksum mismatch (corrupt record)";
    }
    return "?";
}
