"""The simulator on python-can's udp_multicast, fed datagrams that are not CAN messages
(python-can's bus raises "could not unpack received message" for each): every one is
counted and dropped with a record line, the simulator keeps running, and a session after
them completes. Inside a private network namespace of its own (multicast on lo only)."""

import os
import signal
import socket
import subprocess
import sys
import time

import can
import msgpack
import pytest
from can.interfaces.udp_multicast.utils import pack_message

from harvest.canbus import buses, netns, protocol
from harvest.sim import record as sim_record

GROUP, PORT = "239.74.163.2", 43177
WAIT_S = 30.0  # how long to wait for an answer (wall s); not a performance bound


@pytest.fixture(scope="module", autouse=True)
def private_netns():
    try:
        netns.enter_private_netns()
    except netns.NetnsUnavailable as e:
        pytest.skip(f"SKIPPED: no private network namespace: {e}")
    assert netns.in_private_netns(), "namespace has interfaces besides lo"


def _frame(**fields):
    """A datagram as python-can packs it, of a message it would not let through on receive
    (can.Message checks nothing here, the receiving bus checks everything)."""
    fields = dict({"arbitration_id": 0x62, "data": b"\x01\x05", "is_extended_id": False}, **fields)
    return pack_message(can.Message(**fields))


GARBAGE = [
    b"",  # empty
    b"\xc1",  # a byte msgpack never uses
    b"not msgpack at all",
    _frame()[:-4],  # truncated
    _frame() + b"\x00",  # trailing byte
    msgpack.packb([1, 2, 3]),  # not a map
    msgpack.packb({"arbitration_id": 0x62, "colour": "red"}),  # a key can.Message lacks
    msgpack.packb({"arbitration_id": 0x62, "data": "text"}),  # data as a string
    _frame(dlc=3),  # dlc disagrees with the data
    _frame(arbitration_id=0x800),  # standard id too wide
    _frame(is_remote_frame=True, is_error_frame=True, data=b""),
    b"\xdf\xff\xff\xff\xff",  # a map claiming 2^32 entries
]


class Client:
    """Just enough of the executor: commands by DBC name, waits for a status."""

    def __init__(self, proto):
        self.proto = proto
        self.bus = buses.open_bus(f"udp:{GROUP}:{PORT}")

    def send(self, name, **signals):
        m = self.proto.message(name)
        self.bus.send(
            can.Message(arbitration_id=m.frame_id, data=m.encode(signals), is_extended_id=False)
        )

    def wait_for(self, name, pred):
        want = self.proto.message(name).frame_id
        deadline = time.monotonic() + WAIT_S
        while time.monotonic() < deadline:
            try:
                msg = self.bus.recv(0.1)
            except Exception as e:  # the garbage reaches this bus too
                if not buses.is_undecodable_datagram(e):
                    raise
                continue
            if msg is not None and msg.arbitration_id == want:
                s = self.proto.message(name).decode(bytes(msg.data), decode_choices=False)
                if pred(s):
                    return s
        raise AssertionError(f"no {name} frame matched within {WAIT_S} s")


def test_garbage_datagrams_counted_dropped_and_the_session_completes(tmp_path):
    proto = protocol.load()
    rec = tmp_path / "sim.jsonl"
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    sim = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "harvest",
            "sim",
            "--bus",
            f"udp:{GROUP}:{PORT}",
            "--time-scale",
            "20",
            "--rate",
            "20",
            "--exec-timeout",
            "0",
            "--record",
            str(rec),
        ],
        env=env,
        stderr=subprocess.PIPE,
        text=True,
    )
    client = Client(proto)
    try:
        client.wait_for("LeftArmHeartbeat", lambda s: True)
        raw = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        raw.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
        for g in GARBAGE:
            raw.sendto(g, (GROUP, PORT))
        raw.close()
        # the session: enable and home the left arm, after every piece of garbage
        cmd = lambda label: proto.value_of("LeftArmCommand", "Command", label)  # noqa: E731
        idle = proto.value_of("LeftArmStatus", "State", "IDLE")
        client.send("LeftArmCommand", Command=cmd("ENABLE"), CommandSeq=1)
        client.wait_for("LeftArmStatus", lambda s: s["CommandSeq"] == 1 and s["State"] == idle)
        client.send("LeftArmCommand", Command=cmd("HOME"), CommandSeq=2)
        client.wait_for(
            "LeftArmStatus",
            lambda s: s["CommandSeq"] == 2 and s["Homed"] == 1 and s["State"] == idle,
        )
        assert sim.poll() is None, "the simulator stopped"
    finally:
        client.bus.shutdown()
        if sim.poll() is None:
            sim.send_signal(signal.SIGTERM)
        _, err = sim.communicate(timeout=60)
    assert sim.returncode == 0, err
    events = sim_record.read(str(rec))
    stop = events[-1]
    assert stop["event"] == "stop" and stop["reason"] == "stop requested", stop
    assert stop["stats"]["rx_bad_datagram"] == len(GARBAGE), stop["stats"]
    bad = [e for e in events if e["event"] == "rx_rejected"]
    assert len(bad) == len(GARBAGE) and {e["reason"] for e in bad} == {"bad_datagram"}
    assert all("could not unpack" in e["error"] for e in bad), bad
    assert [e for e in events if e["event"] == "homed" and e["node"] == "left_arm"]
    assert f"rejected {len(GARBAGE)}" in err
