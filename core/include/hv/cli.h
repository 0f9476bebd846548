/* Command-line errors as every program prints them (docs/EXIT_CODES.md): one line on
 * stderr, "PROGRAM: what: why", then the program exits HV_EXIT_USAGE. */
#ifndef HV_CLI_H
#define HV_CLI_H

#include "hv/exit_codes.h"

#ifdef __cplusplus
extern "C" {
#endif

/* getopt_long's refusal of `arg` (argv[optind - 1]) when it returned `opt` '?' or ':'
 * (the optstring starting with ':', opterr = 0), `optopt` as it left it:
 * "PROGRAM: --bogus: unknown option (see --help)", "PROGRAM: --out: needs a value (see
 * --help)" or "PROGRAM: --quiet=1: takes no value (see --help)". */
void hv_cli_option_error(const char *program, int opt, int optopt, const char *arg);

/* "PROGRAM: WHAT: WHY (see --help)", e.g. WHAT "--config", WHY "required". */
void hv_cli_usage_error(const char *program, const char *what, const char *why);

#ifdef __cplusplus
}
#endif

#endif
