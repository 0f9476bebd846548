"""The protocol's value tables as IntEnums, read from the DBC (executor/can/harvest.dbc,
the source of truth) at import: Command, State, Health, EeAction, EeState, PlanState (the
firmware's plan upload).

    from harvest.canbus.enums import Command, State
    node.on_command(t, Command.CLEAR_ESTOP, seq)

Which signal each one types, and the checks that make them the DBC's, are dbc_enums.SPEC;
the C side gets the same tables as hv/can_enums.h (HV_CAN_CMD_CLEAR_ESTOP, ...).
"""

import enum

from . import protocol
from .dbc_enums import EnumError, tables


def _int_enums(proto):
    return {
        name: enum.IntEnum(
            name, {label: value for value, label in sorted(t.items())}, module=__name__
        )
        for name, t in tables(proto).items()
    }


_ENUMS = _int_enums(protocol.load())
Command = _ENUMS["Command"]
State = _ENUMS["State"]
Health = _ENUMS["Health"]
EeAction = _ENUMS["EeAction"]
EeState = _ENUMS["EeState"]
PlanState = _ENUMS["PlanState"]


def member(kind, value):
    """The member of enum `kind` with `value`, or None when the DBC lists no such value."""
    try:
        return kind(value)
    except ValueError:
        return None


def label(kind, value):
    """The DBC's label of `value` in enum `kind`, or the number as text when it has none."""
    m = member(kind, value)
    return str(value) if m is None else m.name


def check_same(proto):
    """Raise EnumError when the DBC `proto` was loaded from (e.g. a simulator's --dbc) has
    other value tables than the one these enums were read from."""
    have = {name: {m.value: m.name for m in kind} for name, kind in _ENUMS.items()}
    got = tables(proto)
    for name in have:
        if got[name] != have[name]:
            raise EnumError(
                f"{proto.path}: {name} values {got[name]} differ from "
                f"{protocol.DBC_PATH}'s {have[name]}, which this program uses"
            )
