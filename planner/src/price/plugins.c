/* The branch-and-price's plugins (plugins.h). bp_plugins_include orders them by timing
 * and then priority; the order within a timing is the search's:
 *   BP_AT_START     windows-helper (the helper thread polishes and re-plans windows from
 *                   the start of the root)
 *   BP_PRICE        pricer
 *   BP_ROOT_LP      region-capture (the duals before any cut), subset-row
 *   BP_ROOT_SOLVED  polish
 *   BP_BRANCH       count (interval counts far from integral first), fruit
 *   BP_NODE_LP      rounding (cheap, often), rins (sub-solves, every rins_every nodes)
 *   BP_AFTER_ROOT   column-dive, windows (the dive's plan is the windows' start)
 *   BP_BEFORE_NODE  region */
#include "plugins.h"

static const bp_plugin_t *const all[] = {
    &bp_heur_window_start, &bp_pricer,       &bp_region_capture_plugin, &bp_sep_subset_row,
    &bp_heur_polish,       &bp_branch_count, &bp_branch_fruit,          &bp_heur_round,
    &bp_heur_rins,         &bp_heur_dive,    &bp_heur_window,           &bp_region,
};

const bp_plugin_t *const *bp_plugins_all(size_t *n)
{
    *n = sizeof all / sizeof all[0];
    return all;
}
