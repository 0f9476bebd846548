/* The check of the executor's parameters (private to src/exec_*.c); exec_params.c also
 * holds their defaults (hv_exec_params_default). */
#ifndef HV_EXEC_PARAMS_H
#define HV_EXEC_PARAMS_H

#include "hv/exec_state.h"

/* Every field in its range (hv/exec_state.h says each): 1, else 0. */
int exec_params_ok(const hv_exec_params_t *p);

#endif /* HV_EXEC_PARAMS_H */
