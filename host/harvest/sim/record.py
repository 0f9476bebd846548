"""The simulator's record: one JSON object per line for everything it did (commands
received, moves, picks, injected faults), for tests to check an executor from outside.

Every line carries `t` (simulated s of the event) and `wall` (s since start when written);
a line is flushed as soon as it is written, so a killed simulator loses at most the line
in flight.
"""

import json
import threading


def _clean(value):
    """Floats rounded to the micro-unit, so lines stay short and diffs stay readable."""
    if isinstance(value, float):
        return round(value, 6)
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    return value


class Record:
    """Append-only JSONL writer; `None` path keeps the events in memory only."""

    def __init__(self, path=None):
        self.path = path
        self.events = []
        self._lock = threading.Lock()
        self._file = open(path, "w", encoding="utf-8") if path else None

    def write(self, t, wall, node, event, **fields):
        line = {"t": t, "wall": wall, "node": node, "event": event}
        line.update(fields)
        line = _clean(line)
        with self._lock:
            self.events.append(line)
            if self._file:
                self._file.write(json.dumps(line, separators=(",", ":")) + "\n")
                self._file.flush()

    def close(self):
        with self._lock:
            if self._file:
                self._file.close()
                self._file = None


def read(path):
    """The events of a record file, in order."""
    with open(path, encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]
