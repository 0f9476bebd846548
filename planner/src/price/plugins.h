/* The branch-and-price's plugin records (bp.h), one per plugin file: only the registry
 * (plugins.c) names them. */
#ifndef HV_PRICE_PLUGINS_H
#define HV_PRICE_PLUGINS_H

#include <stddef.h>

#include "bp.h"

extern const bp_plugin_t bp_pricer;                /* pricer.c */
extern const bp_plugin_t bp_branch_count;          /* branch_count.c */
extern const bp_plugin_t bp_branch_fruit;          /* branch_fruit.c */
extern const bp_plugin_t bp_sep_subset_row;        /* sep_subset_row.c */
extern const bp_plugin_t bp_heur_round;            /* heur_round.c */
extern const bp_plugin_t bp_heur_rins;             /* heur_rins.c */
extern const bp_plugin_t bp_heur_polish;           /* heur_polish.c */
extern const bp_plugin_t bp_heur_dive;             /* heur_dive.c */
extern const bp_plugin_t bp_heur_window_start;     /* heur_window.c */
extern const bp_plugin_t bp_heur_window;           /* heur_window.c */
extern const bp_plugin_t bp_region_capture_plugin; /* region.c */
extern const bp_plugin_t bp_region;                /* region.c */

/* Every plugin, for bp_plugins_include; *n receives their number. */
const bp_plugin_t *const *bp_plugins_all(size_t *n);

#endif /* HV_PRICE_PLUGINS_H */
