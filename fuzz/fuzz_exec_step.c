/* Fuzz target: CAN frames, decoded through the DBC (hv_exec_can_decode), into the
 * executor's step function (hv_exec_step), on a plan of the shape the input chooses.
 *
 * Input: one flag byte (bit 0: the operator cleared the e-stop for this run; bit 1:
 * resume, the next n_picks bytes giving each pick's journalled progress; bits 2-3: the
 * plan's shape, hv_fuzz_shape_t), then a list of operations, each an opcode byte and its
 * arguments:
 *   0 tick       dt: 1 byte (x 5 ms)
 *   1 raw frame  id: 2 bytes (11 bits), dlc: 1 byte (mod 9), data
 *   2 heartbeat  node, health, time scale (0: 10.00, else the byte / 10)
 *   3 status     node, state, flags (bit 0 reached/arrived, 1 homed, 2 echo the awaited
 *                sequence numbers, else the next byte), fault bits
 *   4 ee status  arm, state, action, flags (bit 0 fruit held, 1 echo the ee sequence)
 *   5 a well-behaved round: every node's heartbeat and a status echoing what the state
 *                machine waits for (so inputs get deep into the run), then a tick
 *   6 operator stop request (opcode bits 3-4: from_bus, 2 and 3 out of its domain),
 *   7 journal write failure
 * Frames 2-5 are packed with the DBC's generated code, as a node sends them.
 *
 * Properties, checked after every step: hv_fuzz_step (fuzz_nodes.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_nodes.h"
#include "fuzz_plan.h"
#include "fuzz_support.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hv_fuzz_reader_t r = {data, size};
    uint8_t flags = hv_fuzz_byte(&r);
    const hv_exec_plan_t *plan = hv_fuzz_plan_shape((hv_fuzz_shape_t)((flags >> 2) & 3));
    static hv_fuzz_run_t R; /* ~60 KB: off the fuzzer's stack */
    static hv_exec_progress_t prog;
    memset(&prog, 0, sizeof prog);
    if (flags & 2)
        for (unsigned i = 0; i < plan->n_picks; i++)
            prog.pick[i] = hv_fuzz_byte(&r) & 3;
    hv_exec_params_t prm;
    hv_exec_params_default(&prm);
    prm.home_max_s = 20.0;
    prm.clear_estop = flags & 1;
    hv_fuzz_run_init(&R, plan, &prm, (flags & 2) ? &prog : NULL);
    int op;
    unsigned ops = 0;
    while ((op = hv_fuzz_next(&r)) >= 0 && ops++ < 4096)
        hv_fuzz_node_op(&R, op, &r);
    if (getenv("HV_FUZZ_TRACE"))
        fprintf(stderr, "fuzz_exec_step: shape %d, %u ops, phase %s, stop %d, picked %u\n",
                (flags >> 2) & 3, ops, hv_exec_phase_name(R.sm.phase), R.sm.stop, R.sm.picked);
    return 0;
}
