"""Read a cost table file (*.hvct, docs/COST_TABLE_FORMAT.md) into numpy for analysis.

The byte layout is the one documented at the top of core/src/cost_table.c; this reader
checks what the C loader checks (magic, version, sizes, layout, both CRC-32s) so a
figure is never drawn from a truncated or stale table.
"""

import struct
import zlib
from dataclasses import dataclass

import numpy as np

MAGIC = b"HVCOSTTB"
VERSION = 1
HEADER_BYTES = 512
ENCODING_U16_MS = 1
LAYOUT_XZYAW_Y = 1
UNREACHABLE = 0xFFFF
AXES = ("x", "y", "z", "yaw")


class CostTableError(ValueError):
    """A table that cannot be used: the message names the file and the header field."""


@dataclass
class Axis:
    origin: float  # m or rad
    step: float  # m or rad
    count: int

    def values(self):
        return self.origin + self.step * np.arange(self.count)

    def index(self, value):
        """Nearest index, or None outside the grid (as hv_axis_index)."""
        i = int(round((value - self.origin) / self.step))
        return i if 0 <= i < self.count else None


@dataclass
class CostTable:
    path: str
    side: str  # "L" or "R"
    elbow_free: bool
    axes: dict  # name -> Axis
    cost_unit_s: float
    base: tuple  # mount: base x, y, z (m) and heading (rad), vehicle frame
    costs: np.ndarray  # uint16 [x][z][yaw][y], UNREACHABLE where the arm cannot pick

    def seconds(self):
        """Costs in s as float, NaN where unreachable."""
        out = self.costs.astype(np.float64) * self.cost_unit_s
        out[self.costs == UNREACHABLE] = np.nan
        return out

    def reachable(self):
        return self.costs != UNREACHABLE


def load(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise CostTableError(f"{path}: cannot read cost table: {e.strerror}") from None

    def bad(field, what):
        return CostTableError(f"{path}: header field '{field}': {what}")

    if len(data) < HEADER_BYTES:
        raise bad(
            "header", f"file is {len(data)} bytes, shorter than the {HEADER_BYTES}-byte header"
        )
    if data[:8] != MAGIC:
        raise bad("magic", f"expected {MAGIC!r}, got {data[:8]!r}")
    version, hbytes, encoding, side, elbow, layout = struct.unpack_from("<6I", data, 8)
    if version != VERSION:
        raise bad("version", f"expected {VERSION}, got {version}")
    if hbytes != HEADER_BYTES:
        raise bad("header_bytes", f"expected {HEADER_BYTES}, got {hbytes}")
    if encoding != ENCODING_U16_MS:
        raise bad("encoding", f"expected {ENCODING_U16_MS} (uint16 ms), got {encoding}")
    if side not in (0, 1):
        raise bad("side", f"expected 0 (left) or 1 (right), got {side}")
    if layout != LAYOUT_XZYAW_Y:
        raise bad("layout", f"expected {LAYOUT_XZYAW_Y} ([x][z][yaw][y]), got {layout}")
    header_crc = struct.unpack_from("<I", data, 468)[0]
    if zlib.crc32(data[:468]) != header_crc:
        raise bad("header_crc", "CRC-32 of the header does not match")
    axes = {}
    for k, name in enumerate(AXES):
        origin, step, count, _ = struct.unpack_from("<ddII", data, 40 + 24 * k)
        if not (step > 0 and count >= 1 and np.isfinite(origin)):
            raise bad(f"grid.{name}", f"origin {origin}, step {step}, count {count} is not a grid")
        axes[name] = Axis(origin, step, count)
    cost_unit_s = struct.unpack_from("<d", data, 136)[0]
    base = struct.unpack_from("<4d", data, 144)
    payload_bytes, payload_crc = struct.unpack_from("<QI", data, 456)
    cells = 1
    for a in axes.values():
        cells *= a.count
    if payload_bytes != 2 * cells:
        raise bad("payload_bytes", f"{payload_bytes} does not match the grid's {cells} cells")
    if len(data) != HEADER_BYTES + payload_bytes:
        raise bad(
            "payload_bytes",
            f"file has {len(data) - HEADER_BYTES} payload bytes, header says {payload_bytes}",
        )
    payload = memoryview(data)[HEADER_BYTES:]
    if zlib.crc32(payload) != payload_crc:
        raise bad("payload_crc", "CRC-32 of the payload does not match")
    costs = np.frombuffer(payload, dtype="<u2").reshape(
        axes["x"].count, axes["z"].count, axes["yaw"].count, axes["y"].count
    )
    return CostTable(path, "L" if side == 0 else "R", bool(elbow), axes, cost_unit_s, base, costs)
