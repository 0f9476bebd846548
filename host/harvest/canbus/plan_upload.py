"""Upload a plan image (harvest-fw-plan's output) to an executor that takes its plan from
the bus (harvest-fw.elf): ExecutorPlanBegin with the length and CRC-32, the bytes in
ExecutorPlanData frames of 6, then the executor's ExecutorPlanStatus says how it went
(DBC, executor/can/harvest.dbc; the error codes are named in firmware/fw_status.h).

    python -m harvest.canbus.plan_upload --bus udp IMAGE
"""

import argparse
import sys
import time
import zlib

from .buses import open_bus
from .protocol import load

CHUNK = 6


class UploadError(RuntimeError):
    """The executor refused the plan, or did not answer: the message says which."""


def frames(image):
    """The upload's messages, (name, signals), in order."""
    yield "ExecutorPlanBegin", {"TotalBytes": len(image), "Crc32": zlib.crc32(image)}
    for off in range(0, len(image), CHUNK):
        chunk = image[off : off + CHUNK].ljust(CHUNK, b"\0")
        yield "ExecutorPlanData", {"Offset": off, "Data": int.from_bytes(chunk, "little")}


def send(bus, image, pace_s=0.0005):
    """Send the upload on `bus`; pace_s between data frames keeps a bridge's queues short."""
    import can

    proto = load()
    for name, signals in frames(image):
        m = proto.message(name)
        bus.send(
            can.Message(arbitration_id=m.frame_id, data=m.encode(signals), is_extended_id=False)
        )
        if name == "ExecutorPlanData" and pace_s:
            time.sleep(pace_s)


def wait_status(bus, want, timeout):
    """The executor's next ExecutorPlanStatus whose State is in `want` (names); raises
    UploadError on REFUSED or when none comes within `timeout` s."""
    proto = load()
    m = proto.message("ExecutorPlanStatus")
    deadline = time.monotonic() + timeout
    last = None
    while time.monotonic() < deadline:
        msg = bus.recv(max(0.0, deadline - time.monotonic()))
        if msg is None or msg.arbitration_id != m.frame_id:
            continue
        s = m.decode(msg.data)  # State by the DBC's value table
        last = (str(s["State"]), int(s["BytesReceived"]), int(s["Error"]))
        if last[0] == "REFUSED":
            raise UploadError(
                f"the executor refused the plan after {last[1]} bytes: error "
                f"{last[2]} (firmware/fw_status.h)"
            )
        if last[0] in want:
            return last
    raise UploadError(f"no ExecutorPlanStatus {'/'.join(want)} within {timeout} s (last: {last})")


def upload(bus, image, timeout=30.0, pace_s=0.0005, attempts=3):
    """Wait for the executor's status (it sends one a second while it has no plan), send
    `image` and wait until the executor runs it; returns its last status. A refused upload
    (a frame lost on a busy bus: HV_ERR_FW_UPLOAD_ORDER) is sent again, `attempts` times
    in all, each a fresh ExecutorPlanBegin."""
    wait_status(bus, ("IDLE",), timeout)
    for attempt in range(1, attempts + 1):
        send(bus, image, pace_s)
        try:
            return wait_status(bus, ("RUNNING",), timeout)
        except UploadError:
            if attempt == attempts:
                raise


def main(argv=None):
    p = argparse.ArgumentParser(
        prog="python -m harvest.canbus.plan_upload", description=__doc__.split("\n\n")[0]
    )
    p.add_argument("image", help="plan image written by harvest-fw-plan")
    p.add_argument("--bus", default="udp", help="socketcan:IFNAME or udp[:GROUP[:PORT]] (udp)")
    p.add_argument("--timeout", type=float, default=30.0, help="s to wait for RUNNING (30)")
    a = p.parse_args(argv)
    with open(a.image, "rb") as f:
        image = f.read()
    with open_bus(a.bus) as bus:
        try:
            state = upload(bus, image, a.timeout)
        except UploadError as e:
            print(f"plan_upload: {a.image}: {e}", file=sys.stderr)
            return 1
    print(f"plan_upload: {a.image}: {len(image)} bytes, executor {state[0]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
