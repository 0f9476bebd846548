"""The firmware's per-step path runs in single precision, the FPU of the Cortex-M4F.

The M4F's FPU does float only: a double is computed by libgcc's software routines
(__aeabi_d*, __*df*), hundreds of cycles each. The image is disassembled
(arm-none-eabi-objdump) and a call graph made from its direct branches (bl, b.w and every
b<cond> whose target is another function: calls and tail calls); from each function of the
per-step path, no double helper (nor libm's double sqrt or round) may be reachable.

The per-step path: hv_exec_step, the CAN decode of every received frame and the carrying
out of each step's actions (hv_exec_can_decode, hv_exec_port_carry_out, which encodes the
frames), the plan time handed to the journal (hv_exec_executed_s), and the firmware loop's
step() when the compiler keeps it out of line. Calls through a pointer (the port's members)
are not followed; the firmware's port functions are integer code. Left out on purpose, since
it runs once per plan, not per step: the plan upload (hv_fw_upload_frame), which checks the
plan image's f64 fields in double and converts them to the executor's float as each record
arrives (firmware/README.md, "Floating point on a single-precision FPU"). hv_exec_init, once
per run too, happens to need no double.
"""

import re
import subprocess

import fw_build

# hv_fw_journal_append: the port's journal_append, reached through a function pointer the
# call graph does not follow
ROOTS = (
    "hv_exec_step",
    "hv_exec_can_decode",
    "hv_exec_port_carry_out",
    "hv_exec_executed_s",
    "hv_fw_journal_append",
)
# fw_main.c's static step(), under the name the compiler gave it (step.constprop.0 ...)
OPTIONAL_ROOT = re.compile(r"^step(\.\w+)*$")
DOUBLE_HELPER = re.compile(
    r"^(__aeabi_(d\w+|f2d|[iu]2d|u?l2d|cd\w+)|__\w*df\w*|sqrt|__ieee754_sqrt|round)$"
)
FUNCTION = re.compile(r"^[0-9a-f]+ <([^>]+)>:$")
# a direct branch: mnemonic b, bl, b.w, beq, bne.w, ... and its target symbol
BRANCH = re.compile(r"^\s*[0-9a-f]+:\s+(b|bl|b\.w|b[a-z]{2}|b[a-z]{2}\.[nw])\s+[0-9a-f]+ <([^>+]+)")


def call_graph(image):
    """{function: set of functions it branches to} from the image's disassembly."""
    out = subprocess.run(
        ["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", image],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    graph, current = {}, None
    for line in out.splitlines():
        m = FUNCTION.match(line)
        if m:
            current = m.group(1)
            graph.setdefault(current, set())
            continue
        m = BRANCH.match(line)
        if m and current is not None and m.group(2) != current:
            graph[current].add(m.group(2))
    return graph


def double_paths(graph, root):
    """Call chains from root to each double helper reachable from it (breadth first)."""
    parent, queue, found = {root: None}, [root], []
    while queue:
        f = queue.pop(0)
        if DOUBLE_HELPER.match(f):
            chain = [f]
            while parent[chain[-1]] is not None:
                chain.append(parent[chain[-1]])
            found.append(" -> ".join(reversed(chain)))
            continue
        for g in sorted(graph.get(f, ())):
            if g not in parent:
                parent[g] = f
                queue.append(g)
    return found


def test_per_step_path_calls_no_double_helper():
    image = fw_build.require_image()
    graph = call_graph(image)
    missing = [r for r in ROOTS if r not in graph]
    assert not missing, f"{image} lacks {missing}: the test would check nothing for them"
    roots = list(ROOTS) + [f for f in graph if OPTIONAL_ROOT.match(f)]
    found = [p for r in roots for p in double_paths(graph, r)]
    assert not found, "double arithmetic on the per-step path:\n" + "\n".join(found)


def test_graph_sees_the_double_helpers_the_upload_uses():
    """The check can fail: the image does hold double helpers, reached from the plan
    upload's f64 decoding, outside the per-step path."""
    graph = call_graph(fw_build.require_image())
    assert double_paths(graph, "hv_fw_upload_frame"), "no double helper found from the upload"
