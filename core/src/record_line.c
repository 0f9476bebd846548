/* Checksummed journal records (see hv/record_line.h). */
#define _POSIX_C_SOURCE 200809L
#include "hv/record_line.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
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
    char *end;
    unsigned long want = strtoul(star + 2, &end, 16);
    if (*end != '\0' || end == star + 2) {
        return HV_RECORD_BAD_FIELD;
    }
    if (hv_crc32(0, line, (size_t)(star - line)) != (uint32_t)want) {
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
