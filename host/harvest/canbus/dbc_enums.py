"""The protocol's value tables (the DBC's VAL_), named and checked, and the C header the
build generates from the DBC (hv/can_enums.h): those tables as C enums, and the protocol's
numbers that protocol.Protocol reads from the DBC's attributes (version, node ids, message
kinds, cycle times and timeouts, fault bits). harvest.canbus.enums makes Python enums of
the same tables.

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

from .. import generated, resources
from . import protocol

# enum name, C prefix (HV_CAN_<prefix>_<LABEL>), the (message kind, signal) pairs it types;
# a message kind is what follows the node's name ("Status": VehicleStatus, LeftArmStatus, ...)
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
            for _, prefix in proto.nodes.values():
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


def _enum(out, comment, items):
    """Append one C enum of (name, value) pairs; the last without a comma."""
    out.append(f"/* {comment} */")
    out.append("enum {")
    out += [f"    {n} = {v}," for n, v in items[:-1]]
    out.append(f"    {items[-1][0]} = {items[-1][1]}")
    out += ["};", ""]


def _protocol_lines(proto, dbc):
    """The protocol's numbers (the DBC's attributes) as C: version, id layout, nodes,
    kinds, periods and fault bits."""
    out = []
    _enum(
        out,
        f"ProtocolVersion of {dbc}: what every heartbeat carries",
        [("HV_CAN_PROTOCOL_VERSION", proto.version)],
    )
    out += [
        f"/* Frame ids (KindBits of {dbc}): (node id << HV_CAN_KIND_BITS) | kind */",
        f"#define HV_CAN_KIND_BITS {proto.kind_bits}u",
        "#define HV_CAN_KIND_MASK ((1u << HV_CAN_KIND_BITS) - 1u)",
        "#define HV_CAN_ID(node, kind) \\",
        "    ((((unsigned)(node)) << HV_CAN_KIND_BITS) | ((unsigned)(kind) & HV_CAN_KIND_MASK))",
        "#define HV_CAN_ID_NODE(id) ((unsigned)(id) >> HV_CAN_KIND_BITS)",
        "#define HV_CAN_ID_KIND(id) ((unsigned)(id) & HV_CAN_KIND_MASK)",
        "",
    ]
    nodes = [("HV_CAN_NODE_BROADCAST", proto.broadcast_node)]
    nodes += [(f"HV_CAN_NODE_{name.upper()}", n.id) for name, n in proto.nodes.items()]
    _enum(out, f"Node ids (NodeId of each node of {dbc}; BroadcastNodeId)", nodes)
    out.append("/* Node names as programs print and record them (the DBC's, in snake case) */")
    out += [f'#define HV_CAN_NODE_{name.upper()}_NAME "{name}"' for name in proto.nodes]
    out.append("")
    kinds = sorted(proto.kinds.items(), key=lambda kv: (kv[1].number, kv[0]))
    _enum(
        out,
        "Message kinds: the low HV_CAN_KIND_BITS of a frame id, the same on every node",
        [(f"HV_CAN_KIND_{name.upper()}", k.number) for name, k in kinds],
    )
    periods = []
    for name, _ in kinds:
        if name in proto.cycle_ms:
            periods.append((f"HV_CAN_{name.upper()}_CYCLE_MS", proto.cycle_ms[name]))
        if name in proto.timeout_ms:
            periods.append((f"HV_CAN_{name.upper()}_TIMEOUT_MS", proto.timeout_ms[name]))
    _enum(
        out,
        "Periods, ms: _CYCLE_MS of a periodic kind (GenMsgCycleTime), _TIMEOUT_MS after\n"
        " * which its receiver treats the sender as lost (TimeoutTime)",
        periods,
    )
    for table, bits in proto.bit_tables.items():
        prefix = f"HV_CAN_{table_prefix(table)}"
        users = ", ".join(proto.bit_signals[table])
        out.append(f"/* Bits of {users} (VAL_TABLE_ {table} of {dbc}), as masks */")
        for label, bit in sorted(bits.items(), key=lambda kv: kv[1]):
            out.append(f"#define {prefix}_{label} 0x{1 << bit:04X}u")
        every = 0
        for bit in bits.values():
            every |= 1 << bit
        out.append(f"#define {prefix}_ALL 0x{every:04X}u /* every named bit */")
        out.append("")
    return out


def table_prefix(table):
    """C prefix of a bit table: "ArmFault" -> "ARM_FAULT"."""
    return protocol.snake(table).upper()


def c_header(proto):
    """The text of hv/can_enums.h: one C enum per value table, HV_CAN_<prefix>_<LABEL> =
    value, and the protocol's numbers; every name once."""
    t = tables(proto)
    dbc = os.path.basename(proto.path)
    out = [
        f"/* Generated from {dbc} by harvest.canbus.dbc_enums: do not edit. */",
        "#ifndef HV_CAN_ENUMS_H",
        "#define HV_CAN_ENUMS_H",
        "",
    ]
    out += _protocol_lines(proto, dbc)
    for name, prefix, pairs in SPEC:
        where = ", ".join(f"<Node>{k}.{s}" for k, s in pairs)
        items = [(f"HV_CAN_{prefix}_{label}", value) for value, label in sorted(t[name].items())]
        items.append((f"HV_CAN_{prefix}_MAX", max(t[name])))
        _enum(out, f"{where} (VAL_ of {dbc}); _MAX: the largest value", items)
    out.append("#endif")
    names = re.findall(r"^(?:#define|    )\s*(HV_CAN_\w+)", "\n".join(out), flags=re.M)
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise EnumError(f"{proto.path}: the C name {twice[0]} would mean two things")
    return "\n".join(out) + "\n"


def markdown(proto):
    """docs/CAN_PROTOCOL.md: the protocol's numbers as tables, for people."""
    root = resources.source_root()
    dbc = os.path.relpath(proto.path, root) if root and proto.path.startswith(root) else proto.path
    t = tables(proto)
    by_id = {n.id: (name, n) for name, n in proto.nodes.items()}
    out = [
        "# CAN protocol: the numbers",
        "",
        f"Generated from `{dbc}` by",
        "`python -m harvest.canbus.dbc_enums --markdown docs/CAN_PROTOCOL.md`: do not edit.",
        "The DBC is the one source (DESIGN §6); the C names are those of the build's",
        "`hv/can_enums.h`, the Python ones `harvest.canbus.protocol.Protocol` and",
        "`harvest.canbus.enums`.",
        "",
        f"Protocol version (`ProtocolVersion`, in every heartbeat): {proto.version}. Frame id = "
        f"(node id << {proto.kind_bits}) | kind.",
        "",
        "## Nodes",
        "",
        "| node | id | C |",
        "|---|---|---|",
        f"| broadcast | {proto.broadcast_node} | `HV_CAN_NODE_BROADCAST` |",
    ]
    out += [
        f"| {n.prefix} | {n.id} | `HV_CAN_NODE_{name.upper()}` |" for name, n in proto.nodes.items()
    ]
    out += [
        "",
        "## Messages",
        "",
        "| id | message | node | kind | bytes | sent by | cycle ms | timeout ms |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for m in sorted(proto.messages, key=lambda m: m.frame_id):
        node_id, number = proto.split_id(m.frame_id)
        node = by_id[node_id][1].prefix if node_id in by_id else "broadcast"
        kind = proto.kind_of(m.name)
        cycle = proto.cycle_ms.get(kind, "")
        timeout = proto.timeout_ms.get(kind, "")
        senders = ", ".join(s for s in m.senders if s != "Vector__XXX") or "(a host tool)"
        out.append(
            f"| 0x{m.frame_id:03x} | {m.name} | {node} | {number} `HV_CAN_KIND_{kind.upper()}` "
            f"| {m.length} | {senders} | {cycle} | {timeout} |"
        )
    for table, bits in proto.bit_tables.items():
        out += [
            "",
            f"## {table}: bits of {', '.join(proto.bit_signals[table])}",
            "",
            "| bit | name | C mask |",
            "|---|---|---|",
        ]
        prefix = f"HV_CAN_{table_prefix(table)}"
        out += [
            f"| {b} | {lab} | `{prefix}_{lab}` |"
            for lab, b in sorted(bits.items(), key=lambda kv: kv[1])
        ]
    out += ["", "## Value tables", "", "| enum | signals | values | C |", "|---|---|---|---|"]
    for name, prefix, pairs in SPEC:
        where = ", ".join(f"`<Node>{k}.{s}`" for k, s in pairs)
        values = ", ".join(f"{v} {lab}" for v, lab in sorted(t[name].items()))
        out.append(f"| {name} | {where} | {values} | `HV_CAN_{prefix}_*` |")
    return "\n".join(out) + "\n"


def main(argv=None):
    p = argparse.ArgumentParser(
        prog="python -m harvest.canbus.dbc_enums",
        description="Write the C header of the DBC's numbers and value tables, and/or the "
        "document that lists them.",
    )
    p.add_argument("--dbc", help="the DBC (default: the repository's, or $HV_CAN_DBC)")
    p.add_argument("--c-header", help="header to write (replaced atomically)")
    p.add_argument("--markdown", help="document to write (docs/CAN_PROTOCOL.md)")
    p.add_argument("--check", action="store_true", help="compare, write nothing: 1 if stale")
    args = p.parse_args(argv)
    if not args.c_header and not args.markdown:
        p.error("nothing to do: give --c-header and/or --markdown")
    try:
        proto = protocol.Protocol(args.dbc)
        outputs = [(args.c_header, c_header), (args.markdown, markdown)]
        texts = [(path, make(proto)) for path, make in outputs if path]
    except (EnumError, protocol.ProtocolError, OSError) as e:
        print(f"harvest.canbus.dbc_enums: {e}", file=sys.stderr)
        return 1
    return max(generated.emit(path, text, args.check) for path, text in texts)


if __name__ == "__main__":
    sys.exit(main())
