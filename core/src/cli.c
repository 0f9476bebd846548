/* Command-line error lines (hv/cli.h). */
#include "hv/cli.h"

#include <stdio.h>
#include <string.h>

void hv_cli_usage_error(const char *program, const char *what, const char *why)
{
    fprintf(stderr, "%s: %s: %s (see --help)\n", program, what, why);
}

void hv_cli_option_error(const char *program, int opt, int optopt, const char *arg)
{
    /* getopt_long leaves optopt 0 for a long option it does not know, and the option's
     * value for a known one given "=value" that takes none */
    const char *why = opt == ':'                                  ? "needs a value"
                      : optopt != 0 && strncmp(arg, "--", 2) == 0 ? "takes no value"
                                                                  : "unknown option";
    hv_cli_usage_error(program, arg, why);
}
