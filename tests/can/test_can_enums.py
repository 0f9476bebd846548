"""The command, state, health and end-effector enums, in C (the build's hv/can_enums.h) and
in Python (harvest.canbus.enums), are the DBC's value tables as cantools reads them, and
the generator refuses a DBC whose nodes disagree or whose table nobody named."""

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
NODE_PREFIXES = [prefix for _, prefix in protocol.NODES.values()]


def _kind(message_name):
    prefix = next(p for p in NODE_PREFIXES if message_name.startswith(p))
    return message_name[len(prefix) :]


def _dbc_tables():
    """[(message, signal, {value: label})] of every enumerated signal, read by cantools."""
    db = cantools.database.load_file(DBC, strict=True)
    return [
        (m.name, s.name, {int(k): str(v) for k, v in s.choices.items()})
        for m in db.messages
        for s in m.signals
        if s.choices
    ]


def _header_constants():
    if not os.path.isfile(HEADER):
        pytest.skip(f"SKIPPED: {HEADER} is not generated (build the executor in $HV_BUILD_DIR)")
    with open(HEADER, encoding="utf-8") as f:
        text = f.read()
    return {name: int(value) for name, value in re.findall(r"\b(HV_CAN_\w+) = (\d+)", text)}


def test_every_enumerated_signal_of_the_dbc_is_in_the_contract():
    tables = _dbc_tables()
    assert len(tables) >= 12  # three nodes' commands, states, heartbeats and two arms' ee
    for msg, sig, _ in tables:
        assert (_kind(msg), sig) in CONTRACT, f"{msg}.{sig}"


def test_the_c_header_has_the_dbcs_values_and_nothing_else():
    consts = _header_constants()
    expected = {}
    for msg, sig, table in _dbc_tables():
        prefix, _ = CONTRACT[(_kind(msg), sig)]
        for value, label in table.items():
            name = f"HV_CAN_{prefix}_{label}"
            assert consts.get(name) == value, (f"{msg}.{sig} {label}", consts.get(name), value)
            expected[name] = value
        expected[f"HV_CAN_{prefix}_MAX"] = max(table)
    assert consts == expected


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
    consts = _header_constants()
    r = _generate(DBC, tmp_path / "can_enums.h")
    assert r.returncode == 0, r.stderr
    text = (tmp_path / "can_enums.h").read_text()
    assert {n: int(v) for n, v in re.findall(r"\b(HV_CAN_\w+) = (\d+)", text)} == consts


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
