"""The bus suite (test_sim_bus.py) once more, on SocketCAN: directly where this machine has a
usable vcan (a laptop, the vehicle, inside the test-bed guest), otherwise inside the QEMU
test-bed guest of the CAN issue (harvest.canbus.guest), SKIPPED with the runner's reason
when the guest cannot run here.

Python runs ~20x slower in the guest, so the suite runs there at a lower time scale and
feedback rate, with longer waits, and with the simulator in a thread of pytest's process
(starting a Python process per test costs seconds there); the assertions are the same.
"""

import os
import re
import subprocess
import sys

import pytest

from harvest.canbus.guest import guest_or_skip, in_guest, local_vcan, run_in_guest

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.environ.get("HV_SOURCE_DIR", os.path.dirname(os.path.dirname(HERE)))
SUITE = os.path.join(HERE, "test_sim_bus.py")
GUEST_TIMEOUT_S = 1500


def _suite_env(iface, slow):
    env = dict(
        os.environ,
        HV_SIM_BUS="socketcan",
        HV_SIM_CHANNEL=iface,
        HV_SOURCE_DIR=SRC,
        PYTHONDONTWRITEBYTECODE="1",
    )
    if slow:
        env.update(HV_SIM_SCALE="4", HV_SIM_RATE="10", HV_SIM_WAIT="240", HV_SIM_INPROC="1")
    return env


def _check(out, returncode):
    assert returncode == 0, f"suite failed on vcan (exit {returncode}):\n{out[-8000:]}"
    summary = out.strip().splitlines()[-1]
    m = re.search(r"(\d+) passed", summary)
    # every test of the suite ran and passed: none skipped, failed or deselected
    assert m and int(m.group(1)) > 0, summary
    assert not re.search(r"skipped|failed|deselected|error", summary), summary


def test_bus_suite_on_vcan():
    iface = local_vcan()
    cmd = [sys.executable, "-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider", SUITE]
    if iface is not None:
        r = subprocess.run(
            cmd,
            env=_suite_env(iface, in_guest()),
            capture_output=True,
            text=True,
            timeout=GUEST_TIMEOUT_S,
        )
        print(r.stdout)
        _check(r.stdout + r.stderr, r.returncode)
        return
    if in_guest():
        pytest.fail("inside the test-bed guest but vcan0 is not usable")
    # the runner forwards HV_* and PYTHON* variables; vcan0 is up in the guest
    r = guest_or_skip(
        run_in_guest(cmd, timeout=GUEST_TIMEOUT_S, cwd=SRC, env=_suite_env("vcan0", True))
    )
    print(r.stdout)
    print(r.stderr, file=sys.stderr)
    _check(r.stdout, r.returncode)
