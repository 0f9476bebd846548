"""harvest-fw.elf boots in QEMU (mps2-an386): banner and a status line every second on
UART0, SLCAN commands answered as Lawicel's, and each kind of bad line named on the UART
without stopping the firmware."""

import fw_qemu
import pytest


@pytest.fixture
def fw(tmp_path):
    fw_qemu.require_qemu()
    fw_qemu.fw_build.require_image()
    fw_qemu.enter_netns()
    q = fw_qemu.Qemu(str(tmp_path))
    q.connect()
    yield q
    q.stop()


def is_status(line):
    return line.startswith("harvest-fw: status")


def is_reply(line):
    """A Lawicel reply or error: not a status line, not a frame the firmware sends (its
    ExecutorPlanStatus once a second while the channel is open and no plan runs)."""
    return not is_status(line) and not line.startswith("t")


def test_banner_and_heartbeat(fw):
    banner = fw.line()
    assert banner.startswith("harvest-fw: mps2-an386"), banner
    first, _ = fw.wait_for(is_status)
    second, _ = fw.wait_for(is_status)
    a, b = fw_qemu.status_fields(first), fw_qemu.status_fields(second)
    # the clock advances (SysTick) and the loop runs; nothing arrives while no plan is loaded
    assert int(b["up_ms"]) > int(a["up_ms"])
    assert b["phase"] == "NO_PLAN" and b["rx"] == "0"


def test_slcan_commands_and_bad_lines(fw):
    fw.wait_for(lambda ln: ln.startswith("harvest-fw: mps2"))
    # a frame before the channel is open is refused
    fw.send("t0211AA\r")
    ln, _ = fw.wait_for(lambda s: "error" in s)
    assert ln.endswith("HV_ERR_SLCAN_CLOSED") and ln.startswith("\a"), ln
    fw.send("S6\rO\r")
    assert fw.wait_for(is_reply)[0] == ""  # S6 done
    assert fw.wait_for(is_reply)[0] == ""  # O done
    fw.send("t0211AA\r")
    assert fw.wait_for(is_reply)[0] == "z"
    for bad, name in (
        ("t02G1AA", "HV_ERR_SLCAN_HEX"),
        ("t0219", "HV_ERR_SLCAN_LENGTH"),
        ("t0212AA", "HV_ERR_SLCAN_LENGTH"),
        ("Q", "HV_ERR_SLCAN_COMMAND"),
        ("t" + "0" * 40, "HV_ERR_SLCAN_LINE_LONG"),
    ):
        fw.send(bad + "\r")
        ln, _ = fw.wait_for(is_reply)
        assert ln == "\aharvest-fw: error " + name, (bad, ln)
    # still alive, counting: 6 bad lines (the closed-channel frame included), 1 frame
    st, _ = fw.wait_for(is_status)
    f = fw_qemu.status_fields(st)
    assert f["bad_lines"] == "6" and f["rx"] == "1", st
