"""Fixtures of the simulator suites: a python-can test client playing the executor, and a
simulator started on the bus the environment names.

HV_SIM_BUS selects the bus: `virtual` (default; the simulator runs in a thread of this
process, as python-can's virtual bus is in-process), `udp_multicast` or `socketcan` (the
simulator runs as `python -m harvest sim` in a subprocess and is stopped with SIGTERM,
or in a thread with HV_SIM_INPROC=1).
The udp_multicast and socketcan runs only happen inside a private network namespace or the
QEMU guest (test_sim_netns.py, test_sim_guest.py); they set HV_SIM_BUS themselves.
"""

import itertools
import os
import signal
import socket
import subprocess
import sys
import threading
import time

import can
import pytest

from harvest.canbus import buses, protocol
from harvest.sim import cli as sim_cli
from harvest.sim import record as sim_record

BUS = os.environ.get("HV_SIM_BUS", "virtual")
# simulated seconds per wall second; lower in the QEMU guest, where Python runs ~20x slower
SCALE = float(os.environ.get("HV_SIM_SCALE", "20"))
# the simulator runs in a thread of this process (always on `virtual`, which is in-process;
# in the guest too, where starting a Python process per test costs seconds)
INPROC = BUS == "virtual" or os.environ.get("HV_SIM_INPROC") == "1"
# joint state and status rate (simulated Hz): every frame costs more in the guest
RATE = float(os.environ.get("HV_SIM_RATE", "20"))
# how long a test waits for something before it fails (wall s); not a performance bound
WAIT_S = float(os.environ.get("HV_SIM_WAIT", "20"))
_ports = itertools.count(43200 + (os.getpid() % 200) * 10)
_names = itertools.count()


class Client:
    """The executor's side of the bus: sends frames by DBC name, keeps every frame received."""

    def __init__(self, bus, proto):
        self.bus, self.proto = bus, proto
        self.frames = []  # (wall s, name, signals), in arrival order
        self._cond = threading.Condition()
        self._stop = threading.Event()
        self._hb = None
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        while not self._stop.is_set():
            try:
                msg = self.bus.recv(timeout=0.05)
            except can.CanError:
                continue
            if msg is None:
                continue
            m = self.proto.by_id(msg.arbitration_id)
            if m is None or self.proto.nodes["executor"].prefix in m.senders:
                continue  # our own frames looped back, or foreign ids
            signals = m.decode(bytes(msg.data), decode_choices=False)
            with self._cond:
                self.frames.append((time.monotonic(), m.name, signals))
                self._cond.notify_all()

    def send(self, name, strict=True, **signals):
        m = self.proto.message(name)
        data = m.encode(signals, strict=strict)
        self.bus.send(can.Message(arbitration_id=m.frame_id, data=data, is_extended_id=False))

    def mark(self):
        """Index of the next frame to arrive: wait_for(since=mark) sees only newer frames."""
        with self._cond:
            return len(self.frames)

    def wait_for(self, name, pred=lambda s: True, since=0, timeout=None):
        """First frame `name` from index `since` on whose signals satisfy pred; (index, signals)."""
        deadline = time.monotonic() + (timeout or WAIT_S)
        i = since
        with self._cond:
            while True:
                while i < len(self.frames):
                    _, n, s = self.frames[i]
                    if n == name and pred(s):
                        return i, s
                    i += 1
                left = deadline - time.monotonic()
                if left <= 0:
                    last = [s for _, n, s in self.frames if n == name][-1:]
                    raise AssertionError(
                        f"no {name} frame matched within {timeout or WAIT_S} s "
                        f"wall; last {name}: {last}"
                    )
                self._cond.wait(left)

    def all(self, name, since=0, until=None):
        with self._cond:
            return [s for _, n, s in self.frames[since:until] if n == name]

    def heartbeat(self, period_s=0.05, scale=SCALE):
        """Send ExecutorHeartbeat every period_s (wall) until stop_heartbeat()."""
        stop = threading.Event()

        def loop():
            counter = 0
            while True:
                counter = (counter + 1) % 256
                self.send(
                    "ExecutorHeartbeat",
                    Counter=counter,
                    Health=0,
                    TimeScale=scale,
                    ProtocolVersion=self.proto.version,
                )
                if stop.wait(period_s):
                    break

        self._hb = (stop, threading.Thread(target=loop, daemon=True))
        self._hb[1].start()

    def stop_heartbeat(self):
        if self._hb:
            self._hb[0].set()
            self._hb[1].join()
            self._hb = None

    def close(self):
        self.stop_heartbeat()
        self._stop.set()
        self._reader.join()


class SimHandle:
    """A running simulator: its record path and a stop() that returns the record's events."""

    def __init__(self, record_path, stop, scale):
        self.record_path, self._stop, self.scale = record_path, stop, scale
        self._stopped = False

    def stop(self):
        if not self._stopped:
            self._stopped = True
            self._stop()
        return sim_record.read(self.record_path)

    def wait_events(self, event, count, timeout=None):
        """Record lines `event` once there are at least `count` of them."""
        deadline = time.monotonic() + (timeout or WAIT_S)
        while True:
            found = self.events(event)
            if len(found) >= count:
                return found
            assert time.monotonic() < deadline, f"record has {len(found)} '{event}', wanted {count}"
            time.sleep(0.02)

    def events(self, event=None, node=None):
        """Record lines written so far (the record is flushed line by line)."""
        out = sim_record.read(self.record_path)
        return [
            e
            for e in out
            if (event is None or e["event"] == event) and (node is None or e["node"] == node)
        ]


def _bus_args():
    if BUS == "virtual":
        return ["--interface", "virtual", "--channel", f"hv-sim-{os.getpid()}-{next(_names)}"]
    if BUS == "udp_multicast":
        # multicast must never leave the machine: only where lo is the one interface
        # (socket.if_nameindex asks the kernel about this namespace; /sys/class/net, which
        # netns.in_private_netns reads, still shows the host's sysfs after unshare)
        if [name for _, name in socket.if_nameindex()] != ["lo"]:
            pytest.skip(
                "SKIPPED: udp_multicast runs only inside a private network namespace "
                "(test_sim_netns.py starts one)"
            )
        return ["--bus", f"udp:239.74.163.2:{next(_ports)}"]
    if BUS == "socketcan":
        return ["--bus", f"socketcan:{os.environ.get('HV_SIM_CHANNEL', 'vcan0')}"]
    raise RuntimeError(f"HV_SIM_BUS={BUS!r}: expected virtual, udp_multicast or socketcan")


def _open_client_bus(bus_args):
    kw = dict(zip(bus_args[::2], bus_args[1::2]))
    if "--bus" in kw:
        return buses.open_bus(kw["--bus"])
    return can.Bus(interface=kw["--interface"], channel=kw["--channel"])


@pytest.fixture
def proto():
    return protocol.load()


@pytest.fixture
def sim(tmp_path, proto):
    """start(*flags) -> (SimHandle, Client); everything is stopped at teardown."""
    started = []

    def start(*flags, scale=SCALE, rate=RATE):
        bus_args = _bus_args()
        record = str(tmp_path / f"record{len(started)}.jsonl")
        argv = bus_args + [
            "--time-scale",
            f"{scale:g}",
            "--rate",
            f"{rate:g}",
            "--record",
            record,
            "--exec-timeout",
            "0",
            *flags,
        ]
        client_bus = _open_client_bus(bus_args)
        if INPROC:
            ev = threading.Event()
            result = {}
            th = threading.Thread(
                target=lambda: result.setdefault("rc", sim_cli.main(argv, ev)), daemon=True
            )
            th.start()

            def stop():
                ev.set()
                th.join(30)
                assert not th.is_alive(), "simulator thread did not stop"
                assert result.get("rc") == 0, f"simulator exited with {result.get('rc')}"
        else:
            env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
            proc = subprocess.Popen(
                [sys.executable, "-m", "harvest", "sim", *argv],
                env=env,
                stderr=subprocess.PIPE,
                text=True,
            )

            def stop():
                if proc.poll() is None:
                    proc.send_signal(signal.SIGTERM)
                _, err = proc.communicate(timeout=60)
                assert proc.returncode == 0, f"simulator exited with {proc.returncode}: {err}"

        client = Client(client_bus, proto)
        handle = SimHandle(record, stop, scale)
        started.append((handle, client, client_bus))
        # the simulator is up once all three heartbeats are on the bus
        for name in ("VehicleHeartbeat", "LeftArmHeartbeat", "RightArmHeartbeat"):
            client.wait_for(name, timeout=max(WAIT_S, 60))
        return handle, client

    yield start
    for handle, client, bus in started:
        client.close()
        try:
            handle.stop()
        finally:
            bus.shutdown()
