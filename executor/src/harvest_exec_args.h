/* harvest-exec's command line (private to the program): the usage text, the options and
 * their parsing. Every refusal is one line on stderr naming the option (hv/cli.h). */
#ifndef HV_HARVEST_EXEC_ARGS_H
#define HV_HARVEST_EXEC_ARGS_H

/* The options (s, m/s; NULL: not given). */
typedef struct exec_args {
    const char *plan, *config, *table[2], *transport, *channel, *journal, *lcm_url, *summary;
    const char *clear_by; /* --clear-estop, or NULL */
    int port, quiet, check_only, online;
    double time_scale, margin, slack_s, startup_s, hb_timeout_s, latency_s;
    long max_retries;
} exec_args_t;

/* 0, or -1 after a line on stderr; --help and --version print and exit 0. */
int exec_args_parse(int argc, char **argv, exec_args_t *o);

#endif /* HV_HARVEST_EXEC_ARGS_H */
