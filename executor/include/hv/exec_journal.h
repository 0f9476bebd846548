/* The harvest journal: an append-only text file that survives a crash (DESIGN §7).
 *
 * One record per line, each ending in " *" + the CRC-32 of the text before it (exactly 8
 * lowercase hex digits, as "%08x"):
 *   HVJ 1 plan=<crc32 of the plan's stops and picks> picks=<n> stops=<n>   (first line)
 *   S <stop> t=<s>                      stop reached (position in the plan's stop list)
 *   C <L|R> <fruit id> a=<attempt> t=<s>     cut issued
 *   R <L|R> <fruit id> a=<attempt> t=<s>     release issued
 *   F <L|R> <fruit id> <picked|failed|skipped> <reason> a=<attempt> t=<s>
 *   D t=<s>                             row done
 *   E <operator> nodes=<node>[,<node>] t=<s>   an operator cleared the e-stop latched on
 *                                       these nodes (vehicle, left_arm, right_arm)
 *   H <operator|plan_timeout> t=<s>     a controlled stop and why (hv_exec_stop_reason_t):
 *                                       nothing latched, the next run resumes
 * <operator>: 1 to 32 of A-Z a-z 0-9 . _ - (hv_exec_journal_operator_ok).
 *
 * Online (harvest-exec --online) the plan is not a file: it grows from the planner's
 * committed stops, and the journal holds them, so a restart rebuilds the plan before it
 * replays the outcomes. Its header is "HVJ 1 online"; then, interleaved with the records
 * above, in the order the stops were appended:
 *   O start=<m> length=<m> margin=<m>   the course (the row and its stop margin), once,
 *                                       before the first stop
 *   P <candidate index> y=<m> left=<n> right=<n>   a committed stop appended, followed by
 *   Q <L|R> <fruit id> x=<m> y=<m> z=<m> yaw=<rad> cost=<s>   its left + right picks, left
 *                                       first, one record each
 * Numbers are printed with 17 significant digits, so they read back to the same double.
 * The stops of one batch are written before the state machine hears of them and synced
 * once; a stop whose Q records are incomplete at the end of the file (a crash while the
 * batch was written) was never acted on and is cut off like a torn line.
 * t is the executor's run time (s, informational). Each record is written with one
 * write() and made durable with fdatasync() before the call returns, so the program
 * carries out the next action only after the record is on disk.
 *
 * Journals written before the E record existed read the same (the version stays 1); a
 * program that predates it stops at an E line with "unknown record".
 *
 * Opening an existing journal replays it into an hv_exec_progress_t: a torn last line
 * (a crash in the middle of a write: no newline) is cut off; a complete line with a bad
 * CRC, an unknown record or a fruit the plan does not have is an error naming the line.
 */
#ifndef HV_EXEC_JOURNAL_H
#define HV_EXEC_JOURNAL_H

#include <stddef.h>
#include <stdint.h>

#include "hv/exec_outcome.h"
#include "hv/exec_plan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hv_exec_journal {
    int fd; /* -1 when closed */
    uint32_t plan_hash;
    const hv_exec_plan_t *plan;
    int online;                /* 1: the plan grows, its stops are journalled (O, P, Q) */
    hv_exec_plan_t *grow;      /* online: the plan replay rebuilds (== plan) */
    uint16_t stops_journalled; /* online: plan stops [0, this) are in the journal */
    int course_journalled;     /* online: the O record is in the journal */
    unsigned records;          /* records replayed + written */
    unsigned torn_bytes;       /* bytes of a torn last line removed at open */
    char path[512];
} hv_exec_journal_t;

/* CRC-32 over what identifies a plan for the journal: stops and picks (ids, sides, order). */
uint32_t hv_exec_plan_hash(const hv_exec_plan_t *plan);

/* Open (create when absent) the journal of `plan` at `path`; replay what it holds into
 * `progress` (zeroed first). Codes: HV_ERR_EXEC_JOURNAL_IO, _FORMAT, _PLAN, _UNKNOWN;
 * `err` gets "<path>: line <n>: <what>". */
hv_status_t hv_exec_journal_open(hv_exec_journal_t *j, const char *path, const hv_exec_plan_t *plan,
                                 hv_exec_progress_t *progress, char *err, size_t errlen);

/* Online: open (create when absent) the journal at `path` of a plan that grows. An
 * existing journal first rebuilds `plan` (empty on entry: course 0, no stops) from its O,
 * P and Q records, in their order, with hv_exec_plan_append, then replays the rest into
 * `progress` as above; run hv_exec_plan_prepare() on the rebuilt plan afterwards. Codes as
 * hv_exec_journal_open, and HV_ERR_EXEC_JOURNAL_PLAN for a plan file's journal. */
hv_status_t hv_exec_journal_open_online(hv_exec_journal_t *j, const char *path,
                                        hv_exec_plan_t *plan, hv_exec_progress_t *progress,
                                        char *err, size_t errlen);

/* Online: journal the plan's stops not yet journalled (the course first, when it is not
 * yet), one record per line, synced once at the end. Call it after the plan grew and
 * before the state machine hears of it. HV_OK when there is nothing new;
 * HV_ERR_EXEC_JOURNAL_IO on failure; HV_ERR_EXEC_JOURNAL_ID for a fruit id that could not
 * be read back (nothing of that stop written); HV_ERR_ARG on a journal not opened online. */
hv_status_t hv_exec_journal_stops(hv_exec_journal_t *j);

/* Append one record and make it durable. HV_ERR_EXEC_JOURNAL_IO on failure;
 * HV_ERR_EXEC_JOURNAL_ID, with nothing written, for a fruit whose id is outside the set of
 * hv/fruit_id.h (replay could not read it back as the same fruit). */
hv_status_t hv_exec_journal_stop(hv_exec_journal_t *j, int stop, double t_s);
hv_status_t hv_exec_journal_cut(hv_exec_journal_t *j, int pick, int attempt, double t_s);
hv_status_t hv_exec_journal_release(hv_exec_journal_t *j, int pick, int attempt, double t_s);
hv_status_t hv_exec_journal_outcome(hv_exec_journal_t *j, int pick, int outcome, int reason,
                                    int attempt, double t_s);
hv_status_t hv_exec_journal_done(hv_exec_journal_t *j, double t_s);
/* A controlled stop ("H <reason>"): `reason` an hv_exec_stop_reason_t other than NONE. */
hv_status_t hv_exec_journal_halt(hv_exec_journal_t *j, int reason, double t_s);
/* `nodes`: 1 << HV_EXEC_* of the nodes cleared (not 0); HV_ERR_ARG for a bad operator name. */
hv_status_t hv_exec_journal_estop_clear(hv_exec_journal_t *j, const char *operator_name,
                                        unsigned nodes, double t_s);

/* 1 when `name` can stand as the operator of an E record. */
int hv_exec_journal_operator_ok(const char *name);

void hv_exec_journal_close(hv_exec_journal_t *j);

#ifdef __cplusplus
}
#endif
#endif /* HV_EXEC_JOURNAL_H */
