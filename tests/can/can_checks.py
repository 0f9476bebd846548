"""Checks shared by the udp (namespace) and vcan (host or guest) suites: hv-can-tool (the C
transports and the cantools-generated C code) against python-can + cantools (Python).
Each check raises AssertionError with what differed."""

import os
import random
import select
import subprocess
import time

from harvest.canbus import load
from harvest.canbus.buses import open_bus

# Everything is ~20x slower inside the QEMU guest: scale every wait.
SLOW = 20 if os.environ.get("HV_IN_GUEST") == "1" else 1


def tool_path():
    build = os.environ.get(
        "HV_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build")
    )
    return os.path.join(build, "executor", "can", "hv-can-tool")


def random_values(message, rng, on_grid=True):
    """In-range physical values for every signal; on the encoding grid or anywhere."""
    values = {}
    for sig in message.signals:
        lo = sig.minimum if sig.minimum is not None else 0
        hi = sig.maximum if sig.maximum is not None else 0
        scale, offset = sig.scale, sig.offset
        raw_lo = int(-(-(lo - offset) // scale))  # ceil
        raw_hi = int((hi - offset) // scale)
        if sig.choices or scale == 1 or on_grid:
            raw = rng.choice([raw_lo, raw_hi, rng.randint(raw_lo, raw_hi)])
            values[sig.name] = raw * scale + offset if scale != 1 or offset else raw
        else:
            values[sig.name] = rng.uniform(raw_lo * scale + offset, raw_hi * scale + offset)
    return values


def vectors(per_message, seed, on_grid=True):
    """[(message name, values, encoded bytes)] covering every DBC message."""
    proto = load()
    rng = random.Random(seed)
    out = []
    for m in proto.messages:
        for _ in range(per_message):
            v = random_values(m, rng, on_grid)
            out.append((m.name, v, bytes(proto.encode(m.name, v))))
    return out


def msg_line(name, values):
    return name + " " + " ".join(f"{k}={float(v)!r}" for k, v in values.items())


def frame_text(can_id, data):
    return f"{can_id:03X}#{bytes(data).hex().upper()}"


def start_tool(args, timeout=10.0):
    """hv-can-tool started in the background, returned once it printed 'ready'."""
    proc = subprocess.Popen(
        [tool_path()] + args,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + timeout * SLOW
    while True:
        left = deadline - time.monotonic()
        ready, _, _ = select.select([proc.stderr], [], [], max(left, 0))
        if not ready:
            proc.kill()
            raise AssertionError(
                f"hv-can-tool {' '.join(args)}: no 'ready' within {timeout * SLOW} s"
            )
        line = proc.stderr.readline()
        if not line:
            proc.wait()
            raise AssertionError(
                f"hv-can-tool {' '.join(args)} exited {proc.returncode} before ready"
            )
        if line.startswith("ready "):
            return proc


def finish(proc, timeout=30.0):
    out, err = proc.communicate(timeout=timeout * SLOW)
    return proc.returncode, out, err


def run_tool(args, stdin="", timeout=30.0):
    p = subprocess.run(
        [tool_path()] + args, input=stdin, capture_output=True, text=True, timeout=timeout * SLOW
    )
    return p.returncode, p.stdout, p.stderr


def stats_of(stderr):
    """{'tx': .., 'rx': .., 'malformed': ..} from the tool's closing stats line."""
    for line in stderr.splitlines():
        if line.startswith("stats "):
            return {k: int(v) for k, v in (f.split("=") for f in line.split()[1:])}
    raise AssertionError(f"no stats line in: {stderr!r}")


def check_python_to_c(spec, per_message=3, seed=1):
    """python-can sends every DBC message (cantools-encoded); C receives the same bytes."""
    vec = vectors(per_message, seed)
    proto = load()
    rx = start_tool(
        ["--bus", spec, "recv", "--count", str(len(vec)), "--timeout-ms", str(5000 * SLOW)]
    )
    with open_bus(spec) as bus:
        import can

        for name, _, data in vec:
            bus.send(
                can.Message(
                    arbitration_id=proto.message(name).frame_id, data=data, is_extended_id=False
                )
            )
    rc, out, err = finish(rx)
    assert rc == 0, f"C receiver exit {rc}: {err}"
    got = out.split()
    want = [frame_text(proto.message(n).frame_id, d) for n, _, d in vec]
    assert got == want, f"C received {got[:5]}..., python-can sent {want[:5]}..."
    assert stats_of(err)["rx"] == len(vec)


def check_c_to_python(spec, per_message=3, seed=2):
    """C packs every DBC message with the generated code and sends it; python-can receives
    it and cantools decodes the values and the very bytes cantools would have sent."""
    vec = vectors(per_message, seed)
    proto = load()
    lines = "".join(msg_line(n, v) + "\n" for n, v, _ in vec)
    with open_bus(spec) as bus:
        sender = subprocess.Popen(
            [tool_path(), "--bus", spec, "send-msg"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        _, err = sender.communicate(lines, timeout=30 * SLOW)
        assert sender.returncode == 0, f"C sender exit {sender.returncode}: {err}"
        received = []
        deadline = time.monotonic() + 10 * SLOW
        while len(received) < len(vec) and time.monotonic() < deadline:
            m = bus.recv(0.5)
            if m is not None:
                received.append(m)
    assert len(received) == len(vec), f"python-can got {len(received)} of {len(vec)} frames"
    for (name, values, data), m in zip(vec, received):
        msg = proto.message(name)
        assert m.arbitration_id == msg.frame_id and not m.is_extended_id, (name, m)
        assert bytes(m.data) == data, f"{name}: C sent {bytes(m.data).hex()}, cantools {data.hex()}"
        decoded = msg.decode(bytes(m.data), decode_choices=False)
        for sig in msg.signals:
            assert abs(decoded[sig.name] - values[sig.name]) <= sig.scale / 2 + 1e-12, (
                name,
                sig.name,
            )


def check_filters(spec):
    """A C bus filtered to node 3 (left arm, id & 0x7E0 == 0x060) gets only its frames."""
    import can

    proto = load()
    left = sorted(m.frame_id for m in proto.messages if m.frame_id & 0x7E0 == 0x060)
    rx = start_tool(
        [
            "--bus",
            spec,
            "recv",
            "--count",
            "0",
            "--timeout-ms",
            str(1500 * SLOW),
            "--filter",
            "060:7E0",
        ]
    )
    vec = vectors(1, seed=3)
    with open_bus(spec) as bus:
        for name, _, data in vec:
            bus.send(
                can.Message(
                    arbitration_id=proto.message(name).frame_id, data=data, is_extended_id=False
                )
            )
        # an extended id with the same low bits must not pass a standard-id filter
        bus.send(can.Message(arbitration_id=0x00000064, data=b"\x01", is_extended_id=True))
    rc, out, err = finish(rx)
    assert rc == 0, err
    got = sorted(int(line.split("#")[0], 16) for line in out.split())
    assert got == left, f"filter 060:7E0 let through {[hex(i) for i in got]}"


def check_timeout(spec):
    """recv with nothing on the bus ends with the timeout status and no frame."""
    rc, out, err = run_tool(["--bus", spec, "recv", "--count", "1", "--timeout-ms", "300"])
    assert rc == 3, f"expected exit 3 (timeout), got {rc}: {err}"
    assert out == ""
    assert stats_of(err)["rx"] == 0
