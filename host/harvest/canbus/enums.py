"""The protocol's value tables as IntEnums, read from the DBC (executor/can/harvest.dbc,
the source of truth) at import: Command, State, Health, EeAction, EeState, PlanState (the
firmware's plan upload); and its bit tables as IntFlags: VehicleFault, ArmFault (the
FaultBits of the status frames).

    from harvest.canbus.enums import ArmFault, Command, State
    node.on_command(t, Command.CLEAR_ESTOP, seq)
    node.fault(t, ArmFault.SETPOINT_REJECTED, "out of range")

Which signal each one types, and the checks that make them the DBC's, are dbc_enums.SPEC
and protocol.Protocol (BitTable); the C side gets the same tables as hv/can_enums.h
(HV_CAN_CMD_CLEAR_ESTOP, HV_CAN_ARM_FAULT_ESTOP, ...).
"""

import enum

from . import protocol
from .dbc_enums import EnumError, tables


def _int_enums(proto):
    out = {
        name: enum.IntEnum(
            name, {label: value for value, label in sorted(t.items())}, module=__name__
        )
        for name, t in tables(proto).items()
    }
    for name, bits in proto.bit_tables.items():
        out[name] = enum.IntFlag(
            name,
            {label: 1 << bit for label, bit in sorted(bits.items(), key=lambda kv: kv[1])},
            module=__name__,
        )
    return out


_ENUMS = _int_enums(protocol.load())
Command = _ENUMS["Command"]
State = _ENUMS["State"]
Health = _ENUMS["Health"]
EeAction = _ENUMS["EeAction"]
EeState = _ENUMS["EeState"]
PlanState = _ENUMS["PlanState"]
VehicleFault = _ENUMS["VehicleFault"]
ArmFault = _ENUMS["ArmFault"]


def member(kind, value):
    """The member of enum `kind` with `value`, or None when the DBC lists no such value."""
    try:
        return kind(value)
    except ValueError:
        return None


def flag_names(kind, bits):
    """The DBC's names of the bits set in `bits` of bit table `kind`, lowest first; a bit
    the table does not name as its hex value."""
    names = [m.name for m in kind if bits & m]
    rest = bits & ~sum(kind)
    return names + ([f"0x{rest:x}"] if rest else [])


def label(kind, value):
    """The DBC's label of `value` in enum `kind`, or the number as text when it has none."""
    m = member(kind, value)
    return str(value) if m is None else m.name


def check_same(proto):
    """Raise EnumError when the DBC `proto` was loaded from (e.g. a simulator's --dbc) has
    other value or bit tables than the one these enums were read from."""
    have = {name: {m.value: m.name for m in kind} for name, kind in _ENUMS.items()}
    got = {name: {m.value: m.name for m in kind} for name, kind in _int_enums(proto).items()}
    for name in have:
        if got.get(name) != have[name]:
            raise EnumError(
                f"{proto.path}: {name} values {got.get(name)} differ from "
                f"{protocol.load().path}'s {have[name]}, which this program uses"
            )
