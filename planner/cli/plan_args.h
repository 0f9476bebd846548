/* harvest-plan's command line (private to planner/cli): the usage text, the options of a
 * planning run and of `harvest-plan check`, their parsing and their checks against each
 * other. Every refusal is one line on stderr naming the option (hv/cli.h). */
#ifndef HV_PLAN_ARGS_H
#define HV_PLAN_ARGS_H

/* A planning run's options (m, s; 0 or NULL: not given). */
typedef struct plan_args {
    const char *config, *left, *right, *fruits, *method, *out, *export_lp, *algorithm;
    double time_limit_s, gap, fov_width_m, fov_offset_m, horizon_m, commit_m, row_length_m;
    int quiet;
    int compare_single;
    int threads; /* 0: the default */
} plan_args_t;

/* `harvest-plan check`'s options: the plan file, and the inputs that override its own. */
typedef struct plan_check_args {
    const char *plan, *config, *left, *right, *fruits;
    int quiet;
} plan_check_args_t;

/* Each returns 0 to go on, 1 when it printed what was asked (--help, --version,
 * --help-params: exit 0), else HV_EXIT_USAGE after its message. */
int plan_args_parse(int argc, char **argv, plan_args_t *a);
/* argv[1] is "check". */
int plan_args_parse_check(int argc, char **argv, plan_check_args_t *c);

#endif /* HV_PLAN_ARGS_H */
