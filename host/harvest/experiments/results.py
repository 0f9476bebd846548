"""The results CSV: one row per (instance, method), appended and synced as each finishes.

Resuming reads the rows already there and skips their keys, so an interrupted run never
recomputes finished work. A kill can at worst leave a torn last line (no newline): it is
cut off on open, with a warning, and that row is computed again.
"""

import csv
import io
import os
import sys

KEY = ("distribution", "alpha", "seed", "method")
COLUMNS = KEY + (
    "n_left",
    "n_right",
    "stops",
    "makespan_s",
    "throughput_fruit_per_s",
    "runtime_s",
    "status",
    "gap",
    "pick_time_s",
    "stop_time_s",
    "travel_time_s",
    "idle_s",
    "fruits_planned",
    "fruits_unreachable",
    "fov_moved",
    "time_limit_s",
    "wall_s",
    "plan",
    "finished_utc",
    "error",
)
FLOAT_COLUMNS = (
    "alpha",
    "makespan_s",
    "throughput_fruit_per_s",
    "runtime_s",
    "gap",
    "pick_time_s",
    "stop_time_s",
    "travel_time_s",
    "idle_s",
    "time_limit_s",
    "wall_s",
)
INT_COLUMNS = (
    "seed",
    "n_left",
    "n_right",
    "stops",
    "fruits_planned",
    "fruits_unreachable",
    "fov_moved",
)


class ResultsError(ValueError):
    pass


def row_key(row):
    """(distribution, alpha, seed, method) with alpha as text of a float: '1.0' == '1'."""
    return (row["distribution"], float(row["alpha"]), int(row["seed"]), row["method"])


def _typed(path, n, row):
    out = dict(row)
    for c in FLOAT_COLUMNS + INT_COLUMNS:
        text = row[c]
        if text == "":
            out[c] = None
            continue
        try:
            out[c] = int(text) if c in INT_COLUMNS else float(text)
        except ValueError:
            raise ResultsError(f"{path}:{n}: field '{c}' is not a number: {text!r}") from None
    return out


def read(path):
    """Typed rows of a results file (ints, floats, None for empty); [] when it does not exist."""
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8", newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return []
    if tuple(rows[0]) != COLUMNS:
        raise ResultsError(
            f"{path}:1: header is not this runner's columns "
            f"({','.join(COLUMNS)}): use another --out directory"
        )
    out = []
    for n, r in enumerate(rows[1:], 2):
        if len(r) != len(COLUMNS):
            raise ResultsError(f"{path}:{n}: expected {len(COLUMNS)} fields, got {len(r)}")
        out.append(_typed(path, n, dict(zip(COLUMNS, r))))
    return out


class ResultsFile:
    """Append-only results with the keys already done; each append is flushed and fsynced."""

    def __init__(self, path, log=sys.stderr):
        self.path = path
        self._repair_torn_tail(log)
        rows = read(path)
        self.done = {row_key(r): r for r in rows}
        if len(self.done) != len(rows):
            raise ResultsError(
                f"{path}: the same (distribution, alpha, seed, method) appears twice"
            )
        if not rows and not self._has_header():
            with open(path, "w", encoding="utf-8", newline="") as f:
                f.write(self._line(COLUMNS))
                f.flush()
                os.fsync(f.fileno())

    def _has_header(self):
        return os.path.exists(self.path) and os.path.getsize(self.path) > 0

    def _repair_torn_tail(self, log):
        if not os.path.exists(self.path):
            return
        with open(self.path, "rb+") as f:
            data = f.read()
            if not data or data.endswith(b"\n"):
                return
            keep = data.rfind(b"\n") + 1
            print(
                f"results: {self.path}: dropping an unfinished last line "
                f"({len(data) - keep} bytes) left by an interrupted run",
                file=log,
            )
            f.truncate(keep)

    @staticmethod
    def _line(values):
        buf = io.StringIO()
        csv.writer(buf, lineterminator="\n").writerow(values)
        return buf.getvalue()

    def append(self, row):
        missing = [c for c in COLUMNS if c not in row]
        if missing:
            raise ResultsError(f"results row lacks {', '.join(missing)}")
        values = [
            "" if row[c] is None else (repr(row[c]) if isinstance(row[c], float) else row[c])
            for c in COLUMNS
        ]
        line = self._line(values)
        # One write of the whole line, then flush + fsync: a kill between rows loses nothing.
        with open(self.path, "a", encoding="utf-8", newline="") as f:
            f.write(line)
            f.flush()
            os.fsync(f.fileno())
        self.done[row_key(row)] = row

    def drop_errors(self):
        """Remove the rows whose plan failed (rewrite + rename), so they are run again."""
        rows = read(self.path)
        keep = [r for r in rows if r["status"] != "error"]
        if len(keep) == len(rows):
            return 0
        with open(self.path, encoding="utf-8", newline="") as f:
            lines = f.read().splitlines(keepends=True)
        # read() kept the file's row order, so line k + 1 is rows[k]
        kept_lines = [lines[0]] + [
            lines[k + 1] for k, r in enumerate(rows) if r["status"] != "error"
        ]
        tmp = f"{self.path}.tmp{os.getpid()}"
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.writelines(kept_lines)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, self.path)
        self.done = {row_key(r): r for r in keep}
        return len(rows) - len(keep)
