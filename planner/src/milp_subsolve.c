/* Options for the MILP's own sub-solves (milp_subsolve.h). */
#include "hv/milp_subsolve.h"

void hv_milp_subsolve_options(const hv_milp_options_t *opt, double limit_s, hv_milp_options_t *out)
{
    *out = *opt;
    out->verbose = 0;
    out->export_lp_path = NULL;
    out->time_limit_s = limit_s;
    out->tree_threads = 1;
    out->window_width = 0;
    out->polish_work = 0;
    out->rins_every = 0;
    out->region_stops = 0;
}
