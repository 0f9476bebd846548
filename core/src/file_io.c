/* File helpers for hosted programs: whole-file read, atomic write, and loading the config
 * and cost tables with one-line messages "<path>: <field>: <message>". */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hv/file_io.h"

static void set_err(char *err, size_t errlen, const char *path, const char *field, const char *msg)
{
    if (err != NULL && errlen > 0) {
        snprintf(err, errlen, "%s: %s: %s", path, field, msg);
    }
}

hv_status_t hv_file_read_all(const char *path, void **data, size_t *len, char *err, size_t errlen)
{
    if (path == NULL || data == NULL || len == NULL) {
        return HV_ERR_ARG;
    }
    *data = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        set_err(err, errlen, path, "open", strerror(errno));
        return HV_ERR_IO;
    }
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        set_err(err, errlen, path, "open", "not a regular file");
        fclose(f);
        return HV_ERR_IO;
    }
    size_t size = (size_t)st.st_size;
    char *buf = malloc(size + 1);
    if (buf == NULL) {
        set_err(err, errlen, path, "read", "out of memory");
        fclose(f);
        return HV_ERR_NOMEM;
    }
    size_t got = fread(buf, 1, size, f);
    int failed = ferror(f);
    fclose(f);
    if (failed || got != size) {
        set_err(err, errlen, path, "read", "short read");
        free(buf);
        return HV_ERR_IO;
    }
    buf[size] = '\0';
    *data = buf;
    *len = size;
    return HV_OK;
}

hv_status_t hv_file_write_atomic(const char *path, const void *data, size_t len, char *err,
                                 size_t errlen)
{
    if (path == NULL || (data == NULL && len > 0)) {
        return HV_ERR_ARG;
    }
    size_t plen = strlen(path);
    char *tmp = malloc(plen + 16);
    if (tmp == NULL) {
        return HV_ERR_NOMEM;
    }
    snprintf(tmp, plen + 16, "%s.tmp.XXXXXX", path);
    int fd = mkstemp(tmp);
    if (fd < 0) {
        set_err(err, errlen, path, "create", strerror(errno));
        free(tmp);
        return HV_ERR_IO;
    }
    const char *p = data;
    size_t left = len;
    while (left > 0) {
        ssize_t n = write(fd, p, left);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            set_err(err, errlen, path, "write", strerror(errno));
            close(fd);
            unlink(tmp);
            free(tmp);
            return HV_ERR_IO;
        }
        p += n;
        left -= (size_t)n;
    }
    if (fchmod(fd, 0644) != 0 || fsync(fd) != 0 || close(fd) != 0) {
        set_err(err, errlen, path, "sync", strerror(errno));
        unlink(tmp);
        free(tmp);
        return HV_ERR_IO;
    }
    if (rename(tmp, path) != 0) {
        set_err(err, errlen, path, "rename", strerror(errno));
        unlink(tmp);
        free(tmp);
        return HV_ERR_IO;
    }
    free(tmp);
    return HV_OK;
}

hv_status_t hv_config_load(const char *path, hv_config_t *cfg, char *err, size_t errlen)
{
    void *text;
    size_t len;
    hv_status_t st = hv_file_read_all(path, &text, &len, err, errlen);
    if (st != HV_OK) {
        return st;
    }
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    st = hv_config_parse(text, len, cfg, &d);
    free(text);
    if (st != HV_OK && err != NULL && errlen > 0) {
        if (d.line > 0) {
            snprintf(err, errlen, "%s:%d: %s: %s", path, d.line, d.field, d.message);
        } else {
            snprintf(err, errlen, "%s: %s: %s", path, d.field, d.message);
        }
    }
    return st;
}

hv_status_t hv_costtab_load(const char *path, hv_costtab_file_t *file, char *err, size_t errlen)
{
    if (file == NULL) {
        return HV_ERR_ARG;
    }
    memset(file, 0, sizeof *file);
    void *buf;
    size_t len;
    hv_status_t st = hv_file_read_all(path, &buf, &len, err, errlen);
    if (st != HV_OK) {
        return st;
    }
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    st = hv_costtab_open(&file->tab, buf, len, &d);
    if (st != HV_OK) {
        set_err(err, errlen, path, d.field, d.message);
        free(buf);
        return st;
    }
    file->buffer = buf;
    file->size = len;
    return HV_OK;
}

hv_status_t hv_costtab_check_for(const char *path, const hv_config_t *cfg, hv_side_t side,
                                 char *err, size_t errlen)
{
    if (cfg == NULL) {
        return HV_ERR_ARG;
    }
    hv_costtab_file_t file;
    hv_status_t st = hv_costtab_load(path, &file, err, errlen);
    if (st != HV_OK) {
        return st;
    }
    hv_arm_t arm;
    hv_grid_t grid;
    hv_config_arm(cfg, side, &arm);
    hv_config_grid(cfg, side, &grid);
    hv_diag_t d;
    memset(&d, 0, sizeof d);
    st = hv_costtab_expect_arm(&file.tab, &arm, &grid, &d);
    if (st != HV_OK) {
        char msg[sizeof d.message + 40];
        snprintf(msg, sizeof msg, "%s (%s)", d.message, hv_status_name(st));
        set_err(err, errlen, path, d.field, msg);
    }
    hv_costtab_unload(&file);
    return st;
}

void hv_costtab_unload(hv_costtab_file_t *file)
{
    if (file != NULL) {
        free(file->buffer);
        memset(file, 0, sizeof *file);
    }
}
