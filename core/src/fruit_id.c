/* Fruit id check (hv/fruit_id.h). */
#include "hv/fruit_id.h"

#include <stdio.h>

#define ID_SET "A-Z a-z 0-9 _ . -"

/* The set by hand, not <ctype.h>: isalnum() follows the locale, the id set must not. */
int hv_fruit_id_char(int c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
}

static hv_status_t id_fail(hv_diag_t *diag, const char *message)
{
    if (diag != NULL) {
        snprintf(diag->field, sizeof diag->field, "id");
        snprintf(diag->message, sizeof diag->message, "%s", message);
        diag->line = 0;
    }
    return HV_ERR_FRUIT_ID;
}

hv_status_t hv_fruit_id_check(const char *id, size_t len, hv_diag_t *diag)
{
    if (id == NULL) {
        return HV_ERR_ARG;
    }
    char msg[120];
    if (len == 0) {
        return id_fail(diag, "empty");
    }
    if (len > HV_FRUIT_ID_MAX_CHARS) {
        snprintf(msg, sizeof msg, "%zu characters, more than %d", len, HV_FRUIT_ID_MAX_CHARS);
        return id_fail(diag, msg);
    }
    for (size_t i = 0; i < len; ++i) {
        unsigned char c = (unsigned char)id[i];
        if (!hv_fruit_id_char(c)) {
            snprintf(msg, sizeof msg,
                     "character 0x%02x at position %zu not allowed (only " ID_SET ")", (unsigned)c,
                     i + 1);
            return id_fail(diag, msg);
        }
    }
    return HV_OK;
}
