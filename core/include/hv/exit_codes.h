/* The exit codes of every program (docs/EXIT_CODES.md, the one table): 0, 1 and 2 mean
 * the same everywhere; a program uses a higher code only where that table lists it. */
#ifndef HV_EXIT_CODES_H
#define HV_EXIT_CODES_H

enum {
    HV_EXIT_OK = 0,      /* done */
    HV_EXIT_FAILURE = 1, /* runtime failure: I/O, the bus, memory, a solver error */
    HV_EXIT_USAGE = 2,   /* usage or bad input: nothing done, the option or file named */

    /* harvest-plan */
    HV_EXIT_PLAN_NO_SOLUTION = 3, /* no plan within the time limit: nothing written */
    HV_EXIT_PLAN_CHECK = 4,       /* the plan failed the independent check */
    HV_EXIT_PLAN_INTERRUPTED = 5, /* SIGINT/SIGTERM: the best plan so far written */

    /* harvest-plan-online */
    HV_EXIT_ONLINE_EXEC_SAFE = 4,    /* the executor stopped in the safe state */
    HV_EXIT_ONLINE_INTERRUPTED = 5,  /* SIGINT/SIGTERM before the row was planned */
    HV_EXIT_ONLINE_EXEC_STOPPED = 6, /* the executor made a controlled stop */

    /* harvest-exec */
    HV_EXIT_EXEC_SAFE = 3,          /* stopped in the safe state: the nodes hold an e-stop */
    HV_EXIT_EXEC_ESTOP_LATCHED = 4, /* not started: a node reports a latched e-stop */
    HV_EXIT_EXEC_REFUSED = 5,       /* --check-plan: the IK refuses a planned pick */
    HV_EXIT_EXEC_STOPPED = 6,       /* a controlled stop on request, nothing latched */

    /* hv-can-tool */
    HV_EXIT_CAN_TIMEOUT = 3 /* fewer frames than asked for before the timeout, or lost */
};

/* The start of every program's last --help line; each adds its higher codes and ")". */
#define HV_EXIT_CODES_HELP                                                                         \
    "Exit codes: docs/EXIT_CODES.md (0 done, 1 runtime failure, 2 usage or bad input"

#endif
