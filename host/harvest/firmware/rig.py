"""The pieces around the firmware: QEMU with UART0 on TCP loopback (its output kept in a
log), python-can's bridge from that serial line (slcan over a pyserial socket:// URL) to
the udp_multicast bus, and readers of the firmware's text lines. Callers run inside a
private network namespace (harvest.canbus.netns), so the port and the multicast stay on
its loopback."""

import os
import socket
import subprocess
import sys
import time

SERIAL_PORT = 47000  # any free port: the namespace is the caller's own
UDP_GROUP = "239.74.163.2"
# -icount shift=5: every instruction advances the virtual clock by 2^5 = 32 ns, so the
# SysTick (25 MHz) counts 0.8 per instruction and a step's cycles on the firmware's status
# line are instructions x 0.8, independent of the host's speed.
ICOUNT_SHIFT = 5
CYCLES_PER_INSN = (2**ICOUNT_SHIFT) * 25e6 / 1e9


def semihosting_args(journal):
    """Semihosting on, and the journal's file named on its command line, which the
    firmware reads (firmware/fw_semihost.h): the host file stands for the board's flash.
    QEMU's option values escape a comma by doubling it."""
    path = os.path.abspath(journal).replace(",", ",,")
    return [
        "-semihosting-config",
        f"enable=on,target=native,arg=harvest-fw,arg=--journal,arg={path}",
    ]


def qemu_argv(image, port, uart_log, journal, icount=False):
    """QEMU waits for the client before the firmware starts (wait=on): nothing is lost.
    nodelay=on: the UART sends byte by byte, and with Nagle's algorithm each reply waited
    for the client's delayed ACK (a "V" line's round trip 41 ms median, 0.2 ms without).
    Everything the firmware writes to UART0 is also kept in uart_log (appended: a restart
    keeps what the run before it wrote); its journal goes to the file `journal` (created
    when absent, kept across QEMU's restarts)."""
    argv = [
        "qemu-system-arm",
        "-M",
        "mps2-an386",
        "-nographic",
        "-monitor",
        "none",
        "-chardev",
        f"socket,id=uart0,host=127.0.0.1,port={port},server=on,wait=on,nodelay=on,"
        f"logfile={uart_log},logappend=on",
        "-serial",
        "chardev:uart0",
        "-kernel",
        image,
    ] + semihosting_args(journal)
    if icount:
        argv += ["-icount", f"shift={ICOUNT_SHIFT},align=off,sleep=on"]
    return argv


def stop_process(proc):
    """SIGTERM, and SIGKILL when that was not enough within 10 s."""
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


class Qemu:
    """The firmware in QEMU. connect() makes .sock UART0 (tests that speak SLCAN
    themselves); a Bridge connects instead when the firmware goes on the bus. The journal
    file (default: workdir/fw.journal) is the board's storage: a QEMU started again on the
    same file resumes the row it holds. Each start appends to the logs."""

    def __init__(self, image, workdir, port=SERIAL_PORT, icount=False, journal=None):
        self.port = port
        self.journal = journal or os.path.join(workdir, "fw.journal")
        self.log = open(os.path.join(workdir, "qemu.log"), "a")
        self.uart_log = os.path.join(workdir, "uart0.log")
        self.proc = subprocess.Popen(
            qemu_argv(image, port, self.uart_log, self.journal, icount),
            stdout=self.log,
            stderr=subprocess.STDOUT,
        )
        self.sock = None
        self.buf = b""

    def wait_listening(self, timeout=20.0):
        """Wait until QEMU listens on its port, without connecting (the first client is
        the one QEMU serves): a bridge started earlier fails to connect and exits."""
        want = f":{self.port:04X} "
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            for table in ("/proc/self/net/tcp", "/proc/self/net/tcp6"):
                try:
                    with open(table) as f:
                        rows = f.read().splitlines()[1:]
                except OSError:
                    continue
                # local address column, state 0A = LISTEN
                if any(want in r.split()[1] + " " and r.split()[3] == "0A" for r in rows):
                    return
            if self.proc.poll() is not None:
                raise RuntimeError(f"QEMU exited {self.proc.returncode}")
            time.sleep(0.05)
        raise TimeoutError(f"QEMU does not listen on port {self.port} after {timeout} s")

    def connect(self, timeout=20.0):
        end = time.monotonic() + timeout
        while True:
            try:
                self.sock = socket.create_connection(("127.0.0.1", self.port), timeout=1.0)
                return self.sock
            except OSError:
                if self.proc.poll() is not None:
                    raise RuntimeError(f"QEMU exited {self.proc.returncode}") from None
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
                raise TimeoutError(
                    f"no line from the firmware within {timeout} s; have {self.buf!r}"
                )
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

    def kill(self):
        """SIGKILL, as a power cut: nothing of the firmware's runs after it."""
        if self.sock:
            self.sock.close()
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        self.log.close()


class Bridge:
    """python -m can.bridge between the firmware's serial line (slcan) and the udp bus."""

    def __init__(self, workdir, port, group=UDP_GROUP, env=None):
        """Start it once QEMU listens (Qemu.wait_listening)."""
        self.log = open(os.path.join(workdir, "bridge.log"), "w")
        argv = [
            sys.executable,
            "-m",
            "can.bridge",
            "--bus1-interface",
            "slcan",
            "--bus1-channel",
            f"socket://127.0.0.1:{port}",
            "--bus2-interface",
            "udp_multicast",
            "--bus2-channel",
            group,
            "--bus2-bus-kwargs",
            "hop_limit=0",
        ]
        self.proc = subprocess.Popen(argv, stdout=self.log, stderr=subprocess.STDOUT, env=env)

    def stop(self):
        stop_process(self.proc)
        self.log.close()


def uart_lines(path):
    """The firmware's text lines in a UART log (SLCAN frames and replies left out). A line
    still being written (no carriage return yet) is left out: the firmware writes the log
    while it is read."""
    with open(path, "rb") as f:
        data = f.read().decode("ascii", "replace")
    return [ln.lstrip("\a") for ln in data.split("\r")[:-1] if "harvest-fw:" in ln]


def status_fields(line):
    """{'up_ms': '1000', ...} of a 'harvest-fw: status k=v ...' line."""
    return dict(kv.split("=", 1) for kv in line.split()[2:])


def last_status(path):
    """Fields of the firmware's last status line in a UART log, {} when none yet."""
    lines = [ln for ln in uart_lines(path) if ln.startswith("harvest-fw: status")]
    return status_fields(lines[-1]) if lines else {}
