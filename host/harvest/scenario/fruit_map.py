"""The planner's fruit-map CSV (`id,side,x,y,z,yaw`, m and rad, frames in docs/FRAMES.md)."""

import csv
import math
import os
from dataclasses import dataclass

HEADER = ["id", "side", "x", "y", "z", "yaw"]

# Fruit ids (docs/FRAMES.md, fruit map): the set of core/include/hv/fruit_id.h, which the
# planner and the executor enforce; an id outside it would not read back the same in the
# CSV, the plan's JSON or the executor's journal.
ID_MAX_CHARS = 31
_ID_CHARS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-")


def check_id(fid):
    """None when `fid` is a valid fruit id, else why not: the C readers' wording, with the
    character shown as Python writes it rather than as 0xNN."""
    if not fid:
        return "empty"
    if len(fid) > ID_MAX_CHARS:
        return f"{len(fid)} characters, more than {ID_MAX_CHARS}"
    for pos, ch in enumerate(fid, 1):
        if ch not in _ID_CHARS:
            return f"character {ch!r} at position {pos} not allowed (only A-Z a-z 0-9 _ . -)"
    return None


class FruitMapError(ValueError):
    """A fruit map that cannot be read: the message names the file, line and field."""


@dataclass(frozen=True)
class Fruit:
    id: str
    side: str  # "L" or "R"
    x: float  # m, vehicle frame (negative on the left)
    y: float  # m along the row
    z: float  # m above the floor
    yaw: float  # rad, relative to the side's inward normal


def write(path, fruits):
    """Write atomically (temp file + rename), so a crash never leaves half a map behind.
    An id outside the id set (check_id) raises FruitMapError and nothing is written.

    Fixed decimals (0.1 mm, 1e-5 rad: far below the 0.01 m / 5 deg table grid) make the
    file a pure function of the fruits, so one seed always gives the same bytes.
    """
    for n, fr in enumerate(fruits):
        why = check_id(fr.id)
        if why is not None:
            raise FruitMapError(f"{path}: fruit {n}: field 'id' {fr.id!r}: {why}")
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8", newline="") as f:
        f.write(",".join(HEADER) + "\n")
        for fr in fruits:
            f.write(f"{fr.id},{fr.side},{fr.x:.4f},{fr.y:.4f},{fr.z:.4f},{fr.yaw:.5f}\n")
    os.replace(tmp, path)


def read(path):
    try:
        f = open(path, encoding="utf-8", newline="")
    except OSError as e:
        raise FruitMapError(f"{path}: cannot read fruit map: {e.strerror}") from None
    with f:
        rows = csv.reader(f)
        header = next(rows, None)
        if header != HEADER:
            raise FruitMapError(f"{path}:1: header must be {','.join(HEADER)}, got {header}")
        fruits, seen = [], set()
        for n, row in enumerate(rows, 2):
            if len(row) != len(HEADER):
                raise FruitMapError(f"{path}:{n}: expected {len(HEADER)} fields, got {len(row)}")
            fid, side = row[0], row[1]
            why = check_id(fid)
            if why is not None:
                raise FruitMapError(f"{path}:{n}: field 'id' {fid!r}: {why}")
            if fid in seen:
                raise FruitMapError(f"{path}:{n}: field 'id' is repeated: {fid!r}")
            if side not in ("L", "R"):
                raise FruitMapError(f"{path}:{n}: field 'side' must be L or R, got {side!r}")
            vals = []
            for name, text in zip(HEADER[2:], row[2:]):
                try:
                    v = float(text)
                except ValueError:
                    v = math.nan
                if not math.isfinite(v):
                    raise FruitMapError(
                        f"{path}:{n}: field '{name}' is not a finite number: {text!r}"
                    )
                vals.append(v)
            seen.add(fid)
            fruits.append(Fruit(fid, side, *vals))
    return fruits
