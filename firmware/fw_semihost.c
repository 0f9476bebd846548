/* The journal's storage on a host file through Arm semihosting (see fw_semihost.h). */
#include "fw_semihost.h"

#include <stddef.h>
#include <string.h>

#include "fw_status.h"

/* operation numbers (Arm semihosting specification) */
#define SYS_OPEN        0x01u
#define SYS_WRITE       0x05u
#define SYS_READ        0x06u
#define SYS_SEEK        0x0Au
#define SYS_GET_CMDLINE 0x15u
/* SYS_OPEN modes, as fopen's */
#define MODE_RB_PLUS    3u /* "r+b": an existing file, read and write */
#define MODE_WB_PLUS    7u /* "w+b": created when absent */

#define JOURNAL_ARG "--journal "

/* The text after "--journal " in cmd, NULL when absent (a plain scan: newlib's strstr
 * costs the image a kilobyte). */
static const char *journal_arg(const char *cmd)
{
    size_t k = strlen(JOURNAL_ARG);
    for (; *cmd; cmd++)
        if (strncmp(cmd, JOURNAL_ARG, k) == 0)
            return cmd + k;
    return NULL;
}

/* r0 = operation, r1 = its parameter block; the result comes back in r0 */
static int32_t semihost(uint32_t op, void *params)
{
    register uint32_t r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = params;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return (int32_t)r0;
}

static int seek(hv_fw_semihost_t *s, uint32_t offset)
{
    uint32_t p[2] = {(uint32_t)s->handle, offset};
    return semihost(SYS_SEEK, p) == 0;
}

static hv_status_t sh_read(void *ctx, uint32_t offset, uint8_t *buf, uint32_t n, uint32_t *got)
{
    hv_fw_semihost_t *s = ctx;
    *got = 0;
    if (s->handle < 0)
        return HV_ERR_FW_JOURNAL_IO;
    if (!seek(s, offset))
        return HV_OK; /* beyond the end: nothing there */
    uint32_t p[3] = {(uint32_t)s->handle, (uint32_t)(uintptr_t)buf, n};
    int32_t left = semihost(SYS_READ, p); /* bytes NOT read */
    if (left < 0 || (uint32_t)left > n)
        return HV_ERR_FW_JOURNAL_IO;
    *got = n - (uint32_t)left;
    return HV_OK;
}

static hv_status_t sh_write(void *ctx, uint32_t offset, const uint8_t *buf, uint32_t n)
{
    hv_fw_semihost_t *s = ctx;
    if (s->handle < 0 || !seek(s, offset))
        return HV_ERR_FW_JOURNAL_IO;
    uint32_t p[3] = {(uint32_t)s->handle, (uint32_t)(uintptr_t)buf, n};
    return semihost(SYS_WRITE, p) == 0 ? HV_OK : HV_ERR_FW_JOURNAL_IO; /* 0: all written */
}

static int32_t open_mode(const char *path, uint32_t mode)
{
    uint32_t p[3] = {(uint32_t)(uintptr_t)path, mode, (uint32_t)strlen(path)};
    return semihost(SYS_OPEN, p);
}

hv_status_t hv_fw_semihost_open(hv_fw_semihost_t *s, hv_fw_store_t *store)
{
    char cmd[HV_FW_SEMIHOST_PATH_MAX + 32];
    uint32_t p[2] = {(uint32_t)(uintptr_t)cmd, sizeof cmd};
    memset(s, 0, sizeof *s);
    s->handle = -1;
    store->ctx = s;
    store->read = sh_read;
    store->write = sh_write;
    if (semihost(SYS_GET_CMDLINE, p) != 0 || p[1] >= sizeof cmd)
        return HV_ERR_FW_JOURNAL_IO;
    cmd[p[1]] = '\0';
    const char *arg = journal_arg(cmd);
    if (!arg)
        return HV_ERR_FW_JOURNAL_IO;
    size_t n = strlen(arg);
    if (n == 0 || n > HV_FW_SEMIHOST_PATH_MAX)
        return HV_ERR_FW_JOURNAL_IO;
    /* the name is needed for the open only: the host keeps the file by its handle */
    s->handle = open_mode(arg, MODE_RB_PLUS);
    if (s->handle < 0)
        s->handle = open_mode(arg, MODE_WB_PLUS);
    return s->handle < 0 ? HV_ERR_FW_JOURNAL_IO : HV_OK;
}
