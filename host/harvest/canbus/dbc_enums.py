"""The protocol's value tables (the DBC's VAL_), named and checked, and the C header the
build generates from them (hv/can_enums.h); harvest.canbus.enums makes IntEnums of them.

Each enum types one signal of one message kind, on every node that sends that kind; the
tables of those messages must be equal, and every enumerated signal of the DBC must be
typed by exactly one enum, so a value added to one node's table only, or a new table
nobody named, is an error here (and so in the build) rather than a silent difference.

    python -m harvest.canbus.dbc_enums --c-header OUT.h [--dbc PATH]
"""

import argparse
import os
import re
import sys

from . import protocol

# enum name, C prefix (HV_CAN_<prefix>_<LABEL>), the (message kind, signal) pairs it types;
# a message kind is a protocol.COMMANDS suffix ("Status": VehicleStatus, LeftArmStatus, ...)
SPEC = (
    ("Command", "CMD", (("Command", "Command"),)),
    ("State", "STATE", (("Status", "State"),)),
    ("Health", "HEALTH", (("Heartbeat", "Health"),)),
    ("EeAction", "EE_ACTION", (("EeCommand", "Action"), ("EeStatus", "Action"))),
    ("EeState", "EE_STATE", (("EeStatus", "State"),)),
    ("PlanState", "PLAN_STATE", (("PlanStatus", "State"),)),  # the firmware's plan upload
)


_LABEL = re.compile(r"[A-Z][A-Z0-9_]*")


class EnumError(ValueError):
    pass


def tables(proto):
    """{enum name: {value: label}} from the DBC, checked as the module docstring says."""
    typed, found = {}, {}
    names = {m.name for m in proto.messages}
    for name, _, pairs in SPEC:
        for kind, signal in pairs:
            for _, prefix in protocol.NODES.values():
                msg = prefix + kind
                if msg not in names:
                    continue
                choices = proto.choices(msg, signal)
                if not choices:
                    raise EnumError(f"{proto.path}: {msg}.{signal} has no value table (VAL_)")
                bad = [label for label in choices.values() if not _LABEL.fullmatch(label)]
                if bad:
                    raise EnumError(
                        f"{proto.path}: {msg}.{signal}: label {bad[0]!r} is not an "
                        "upper-case identifier (it names a C and a Python constant)"
                    )
                if name in found and found[name][1] != choices:
                    raise EnumError(
                        f"{proto.path}: {msg}.{signal} values {choices} differ from "
                        f"{found[name][0]}'s {found[name][1]}"
                    )
                found.setdefault(name, (f"{msg}.{signal}", choices))
                typed[(msg, signal)] = name
        if name not in found:
            raise EnumError(
                f"{proto.path}: no message carries enum {name} "
                f"({', '.join(f'<Node>{k}.{s}' for k, s in pairs)})"
            )
    for m in proto.messages:
        for s in m.signals:
            if s.choices and (m.name, s.name) not in typed:
                raise EnumError(
                    f"{proto.path}: {m.name}.{s.name} has a value table that no "
                    f"enum of harvest.canbus.dbc_enums.SPEC names"
                )
    return {name: choices for name, (_, choices) in found.items()}


def c_header(proto):
    """The text of hv/can_enums.h: one C enum per table, HV_CAN_<prefix>_<LABEL> = value."""
    t = tables(proto)
    dbc = os.path.basename(proto.path)
    out = [
        f"/* Generated from {dbc} by harvest.canbus.dbc_enums: do not edit. */",
        "#ifndef HV_CAN_ENUMS_H",
        "#define HV_CAN_ENUMS_H",
        "",
    ]
    for name, prefix, pairs in SPEC:
        where = ", ".join(f"<Node>{k}.{s}" for k, s in pairs)
        items = sorted(t[name].items())
        out.append(f"/* {where} (VAL_ of {dbc}) */")
        out.append("enum {")
        out += [f"    HV_CAN_{prefix}_{label} = {value}," for value, label in items]
        out.append(f"    HV_CAN_{prefix}_MAX = {items[-1][0]} /* the largest value */")
        out += ["};", ""]
    out.append("#endif")
    return "\n".join(out) + "\n"


def main(argv=None):
    p = argparse.ArgumentParser(
        prog="python -m harvest.canbus.dbc_enums",
        description="Write the C header of the DBC's value tables.",
    )
    p.add_argument("--dbc", default=protocol.DBC_PATH, help="the DBC (default: %(default)s)")
    p.add_argument("--c-header", required=True, help="header to write (replaced atomically)")
    args = p.parse_args(argv)
    try:
        text = c_header(protocol.Protocol(args.dbc))
    except (EnumError, protocol.ProtocolError, OSError) as e:
        print(f"harvest.canbus.dbc_enums: {e}", file=sys.stderr)
        return 1
    os.makedirs(os.path.dirname(os.path.abspath(args.c_header)), exist_ok=True)
    tmp = f"{args.c_header}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, args.c_header)
    return 0


if __name__ == "__main__":
    sys.exit(main())
