/* A string as a JSON string literal, for the programs' hand-written JSON summaries (library
 * hv_core_io): the summaries quote messages and paths, which may hold quotes. */
#ifndef HV_JSON_QUOTE_H
#define HV_JSON_QUOTE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* s between double quotes, with `"`, `\` and control characters escaped (other bytes as
 * they are), into out (n bytes, NUL-terminated, cut short when too small). Returns out. */
char *hv_json_quote(const char *s, char *out, size_t n);

#ifdef __cplusplus
}
#endif
#endif /* HV_JSON_QUOTE_H */
