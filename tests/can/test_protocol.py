"""The DBC, the Python side (cantools) and the C side (cantools-generated code behind
hv-can-tool) agree: same ids and layout, identical bytes for the same values, identical
values for the same bytes. No bus needed."""

import os
import random
import re
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import can_checks as cc  # noqa: E402

from harvest.canbus import load  # noqa: E402

SOURCE = os.environ.get("HV_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture(scope="module")
def tool():
    if not os.path.exists(cc.tool_path()):
        pytest.fail(
            f"hv-can-tool not built at {cc.tool_path()} "
            f"(HV_BUILD_DIR={os.environ.get('HV_BUILD_DIR')})"
        )
    return cc.tool_path()


def test_every_id_follows_node_command_layout():
    proto = load()
    seen = set()
    for m in proto.messages:
        assert m.frame_id < 0x800 and not m.is_extended_frame
        assert m.length <= 8
        assert m.frame_id not in seen
        seen.add(m.frame_id)
        assert m.name == "Estop" or proto.node_of(m.frame_id) is not None, m.name
    # DESIGN §6 frames exist for every node that needs them
    for node in ("vehicle", "left_arm", "right_arm"):
        for kind in ("heartbeat", "command", "status"):
            proto.name_for(node, kind)
    for node in ("left_arm", "right_arm"):
        for kind in ("setpoint", "joint_state", "joint_velocity", "ee_command", "ee_status"):
            proto.name_for(node, kind)
    proto.name_for("vehicle", "move")
    proto.name_for("executor", "heartbeat")


def test_sequence_counters_are_echoed():
    """Every request's sequence signal reappears, same width, in its answer."""
    proto = load()
    pairs = [
        ("Setpoint", "Status", "SetpointSeq"),
        ("Command", "Status", "CommandSeq"),
        ("EeCommand", "EeStatus", "EeSeq"),
    ]
    for prefix in ("LeftArm", "RightArm"):
        for req, ans, sig in pairs:
            a = proto.message(prefix + req).get_signal_by_name(sig)
            b = proto.message(prefix + ans).get_signal_by_name(sig)
            assert a.length == b.length, (prefix, req, sig)
    for req, sig in (("Move", "MoveSeq"), ("Command", "CommandSeq")):
        a = proto.message("Vehicle" + req).get_signal_by_name(sig)
        assert a.length == proto.message("VehicleStatus").get_signal_by_name(sig).length


def test_ids_are_the_node_id_and_the_kind():
    """Each frame id is its node's NodeId and its kind's number, as the DBC says."""
    proto = load()
    assert proto.nodes["left_arm"].prefix == "LeftArm"
    for node, n in proto.nodes.items():
        for kind, k in proto.kinds.items():
            name = n.prefix + k.suffix
            if name in {m.name for m in proto.messages}:
                assert proto.message(name).frame_id == proto.frame_id(n.id, k.number), name
                assert proto.split_id(proto.message(name).frame_id) == (n.id, k.number)
                assert (
                    proto.kind_of(name) == kind and proto.node_of(proto.frame_id(n.id, 0)) == node
                )
    assert proto.message("Estop").frame_id == proto.frame_id(proto.broadcast_node, 0)
    assert proto.kinds["setpoint"].number == proto.kinds["move"].number  # arms / vehicle


@pytest.mark.parametrize(
    "old,new,why",
    [
        ('BA_ "NodeId" BU_ LeftArm 3;', 'BA_ "NodeId" BU_ LeftArm 5;', "whose name does not begin"),
        ('BA_ "NodeId" BU_ LeftArm 3;', 'BA_ "NodeId" BU_ LeftArm 2;', "given twice"),
        ('BA_ "ProtocolVersion" 1;\n', "", "no network attribute ProtocolVersion"),
        ('BA_ "GenMsgCycleTime" BO_ 99 50;', 'BA_ "GenMsgCycleTime" BO_ 99 40;', "one period"),
        ('BA_ "TimeoutTime" BO_ 97 500;\n', "", "LeftArmHeartbeat has no TimeoutTime"),
        ('BA_ "BitTable" SG_ 67 FaultBits "VehicleFault";\n', "", "is no signal's BitTable"),
        (
            'BA_ "BitTable" SG_ 99 FaultBits "ArmFault";',
            'BA_ "BitTable" SG_ 99 FaultBits "X";',
            "no VAL_TABLE_",
        ),
        ('4 "ESTOP" 3 "COMM_TIMEOUT"', '6 "ESTOP" 3 "COMM_TIMEOUT"', "one of the signal's 6 bits"),
    ],
)
def test_a_dbc_whose_attributes_disagree_is_refused(tmp_path, old, new, why):
    from harvest.canbus import Protocol, ProtocolError

    with open(os.path.join(SOURCE, "executor", "can", "harvest.dbc"), encoding="utf-8") as f:
        text = f.read()
    assert old in text
    path = tmp_path / "variant.dbc"
    path.write_text(text.replace(old, new))
    with pytest.raises(ProtocolError, match=re.escape(why)):
        Protocol(str(path))


def test_periods_are_the_dbcs():
    proto = load()
    for m in proto.messages:
        if m.cycle_time:
            assert proto.cycle_s(proto.kind_of(m.name)) == m.cycle_time / 1000.0
    assert proto.timeout_s("heartbeat") > proto.cycle_s("heartbeat")


def test_c_message_table_matches_dbc(tool):
    rc, out, err = cc.run_tool(["list"])
    assert rc == 0, err
    proto = load()
    rows = [line.split() for line in out.splitlines()]
    assert len(rows) == len(proto.messages)
    for row, m in zip(rows, proto.messages):
        assert int(row[0], 16) == m.frame_id and int(row[1]) == m.length and row[2] == m.name
        assert row[3:] == [s.name for s in m.signals]


@pytest.mark.parametrize("on_grid", [True, False], ids=["on-grid", "off-grid"])
def test_c_and_cantools_encode_identically(tool, on_grid):
    """Same physical values -> same bytes, for every message, limits included."""
    vec = cc.vectors(per_message=60, seed=11 if on_grid else 12, on_grid=on_grid)
    rc, out, err = cc.run_tool(["pack"], stdin="".join(cc.msg_line(n, v) + "\n" for n, v, _ in vec))
    assert rc == 0, err
    proto = load()
    got = out.split()
    assert len(got) == len(vec)
    for (name, values, data), line in zip(vec, got):
        want = cc.frame_text(proto.message(name).frame_id, data)
        assert line == want, f"{name} {values}: C {line}, cantools {want}"


def test_c_and_cantools_decode_identically(tool):
    """Same bytes (any bit pattern) -> same physical values."""
    proto = load()
    rng = random.Random(13)
    frames = []
    for m in proto.messages:
        for pattern in (b"\x00" * m.length, b"\xff" * m.length):
            frames.append((m, pattern))
        for _ in range(60):
            frames.append((m, bytes(rng.getrandbits(8) for _ in range(m.length))))
    rc, out, err = cc.run_tool(
        ["unpack"], stdin="".join(cc.frame_text(m.frame_id, d) + "\n" for m, d in frames)
    )
    assert rc == 0, err
    lines = out.splitlines()
    assert len(lines) == len(frames)
    for (m, data), line in zip(frames, lines):
        name, *fields = line.split()
        assert name == m.name, line
        c_values = {k: float(v) for k, v in (f.split("=") for f in fields)}
        py_values = m.decode(data, decode_choices=False)
        assert c_values.keys() == py_values.keys()
        for k, v in py_values.items():
            assert c_values[k] == pytest.approx(float(v), rel=1e-12, abs=1e-12), (
                m.name,
                k,
                data.hex(),
            )


def test_c_pack_rejects_bad_input_lines(tool):
    for line, what in (
        ("NoSuchMessage A=1", "no message"),
        ("Estop EstopActive=1", "signal 'Counter' missing"),
        ("Estop EstopActive=1 Counter=x", "not a number"),
        ("Estop EstopActive=1 Counter=1 Bogus=2", "no signal 'Bogus'"),
        (
            "LeftArmSetpoint Joint1Position=0.6 Joint2Position=0 Joint3Position=0 "
            "Joint4Position=0 SetpointSeq=0",
            "Joint1Position=0.6 outside the DBC range",
        ),
    ):
        rc, out, err = cc.run_tool(["pack"], stdin=line + "\n")
        assert rc == 2 and what in err and "line 1" in err, (line, rc, err)


def test_options_in_both_gnu_forms(tool):
    """getopt_long: `--opt value` and `--opt=value` alike, anywhere on the line."""
    import subprocess

    line = "Estop EstopActive=1 Counter=7\n"
    runs = [
        [tool, "--timeout-ms", "5", "pack"],
        [tool, "--timeout-ms=5", "pack"],
        [tool, "pack", "--timeout-ms=5"],
    ]
    outs = [subprocess.run(r, input=line, capture_output=True, text=True) for r in runs]
    assert all(o.returncode == 0 for o in outs), [o.stderr for o in outs]
    assert len({o.stdout for o in outs}) == 1 and outs[0].stdout.startswith("000#")
    bad = subprocess.run(
        [tool, "--timeout-ms=x", "pack"], input=line, capture_output=True, text=True
    )
    assert bad.returncode == 2 and "hv-can-tool: --timeout-ms: bad value 'x'" in bad.stderr
    unknown = subprocess.run([tool, "--speed=3", "list"], capture_output=True, text=True)
    assert unknown.returncode == 2 and "--speed=3: unknown option" in unknown.stderr
