"""The command, state, health and end-effector enums and the fault bits, in C (the build's
hv/can_enums.h) and in Python (harvest.canbus.enums), are the DBC's value tables as cantools
reads them; the header's protocol numbers (version, node ids, kinds, periods) are the DBC's
attributes; and the generator refuses a DBC whose nodes disagree or whose table nobody
named."""

import os
import re
import subprocess
import sys

import cantools
import pytest

from harvest.canbus import enums, protocol

SOURCE_DIR = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD_DIR = os.environ.get("HV_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
HEADER = os.path.join(BUILD_DIR, "executor", "can", "generated", "enums", "hv", "can_enums.h")
DBC = os.path.join(SOURCE_DIR, "executor", "can", "harvest.dbc")

# What the C names and Python enums promise (DESIGN §6): the kind of message (its name
# without the node) and signal -> C prefix and Python enum.
CONTRACT = {
    ("Command", "Command"): ("CMD", enums.Command),
    ("Status", "State"): ("STATE", enums.State),
    ("Heartbeat", "Health"): ("HEALTH", enums.Health),
    ("EeCommand", "Action"): ("EE_ACTION", enums.EeAction),
    ("EeStatus", "Action"): ("EE_ACTION", enums.EeAction),
    ("EeStatus", "State"): ("EE_STATE", enums.EeState),
    ("PlanStatus", "State"): ("PLAN_STATE", enums.PlanState),
}
DB = cantools.database.load_file(DBC, strict=True)
NODE_PREFIXES = [n.name for n in DB.nodes]


def _kind(message_name):
    prefix = next(p for p in NODE_PREFIXES if message_name.startswith(p))
    return message_name[len(prefix) :]


def _dbc_tables():
    """[(message, signal, {value: label})] of every enumerated signal, read by cantools."""
    return [
        (m.name, s.name, {int(k): str(v) for k, v in s.choices.items()})
        for m in DB.messages
        for s in m.signals
        if s.choices
    ]


def _header_constants():
    if not os.path.isfile(HEADER):
        pytest.skip(f"SKIPPED: {HEADER} is not generated (build the executor in $HV_BUILD_DIR)")
    with open(HEADER, encoding="utf-8") as f:
        text = f.read()
    consts = {name: int(value) for name, value in re.findall(r"\b(HV_CAN_\w+) = (\d+)", text)}
    masks = re.findall(r"#define (HV_CAN_\w+) 0x([0-9A-F]+)u", text)
    return consts, {name: int(value, 16) for name, value in masks}


def _dbc_numbers():
    """{C name: value} of the protocol's numbers, from cantools' reading of the attributes."""
    a = {k: v.value for k, v in DB.dbc.attributes.items()}
    bits = a["KindBits"]
    out = {"HV_CAN_PROTOCOL_VERSION": a["ProtocolVersion"]}
    out["HV_CAN_NODE_BROADCAST"] = a["BroadcastNodeId"]
    for n in DB.nodes:
        out[f"HV_CAN_NODE_{protocol.snake(n.name).upper()}"] = n.dbc.attributes["NodeId"].value
    for m in DB.messages:
        kind = "ESTOP" if m.name == "Estop" else protocol.snake(_kind(m.name)).upper()
        out[f"HV_CAN_KIND_{kind}"] = m.frame_id & ((1 << bits) - 1)
        for attr, what in (("GenMsgCycleTime", "CYCLE"), ("TimeoutTime", "TIMEOUT")):
            if attr in m.dbc.attributes:
                out[f"HV_CAN_{kind}_{what}_MS"] = m.dbc.attributes[attr].value
    return out


def _dbc_masks():
    out = {}
    for table, bits in DB.dbc.value_tables.items():
        prefix = f"HV_CAN_{protocol.snake(table).upper()}"
        for bit, label in bits.items():
            out[f"{prefix}_{label}"] = 1 << bit
        out[f"{prefix}_ALL"] = sum(1 << bit for bit in bits)
    return out


def test_every_enumerated_signal_of_the_dbc_is_in_the_contract():
    tables = _dbc_tables()
    assert len(tables) >= 12  # three nodes' commands, states, heartbeats and two arms' ee
    for msg, sig, _ in tables:
        assert (_kind(msg), sig) in CONTRACT, f"{msg}.{sig}"


def test_the_c_header_has_the_dbcs_values_and_nothing_else():
    consts, masks = _header_constants()
    expected = _dbc_numbers()
    for msg, sig, table in _dbc_tables():
        prefix, _ = CONTRACT[(_kind(msg), sig)]
        for value, label in table.items():
            name = f"HV_CAN_{prefix}_{label}"
            assert consts.get(name) == value, (f"{msg}.{sig} {label}", consts.get(name), value)
            expected[name] = value
        expected[f"HV_CAN_{prefix}_MAX"] = max(table)
    assert consts == expected
    assert masks == _dbc_masks() and masks["HV_CAN_ARM_FAULT_ESTOP"] == 1 << 10


def test_the_python_fault_flags_are_the_dbcs_bits():
    for flag, table in ((enums.VehicleFault, "VehicleFault"), (enums.ArmFault, "ArmFault")):
        bits = DB.dbc.value_tables[table]
        assert {m.value: m.name for m in flag} == {1 << b: str(lab) for b, lab in bits.items()}


def test_the_python_enums_have_the_dbcs_values():
    for msg, sig, table in _dbc_tables():
        _, kind = CONTRACT[(_kind(msg), sig)]
        assert {m.value: m.name for m in kind} == table, f"{msg}.{sig}"
    assert enums.Command.CLEAR_ESTOP == 6 and enums.State.ESTOP == 5  # the DBC's numbers


def _variant(tmp_path, old, new, count=1):
    with open(DBC, encoding="utf-8") as f:
        text = f.read()
    assert old in text
    path = tmp_path / "variant.dbc"
    path.write_text(text.replace(old, new, count))
    return path


def _generate(dbc, out):
    env = dict(os.environ)
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest.canbus.dbc_enums",
            "--dbc",
            str(dbc),
            "--c-header",
            str(out),
        ],
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )


def test_the_generator_writes_the_same_header_as_the_build(tmp_path):
    _header_constants()  # skips when the build has none
    r = _generate(DBC, tmp_path / "can_enums.h")
    assert r.returncode == 0, r.stderr
    with open(HEADER, encoding="utf-8") as f:
        assert (tmp_path / "can_enums.h").read_text() == f.read()


@pytest.mark.parametrize(
    "old,new,why",
    [
        # one arm's command table gains a value the others lack
        ('VAL_ 130 Command 0 "NONE"', 'VAL_ 130 Command 7 "REBOOT" 0 "NONE"', "differ from"),
        # a value table on a signal no enum names
        (
            'VAL_ 33 Health 0 "OK"',
            'VAL_ 66 CommandSeq 0 "FIRST" ;\nVAL_ 33 Health 0 "OK"',
            "VehicleCommand.CommandSeq has a value table that no enum",
        ),
        # a label that is no identifier in C or Python
        ('2 "HOMING"', '2 "HOMING NOW"', "is not an upper-case identifier"),
    ],
)
def test_the_generator_refuses_a_dbc_it_cannot_type(tmp_path, old, new, why):
    out = tmp_path / "can_enums.h"
    r = _generate(_variant(tmp_path, old, new), out)
    assert r.returncode == 1 and why in r.stderr, r.stderr
    assert not out.exists()


def test_a_dbc_with_other_values_than_the_enums_is_refused(tmp_path):
    # every node's State table swaps two values: consistent, but not what the enums say
    other = protocol.Protocol(
        str(_variant(tmp_path, '4 "FAULT" 5 "ESTOP" ;', '4 "ESTOP" 5 "FAULT" ;', count=-1))
    )
    with pytest.raises(enums.EnumError, match="State values"):
        enums.check_same(other)
    enums.check_same(protocol.load(DBC))  # the repository's DBC is the one read at import


def test_the_protocol_document_is_current():
    doc = os.path.join(SOURCE_DIR, "docs", "CAN_PROTOCOL.md")
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "harvest.canbus.dbc_enums",
            "--dbc",
            DBC,
            "--markdown",
            doc,
            "--check",
        ],
        text=True,
        capture_output=True,
    )
    assert r.returncode == 0, r.stderr
