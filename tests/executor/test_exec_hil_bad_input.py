"""Hardware-in-the-loop over UDP multicast with bad input on the bus: datagrams that are
no CAN message and DBC frames too short to decode, sent while harvest-exec and the simulator
run a row. Both count and drop them, and the row still completes. In a private network
namespace (multicast on lo only)."""

import json
import os
import socket
import sys

import can
import msgpack
import pytest
from can.interfaces.udp_multicast.utils import pack_message

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402

from harvest.canbus import protocol  # noqa: E402

_skip = H.enter_udp_netns()
pytestmark = pytest.mark.skipif(bool(_skip), reason="SKIPPED: " + "; ".join(_skip))

SCALE = 20.0
PORT = 43113  # harvest-exec's and the simulator's default udp port


def _bad_datagrams():
    """Datagrams python-can's udp_multicast and the C transport both refuse."""
    ok = pack_message(can.Message(arbitration_id=0x43, data=bytes(8), is_extended_id=False))
    return [
        b"",
        b"\xc1",
        b"garbage, not msgpack",
        ok[:-3],
        ok + b"\x00",
        msgpack.packb([0x43, 8]),
        msgpack.packb({"arbitration_id": 0x43, "x": 1}),
        pack_message(can.Message(arbitration_id=0x43, data=bytes(2), dlc=5, is_extended_id=False)),
    ]


def _short_frames(proto):
    """Well-formed datagrams of a DBC frame the executor decodes, shorter than the DBC's."""
    m = proto.message("VehicleStatus")
    return [
        pack_message(can.Message(arbitration_id=m.frame_id, data=bytes(n), is_extended_id=False))
        for n in range(m.length)
    ]


def test_row_completes_with_bad_input_counted_and_dropped(tmp_path):
    plan = H.make_plan(tmp_path / "plan.json", stops=3, per_arm=2, seed=13)
    n = sum(len(s["left"]) + len(s["right"]) for s in plan["stops"])
    garbage, short = _bad_datagrams(), _short_frames(protocol.load())
    sim = H.Sim(str(tmp_path), SCALE)
    journal = tmp_path / "j.journal"
    try:
        p = H.start_exec(tmp_path / "plan.json", journal, tmp_path / "s.json", SCALE)
        # in the middle of the row: once the vehicle reached its first stop
        reached = H.wait_for(lambda: journal.exists() and b"\nS " in journal.read_bytes(), 60)
        if reached:
            tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            tx.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
            for d in garbage + short:
                tx.sendto(d, (H.GROUP, PORT))
            tx.close()
        out, err = p.communicate(timeout=240)
    finally:
        sim.stop()
    assert reached, "the row never reached its first stop"
    assert p.returncode == 0, err
    summary = json.loads((tmp_path / "s.json").read_text())
    assert summary["phase"] == "row_done" and summary["picked"] == n, summary
    # the executor: garbage dropped by the transport, short frames by the loop
    assert summary["bus_rx_malformed"] == len(garbage), summary
    assert summary["frames_rx_malformed"] == len(short), summary
    # the simulator: every datagram it could not unpack is in its record and stop stats
    stop = sim.events("stop")[-1]
    assert stop["reason"] == "stop requested", stop
    assert stop["stats"]["rx_bad_datagram"] == len(garbage), stop["stats"]
    assert len([e for e in sim.events("rx_rejected") if e["reason"] == "bad_datagram"]) == len(
        garbage
    )
    assert sum(a for a in stop["picks"].values()) == n
    H.assert_every_fruit_cut_once(plan, sim)
