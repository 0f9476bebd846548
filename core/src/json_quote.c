/* hv_json_quote (json_quote.h). */
#include "hv/json_quote.h"

#include <stdio.h>
#include <string.h>

char *hv_json_quote(const char *s, char *out, size_t n)
{
    if (out == NULL || n == 0)
        return out;
    out[0] = '\0';
    if (n < 3)
        return out;
    size_t k = 0;
    out[k++] = '"';
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        char piece[8];
        if (*p == '"' || *p == '\\')
            snprintf(piece, sizeof piece, "\\%c", *p);
        else if (*p < 0x20)
            snprintf(piece, sizeof piece, "\\u%04x", (unsigned)*p);
        else
            snprintf(piece, sizeof piece, "%c", *p);
        size_t len = strlen(piece);
        if (k + len + 2 > n) /* a piece goes in whole with the closing quote, or not at all */
            break;
        memcpy(out + k, piece, len);
        k += len;
    }
    out[k++] = '"';
    out[k] = '\0';
    return out;
}
