"""Where CAN tests run: on the host's own vcan when it has one, else in the QEMU test-bed
guest (testbed/run-in-guest, DESIGN §6).

    iface = local_vcan()              # "vcan0" when usable here (host or inside the guest)
    proc = run_in_guest(["python", "-m", "pytest", ...], rw=[tmpdir])
    guest_or_skip(proc)               # pytest.skip("SKIPPED: ...") when the guest cannot run
"""

import os
import socket
import subprocess

from harvest import resources

# the test-bed is part of the source tree only
RUNNER = os.path.join(resources.source_root() or "/nonexistent", "testbed", "run-in-guest")
SKIP_EXIT = 77


def in_guest():
    """True inside the test-bed guest (the runner sets HV_IN_GUEST=1)."""
    return os.environ.get("HV_IN_GUEST") == "1"


def local_vcan(name=None):
    """Name of a vcan interface usable from this machine, or None. HV_CAN_IFACE overrides
    the name (default vcan0). Checks that the kernel has AF_CAN and the interface is up."""
    name = name or os.environ.get("HV_CAN_IFACE", "vcan0")
    try:
        with open(f"/sys/class/net/{name}/operstate", encoding="ascii") as f:
            state = f.read().strip()
    except OSError:
        return None
    if state not in ("up", "unknown"):
        return None
    try:
        s = socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW)
        s.bind((name,))
        s.close()
    except (OSError, AttributeError):
        return None
    return name


def run_in_guest(argv, timeout=600, rw=(), cwd=None, env=None):
    """Run argv in the guest; CompletedProcess with text stdout/stderr. Exit status 77
    means the guest cannot run here (stderr says why)."""
    cmd = [RUNNER, "--timeout", str(int(timeout))]
    for d in rw:
        cmd += ["--rw", str(d)]
    if cwd:
        cmd += ["--cwd", str(cwd)]
    cmd += ["--"] + [str(a) for a in argv]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout + 60, env=env)


def skip_reason(proc):
    """The runner's "SKIPPED: ..." line when it could not run the guest, else None."""
    if proc.returncode != SKIP_EXIT:
        return None
    for line in proc.stderr.splitlines():
        if line.startswith("SKIPPED:"):
            return line
    return None


def guest_or_skip(proc):
    """pytest.skip with the runner's reason when the guest could not run; returns proc."""
    reason = skip_reason(proc)
    if reason is not None:
        import pytest

        pytest.skip(reason)
    return proc
