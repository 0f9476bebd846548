#!/usr/bin/env python3
"""One source per constant: no hand-written copy of a number that crosses a boundary.

The protocol's numbers have one home (DESIGN §6 and CONTRIBUTING): the DBC
(executor/can/harvest.dbc) for the protocol's version, node ids and names, message kinds,
fault bits and cycle times. C uses the names generated from it (hv/can_enums.h), Python
reads it. Each check greps the tracked files for the forms the copies took before they
were removed; a file that matches one fails unless it is the DBC itself.

usage: scripts/check_one_source.py [--root DIR] [--count]
  --root   the repository (default: this script's parent folder)
  --count  print, per constant, the files that restate it, and the number of
           (constant, file) pairs: the count of hand-written copies
Exit status 0 when no file restates a constant, 1 otherwise.
"""

import argparse
import os
import re
import subprocess
import sys

# Where the checks look: the product's code, its benchmarks and fuzz targets, and its
# docs. Tests may state numbers to test them against (a test asserts a value).
SCOPE = (
    "core/",
    "plan/",
    "planner/",
    "executor/",
    "firmware/",
    "tools/",
    "host/",
    "bench/",
    "fuzz/",
    "scripts/",
    "config/",
)
SUFFIXES = (".c", ".h", ".cpp", ".hpp", ".py", ".sh", ".cfg", ".dbc", ".toml")

DBC = ("executor/can/harvest.dbc",)
# constant -> (what, {form name: regex over the file's text}, home: the files that hold it)
CHECKS = {
    "can.protocol_version": (
        "the CAN protocol version (DBC attribute ProtocolVersion)",
        {
            "C define or enum": r"\bHV_(CAN_)?PROTOCOL_VERSION\s*(=\s*|\s+)\d",
            "Python constant": r"\bPROTOCOL_VERSION\s*=\s*\d",
        },
        DBC,
    ),
    "can.node_ids": (
        "the CAN node ids (DBC attributes NodeId, BroadcastNodeId)",
        {
            "C enum": r"\bHV_(CAN_)?NODE_[A-Z_]+\s*=\s*\d",
            "Python table": r"\(\s*\d+\s*,\s*\"(Executor|Vehicle|LeftArm|RightArm)\"\s*\)",
            "Python constant": r"\bBROADCAST_NODE\s*=\s*\d",
        },
        DBC,
    ),
    "can.node_names": (
        "the CAN node names (the DBC's node names)",
        {
            "Python table": r"NODE_PREFIX\s*=\s*\{",
            "DBC sender name": r"\"(EXECUTOR|VEHICLE|ARM_L|ARM_R)\"",
        },
        DBC,
    ),
    "can.kinds": (
        "the CAN message kinds, the low bits of a frame id (the DBC's frame ids)",
        {
            "C enum": r"\bHV_CAN_(CMD|KIND)_(ESTOP|HEARTBEAT|STATUS|SETPOINT)\s*=\s*\d",
            "Python table": r"\(\s*\d+\s*,\s*\"(Estop|Heartbeat|Command|Status|Setpoint|Move)\""
            r"\s*\)",
            "id layout": r"<<\s*5\)\s*\|",
        },
        DBC,
    ),
    "can.fault_bits": (
        "the FaultBits of the status frames (DBC VAL_TABLE_ VehicleFault, ArmFault)",
        {
            "C mask": r"#define\s+HV_(ARM|VEH)_FAULT_\w+\s+0x",
            "C literal": r"fault_bits\s*&\s*0x",
            "Python bit number": r"\bBIT_[A-Z_]+\s*=\s*\d+",
        },
        DBC,
    ),
    "can.cycle_times": (
        "the CAN frames' cycle times and the heartbeat timeout (GenMsgCycleTime, TimeoutTime)",
        {
            "C default": r"(heartbeat_period_s|heartbeat_timeout_s|resend_s)\s*=\s*0\.\d+\s*;",
            "Python default": r"(exec_timeout_s\"|rate_hz\"),\s*\d",
            "CLI default": r"\"--(exec-timeout|rate)\",\s*type=\w+,\s*default=\d",
            "comment": r"every (100|50|20) ms",
        },
        DBC,
    ),
}


# Copies left to other work, reported but not failed: path -> {constant: who removes it}.
# The coordinator empties this once that work is merged.
def tracked(root):
    """The files in scope: git's tracked ones, or every file of a tree that is no checkout."""
    if os.path.exists(os.path.join(root, ".git")):
        out = subprocess.run(
            ["git", "-C", root, "ls-files"], capture_output=True, text=True, check=True
        ).stdout.split()
    else:
        out = [
            os.path.relpath(os.path.join(d, f), root)
            for d, _, names in os.walk(root)
            for f in names
        ]
    return sorted(f for f in out if f.startswith(SCOPE) and f.endswith(SUFFIXES))


def scan(root, files=None):
    """[(constant, path, form, line number, line)] of every match outside its home."""
    hits = []
    compiled = {
        name: [(form, re.compile(rx, re.M)) for form, rx in forms.items()]
        for name, (_, forms, _) in CHECKS.items()
    }
    for path in files if files is not None else tracked(root):
        try:
            with open(os.path.join(root, path), encoding="utf-8") as f:
                text = f.read()
        except (OSError, UnicodeDecodeError):
            continue
        for name, forms in compiled.items():
            if path in CHECKS[name][2]:
                continue
            for form, rx in forms:
                for m in rx.finditer(text):
                    n = text.count("\n", 0, m.start()) + 1
                    hits.append((name, path, form, n, text.splitlines()[n - 1].strip()))
    return sorted(set(hits), key=lambda h: (h[1], h[3], h[0]))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    p.add_argument("--count", action="store_true", help="count the copies")
    args = p.parse_args(argv)
    hits = scan(args.root)
    if args.count:
        pairs = sorted({(name, path) for name, path, *_ in hits})
        for name in CHECKS:
            files = [path for n, path in pairs if n == name]
            print(f"{name}: {len(files)} {' '.join(files)}")
        print(f"hand-written copies (constant, file): {len(pairs)}")
        return 0
    for name, path, form, n, line in hits:
        print(f"{path}:{n}: restates {CHECKS[name][0]} ({form}): {line}", file=sys.stderr)
    if hits:
        print(
            "a constant that crosses a boundary has one source (DESIGN §6): use the generated "
            "name or read it from its source (scripts/check_one_source.py says where)",
            file=sys.stderr,
        )
    return 1 if hits else 0


if __name__ == "__main__":
    sys.exit(main())
