/* Ownership helpers of hv_plan_t. */
#include "hv/plan.h"

#include <stdlib.h>
#include <string.h>

void hv_plan_free(hv_plan_t *plan)
{
    if (plan == NULL) {
        return;
    }
    for (size_t s = 0; s < plan->n_stops && plan->stops != NULL; ++s) {
        free(plan->stops[s].left);
        free(plan->stops[s].right);
    }
    free(plan->stops);
    free(plan->unreachable);
    memset(plan, 0, sizeof *plan);
}

hv_status_t hv_plan_copy_str(char *dst, size_t cap, const char *src)
{
    if (dst == NULL || src == NULL || cap == 0) {
        return HV_ERR_ARG;
    }
    size_t n = strlen(src);
    if (n >= cap) {
        dst[0] = '\0';
        return HV_ERR_ARG;
    }
    memcpy(dst, src, n + 1);
    return HV_OK;
}
