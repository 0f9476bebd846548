"""The firmware on the simulator's bus: harvest-fw.elf in QEMU, its UART0 carried onto
python-can's udp_multicast bus by python-can's own pieces (the slcan interface over a
pyserial socket:// URL, bridged with `python -m can.bridge`), the simulator (exec_hil.Sim)
on the same bus, the plan uploaded over the bus (harvest.canbus.plan_upload). Callers are
inside a private network namespace (fw_qemu.enter_netns)."""

import os
import subprocess
import sys
import time

import fw_qemu
import pytest

from harvest.firmware import rig

sys.path.insert(
    0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "executor")
)
import exec_hil as H  # noqa: E402

PLAN_TOOL = os.path.join(H.BUILD, "firmware", "harvest-fw-plan")


def missing():
    """Reasons the bus tests cannot run, beside QEMU and the image (empty when none)."""
    out = H.missing_pieces()
    if not os.access(PLAN_TOOL, os.X_OK):
        out.append(f"harvest-fw-plan not built at {PLAN_TOOL}")
    try:
        import serial  # noqa: F401  (pyserial: python-can's slcan needs it)
    except ImportError:
        out.append("pyserial is not installed (host/requirements.txt)")
    return out


def plan_image(workdir, plan_path, time_scale, heartbeat_timeout=H.HEARTBEAT_TIMEOUT_S):
    out = os.path.join(workdir, "plan.img")
    subprocess.run(
        [
            PLAN_TOOL,
            "--plan",
            str(plan_path),
            "--config",
            H.CONFIG,
            "--out",
            out,
            "--time-scale",
            str(time_scale),
            "--heartbeat-timeout",
            str(heartbeat_timeout),
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    with open(out, "rb") as f:
        return f.read()


class Rig:
    """QEMU (serial on TCP, waiting for the bridge), the bridge, the simulator. The
    firmware's journal is workdir/fw.journal, kept when the firmware starts again."""

    def __init__(self, workdir, time_scale, faults=(), sim=True, sim_extra=()):
        self.workdir = str(workdir)
        self.start_firmware()
        self.sim = H.Sim(self.workdir, time_scale, faults, sim_extra) if sim else None

    def start_firmware(self):
        self.qemu = fw_qemu.Qemu(self.workdir)
        self.qemu.wait_listening()
        self.bridge = rig.Bridge(self.workdir, self.qemu.port, H.GROUP, H.env())

    def kill_firmware(self):
        """SIGKILL of QEMU (a power cut of the board), then its serial line's bridge."""
        self.qemu.kill()
        self.bridge.stop()

    def stop(self):
        for part in (self.sim, self.bridge, self.qemu):
            if part is not None:
                part.stop()


def wait_until(predicate, timeout, period=0.5):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(period)
    return predicate()


def rigs(tmp_path, time_scale):
    """The body of a test's rig fixture (`yield from`): skips naming what is missing,
    enters the private network namespace, yields make(faults=(), sim=True) that starts a
    Rig, and stops every rig it made."""
    fw_qemu.require_qemu()
    fw_qemu.fw_build.require_image()
    reasons = missing()
    if reasons:
        pytest.skip("SKIPPED: " + "; ".join(reasons))
    fw_qemu.enter_netns()
    raise_priority()
    made = []

    def make(faults=(), sim=True):
        made.append(Rig(tmp_path, time_scale, faults, sim=sim))
        return made[-1]

    try:
        yield make
    finally:
        for r in made:
            r.stop()


# The rig stands in for a bench of separate boards: QEMU emulating the firmware needs most of
# a core, and the Python bridge and simulator add its bus latency. Starved by other work on a
# shared machine, the bus's round trip passes the firmware's 1 s command timeout and the
# firmware stops safe, rightly. The rig (this process and what it starts) runs ahead of
# ordinary work so the test judges the firmware, not the machine's load.
RIG_NICE = -10


def raise_priority():
    try:
        os.setpriority(os.PRIO_PROCESS, 0, RIG_NICE)
    except OSError as e:
        print(f"fw_hil: the rig keeps the default priority ({e})", file=sys.stderr)


def upload(image, timeout=30.0):
    """The plan image uploaded on the test's bus (harvest.canbus.plan_upload)."""
    from harvest.canbus import plan_upload
    from harvest.canbus.buses import open_bus

    with open_bus("udp") as bus:
        return plan_upload.upload(bus, image, timeout)


def uart_phases(rig):
    """The phase of each status line the firmware wrote to UART0, in order."""
    return [
        fw_qemu.status_fields(ln)["phase"]
        for ln in fw_qemu.uart_lines(rig.qemu.uart_log)
        if ln.startswith("harvest-fw: status")
    ]


def diagnosis(rig):
    """What a failed rig test prints: the firmware's last status line (its phase and, in
    SAFE, the reason and node), the simulator's last refusals, repeats and faults from its
    record, its last log lines, and the rig's priority and load."""
    status = fw_qemu.last_status(rig.qemu.uart_log)
    sim_tail = []
    if rig.sim is not None:
        with open(rig.sim.log.name, errors="replace") as f:
            sim_tail = f.read().splitlines()[-8:]
    trouble = []
    if rig.sim is not None and os.path.exists(rig.sim.record):
        trouble = [
            e
            for e in rig.sim.events()
            if e.get("accepted") is False
            or e.get("repeat")
            or e["event"] in ("comm_timeout", "fault", "fault_injected")
            or (e["event"] == "state" and e.get("to") in ("FAULT", "ESTOP"))
        ][-8:]
    return (
        f"firmware status {status}; rig nice {os.getpriority(os.PRIO_PROCESS, 0)}; "
        f"cpus {len(os.sched_getaffinity(0))}; load {os.getloadavg()}; "
        f"simulator's refusals, repeats and faults {trouble}; simulator log tail {sim_tail}"
    )
