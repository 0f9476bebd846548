"""C socketcan transport <-> python-can socketcan on vcan0: every message type both ways,
filters, a receive timeout, error frames, and a flood of 100 000 frames with no loss.

Where this machine has a usable vcan0 (a developer's laptop, the vehicle, or inside the
test-bed guest) the checks run directly. Elsewhere test_checks_in_guest boots the QEMU
guest once (testbed/run-in-guest) and runs this same file inside it."""

import os
import re
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import can_checks as cc  # noqa: E402

from harvest.canbus.guest import guest_or_skip, in_guest, local_vcan, run_in_guest  # noqa: E402

IFACE = local_vcan()
SPEC = f"socketcan:{IFACE}"
FLOOD = 100_000
DIRECT_TESTS = 6  # the tests below that need vcan; the guest run must pass all of them

# run here where this machine has vcan; elsewhere test_checks_in_guest runs them in the
# guest (conftest.py deselects the way not taken)
needs_vcan = pytest.mark.vcan_direct


@pytest.fixture(scope="module", autouse=True)
def built_tool():
    if not os.path.exists(cc.tool_path()):
        pytest.fail(f"hv-can-tool not built at {cc.tool_path()}")


@needs_vcan
def test_python_to_c_every_message():
    cc.check_python_to_c(SPEC)


@needs_vcan
def test_c_to_python_every_message():
    cc.check_c_to_python(SPEC)


@needs_vcan
def test_filters():
    cc.check_filters(SPEC)


@needs_vcan
def test_receive_timeout():
    cc.check_timeout(SPEC)


@needs_vcan
def test_error_frames_counted():
    """An error frame (CAN_ERR_FLAG) is returned flagged and counted, not taken for data."""
    import can

    rx = cc.start_tool(["--bus", SPEC, "recv", "--count", "2", "--timeout-ms", str(5000 * cc.SLOW)])
    with can.Bus(interface="socketcan", channel=IFACE) as bus:
        bus.send(
            can.Message(
                arbitration_id=0x004,
                is_error_frame=True,
                is_extended_id=False,
                data=bytes([0, 0x04, 0, 0, 0, 0, 0, 0]),
            )
        )
        bus.send(can.Message(arbitration_id=0x123, data=b"\x01", is_extended_id=False))
    rc, out, err = cc.finish(rx)
    assert rc == 0, err
    assert out.split("\n")[0].startswith("ERR 004#"), out
    assert "123#01" in out
    st = cc.stats_of(err)
    assert st["error_frames"] == 1 and st["rx"] == 2, st


def _backlog_drops():
    """Frames the kernel dropped from its per-CPU input backlog (softnet_stat column 2):
    where vcan floods lose frames when the receiver falls behind."""
    try:
        with open("/proc/net/softnet_stat", encoding="ascii") as f:
            return sum(int(line.split()[1], 16) for line in f if line.strip())
    except OSError:
        return -1


@needs_vcan
def test_flood_100k_no_loss():
    """100 000 frames C -> C as fast as the sender can go: all arrive, in order."""
    drops_before = _backlog_drops()
    sink = cc.start_tool(
        [
            "--bus",
            SPEC,
            "sink",
            "--count",
            str(FLOOD),
            "--id",
            "7F0",
            "--filter",
            "7F0:7FF",
            "--rcvbuf",
            str(256 << 20),
            "--timeout-ms",
            str(5000 * cc.SLOW),
        ]
    )
    rc, out, err = cc.run_tool(
        ["--bus", SPEC, "flood", "--count", str(FLOOD), "--id", "7F0", "--timeout-ms", "-1"],
        timeout=120,
    )
    assert rc == 0, err
    src, sout, serr = cc.finish(sink, timeout=120)
    print(out.strip(), "|", sout.strip())
    backlog = _backlog_drops() - drops_before
    assert src == 0, f"sink: {sout} {serr} (kernel input backlog drops during the flood: {backlog})"
    m = re.search(
        r"received=(\d+) expected=(\d+) gaps=(\d+) corrupt=(\d+) kernel_drops=(\d+)", sout
    )
    assert m and m.groups() == (str(FLOOD), str(FLOOD), "0", "0", "0"), sout


@pytest.mark.vcan_via_guest
def test_checks_in_guest():
    if in_guest():
        pytest.fail("inside the test-bed guest but vcan0 is not usable")
    proc = guest_or_skip(
        run_in_guest(
            [
                sys.executable,
                "-m",
                "pytest",
                "-q",
                "-rs",
                "-p",
                "no:cacheprovider",
                os.path.abspath(__file__),
            ],
            timeout=800,
        )
    )
    print(proc.stdout)
    print(proc.stderr, file=sys.stderr)
    assert proc.returncode == 0, f"guest run failed (exit {proc.returncode})"
    m = re.search(r"(\d+) passed", proc.stdout)
    assert m and int(m.group(1)) == DIRECT_TESTS, "not every vcan check passed in the guest"
