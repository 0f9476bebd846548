"""harvest-fw.elf in QEMU's mps2-an386 with its UART0 on a TCP port of loopback: the
tests of tests/firmware enter a private network namespace first (harvest.canbus.netns),
so the port is reachable from nowhere else."""
import os
import shutil
import socket
import subprocess
import time

import pytest

import fw_build

SERIAL_PORT = 47000  # any free port: the namespace is the test's own


def require_qemu():
    if shutil.which("qemu-system-arm") is None:
        pytest.skip("SKIPPED: qemu-system-arm not installed (scripts/setup.sh installs it)")


def enter_netns():
    from harvest.canbus import netns
    try:
        netns.enter_private_netns()
    except netns.NetnsUnavailable as e:
        pytest.skip(f"SKIPPED: no private network namespace: {e}")


def qemu_argv(image, port, extra=()):
    """QEMU waits for the client before the firmware starts (wait=on): nothing is lost."""
    return ["qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none",
            "-serial", f"tcp:127.0.0.1:{port},server=on,wait=on", "-kernel", image] + list(extra)


class Qemu:
    """The firmware in QEMU; .sock is UART0 once connect() returned."""

    def __init__(self, workdir, port=SERIAL_PORT, extra=()):
        self.image = fw_build.require_image()
        self.port = port
        self.log = open(os.path.join(workdir, "qemu.log"), "w")
        self.proc = subprocess.Popen(qemu_argv(self.image, port, extra), stdout=self.log,
                                     stderr=subprocess.STDOUT)
        self.sock = None
        self.buf = b""

    def connect(self, timeout=20.0):
        end = time.monotonic() + timeout
        while True:
            try:
                self.sock = socket.create_connection(("127.0.0.1", self.port), timeout=1.0)
                return self.sock
            except OSError:
                assert self.proc.poll() is None, f"QEMU exited {self.proc.returncode}"
                if time.monotonic() > end:
                    raise
                time.sleep(0.1)

    def send(self, text):
        self.sock.sendall(text.encode("ascii"))

    def line(self, timeout=10.0):
        """The next CR-terminated line (BELLs kept, so a test sees them)."""
        end = time.monotonic() + timeout
        while b"\r" not in self.buf:
            left = end - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"no line from the firmware within {timeout} s; have {self.buf!r}")
            self.sock.settimeout(left)
            try:
                chunk = self.sock.recv(4096)
            except socket.timeout:
                continue
            if not chunk:
                raise EOFError("the firmware's serial line closed")
            self.buf += chunk
        text, _, self.buf = self.buf.partition(b"\r")
        return text.decode("ascii", "replace")

    def wait_for(self, predicate, timeout=10.0):
        """Lines until one satisfies predicate; returns it and the lines before it."""
        seen = []
        end = time.monotonic() + timeout
        while True:
            ln = self.line(max(0.1, end - time.monotonic()))
            if predicate(ln):
                return ln, seen
            seen.append(ln)

    def stop(self):
        if self.sock:
            self.sock.close()
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.log.close()


def status_fields(line):
    """{'up_ms': '1000', ...} of a 'harvest-fw: status k=v ...' line."""
    return dict(kv.split("=", 1) for kv in line.split()[2:])
