/* Plan input paths (plan_paths.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hv/plan_paths.h"

/* Length of the folder part of `path`: "a/b/c" -> 3, "c" -> 0 (the current folder),
 * "/c" -> 1 (the root keeps its slash). */
static size_t dir_len(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (slash == NULL) {
        return 0;
    }
    return slash == path ? 1 : (size_t)(slash - path);
}

static hv_status_t fits(int n, char *out, size_t cap)
{
    if (n < 0 || (size_t)n >= cap) {
        out[0] = '\0';
        return HV_ERR_NOMEM;
    }
    return HV_OK;
}

hv_status_t hv_plan_input_resolve(const char *plan_path, const char *input, char *out, size_t cap)
{
    if (plan_path == NULL || input == NULL || out == NULL || cap == 0 || input[0] == '\0') {
        return HV_ERR_ARG;
    }
    size_t d = input[0] == '/' ? 0 : dir_len(plan_path);
    if (d == 0) {
        return fits(snprintf(out, cap, "%s", input), out, cap);
    }
    if (d == 1 && plan_path[0] == '/') {
        return fits(snprintf(out, cap, "/%s", input), out, cap);
    }
    return fits(snprintf(out, cap, "%.*s/%s", (int)d, plan_path, input), out, cap);
}

/* The real path of the folder `path` lies in (malloc'd), or NULL with `err` set. */
static char *real_dir(const char *path, char *err, size_t errlen)
{
    size_t d = dir_len(path);
    char *dir = malloc(d + 2);
    char *real = NULL;
    if (dir != NULL) {
        if (d == 0) {
            strcpy(dir, ".");
        } else {
            memcpy(dir, path, d);
            dir[d] = '\0';
        }
        real = realpath(dir, NULL);
    }
    if (real == NULL && err != NULL && errlen > 0) {
        snprintf(err, errlen, "%s: cannot resolve its folder: %s", path,
                 dir == NULL ? "out of memory" : strerror(errno));
    }
    free(dir);
    return real;
}

/* Components of an absolute, normalised path below `rest` ("/x/y" -> 2, "" and "/" -> 0). */
static size_t components(const char *rest)
{
    size_t n = 0;
    for (const char *p = rest; *p != '\0'; ++p) {
        n += p[0] == '/' && p[1] != '\0';
    }
    return n;
}

/* `to` relative to `from` (both real, absolute folders), then `base`, into out[cap]. */
static hv_status_t relative(const char *from, const char *to, const char *base, char *out,
                            size_t cap)
{
    size_t k = 0, shared = 0;
    while (from[k] != '\0' && from[k] == to[k]) {
        if (from[k] == '/') {
            shared = k;
        }
        ++k;
    }
    if ((from[k] == '\0' || from[k] == '/') && (to[k] == '\0' || to[k] == '/')) {
        shared = k; /* the whole of the shorter one is a component of the other */
    }
    size_t ups = components(from + shared);
    const char *down = to + shared;
    while (*down == '/') {
        ++down;
    }
    size_t len = 0;
    out[0] = '\0';
    for (size_t u = 0; u < ups; ++u) {
        if (fits(snprintf(out + len, cap - len, "../"), out + len, cap - len) != HV_OK) {
            return HV_ERR_NOMEM;
        }
        len += 3;
    }
    return fits(snprintf(out + len, cap - len, "%s%s%s", down, *down ? "/" : "", base), out,
                cap - len);
}

hv_status_t hv_plan_input_relative(const char *plan_path, const char *input, char *out, size_t cap,
                                   char *err, size_t errlen)
{
    if (plan_path == NULL || input == NULL || out == NULL || cap == 0 || input[0] == '\0') {
        return HV_ERR_ARG;
    }
    if (input[0] == '/') {
        hv_status_t st = fits(snprintf(out, cap, "%s", input), out, cap);
        if (st != HV_OK && err != NULL && errlen > 0) {
            snprintf(err, errlen, "%s: longer than %zu bytes", input, cap - 1);
        }
        return st;
    }
    const char *slash = strrchr(input, '/');
    const char *base = slash ? slash + 1 : input;
    if (*base == '\0' || strcmp(base, ".") == 0 || strcmp(base, "..") == 0) {
        if (err != NULL && errlen > 0) {
            snprintf(err, errlen, "%s: not a file name", input);
        }
        return HV_ERR_ARG;
    }
    char *from = real_dir(plan_path, err, errlen);
    char *to = from ? real_dir(input, err, errlen) : NULL;
    hv_status_t st = HV_ERR_IO;
    if (from != NULL && to != NULL) {
        st = relative(from, to, base, out, cap);
        if (st != HV_OK && err != NULL && errlen > 0) {
            snprintf(err, errlen, "%s: longer than %zu bytes relative to %s", input, cap - 1, from);
        }
    }
    free(from);
    free(to);
    return st;
}
