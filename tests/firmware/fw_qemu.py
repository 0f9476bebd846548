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


def qemu_argv(image, port, uart_log, extra=()):
    """QEMU waits for the client before the firmware starts (wait=on): nothing is lost.
    Everything the firmware writes to UART0 is also kept in uart_log."""
    return ["qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none",
            "-chardev", f"socket,id=uart0,host=127.0.0.1,port={port},server=on,wait=on,"
            f"logfile={uart_log}", "-serial", "chardev:uart0", "-kernel", image] + list(extra)


class Qemu:
    """The firmware in QEMU; .sock is UART0 once connect() returned."""

    def __init__(self, workdir, port=SERIAL_PORT, extra=()):
        self.image = fw_build.require_image()
        self.port = port
        self.log = open(os.path.join(workdir, "qemu.log"), "w")
        self.uart_log = os.path.join(workdir, "uart0.log")
        self.proc = subprocess.Popen(qemu_argv(self.image, port, self.uart_log, extra), stdout=self.log,
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
        stop_process(self.proc)
        self.log.close()


def stop_process(proc):
    """SIGTERM, and SIGKILL when that was not enough within 10 s."""
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def uart_lines(path):
    """The firmware's text lines in a UART log (SLCAN frames and replies left out)."""
    with open(path, "rb") as f:
        data = f.read().decode("ascii", "replace")
    return [ln.lstrip("\a") for ln in data.split("\r") if "harvest-fw:" in ln]


def status_fields(line):
    """{'up_ms': '1000', ...} of a 'harvest-fw: status k=v ...' line."""
    return dict(kv.split("=", 1) for kv in line.split()[2:])
