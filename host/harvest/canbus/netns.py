"""Private network namespaces for UDP multicast tests (DESIGN §6: multicast must stay on
loopback). Two ways in:

- `enter_private_netns()` moves the *calling process* into a fresh network namespace
  (and a user namespace when not root), brings lo up and routes 224.0.0.0/4 to it. A
  pytest file calls it once at import/fixture time; every socket and subprocess created
  afterwards lives there and nothing can reach eth0 (the namespace has no eth0).
- `netns_command(argv)` wraps a command line so it runs in its own such namespace
  (`unshare -rn sh -c ...`), for scripts and benchmarks.
"""

import ctypes
import os
import shutil
import subprocess

CLONE_NEWUSER = 0x10000000
CLONE_NEWNET = 0x40000000
MULTICAST_ROUTE = "224.0.0.0/4"

# Shell prologue run inside the namespace before the real command.
_SETUP = f"ip link set lo up && ip route add {MULTICAST_ROUTE} dev lo"


class NetnsUnavailable(RuntimeError):
    """The namespace could not be made: callers report SKIPPED with str(error)."""


def _write(path, text):
    with open(path, "w", encoding="ascii") as f:
        f.write(text)


def enter_private_netns():
    """Move this process into a new network namespace with lo up and multicast routed
    to lo. Raises NetnsUnavailable with the reason when the kernel or policy refuses."""
    if shutil.which("ip") is None:
        raise NetnsUnavailable("'ip' (iproute2) not found")
    libc = ctypes.CDLL(None, use_errno=True)
    uid, gid = os.geteuid(), os.getegid()
    flags = CLONE_NEWNET if uid == 0 else CLONE_NEWNET | CLONE_NEWUSER
    if libc.unshare(flags) != 0:
        err = ctypes.get_errno()
        raise NetnsUnavailable(
            f"unshare(CLONE_NEWNET{'' if uid == 0 else '|CLONE_NEWUSER'}) "
            f"failed: {os.strerror(err)}"
        )
    if uid != 0:
        # become root of the new user namespace so that we may configure its network
        _write("/proc/self/setgroups", "deny")
        _write("/proc/self/uid_map", f"0 {uid} 1")
        _write("/proc/self/gid_map", f"0 {gid} 1")
    proc = subprocess.run(["sh", "-c", _SETUP], capture_output=True, text=True)
    if proc.returncode != 0:
        raise NetnsUnavailable(f"network namespace set-up failed: {proc.stderr.strip()}")


def in_private_netns():
    """True when the only interface is lo (i.e. we are inside such a namespace). Asks the
    kernel (if_nameindex), not /sys/class/net, which shows the mounter's namespace."""
    import socket

    return [name for _, name in socket.if_nameindex()] == ["lo"]


def netns_command(argv):
    """argv wrapped to run in its own network namespace with multicast on lo."""
    return ["unshare", "-rn", "sh", "-c", _SETUP + ' && exec "$0" "$@"'] + list(argv)


def run_in_netns(argv, **kwargs):
    """subprocess.run(argv) inside a fresh private network namespace."""
    if shutil.which("unshare") is None:
        raise NetnsUnavailable("'unshare' (util-linux) not found")
    return subprocess.run(netns_command(argv), **kwargs)
