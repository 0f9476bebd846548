"""Record every LCM message on a URL into an LCM log file (the standard event-log format,
readable by lcm-logplayer and by `python -m harvest telemetry gantt`).

The log is flushed per message by the LCM writer; a run's end is seen in the executor's
own state (phase row_done or safe), after which the logger waits `--grace` seconds for the
last messages and stops. SIGINT/SIGTERM stop it cleanly too.
"""

import os
import time

import lcm

from ..cmdline import EXIT_FAILURE, EXIT_USAGE, error, open_lcm, stop_on_signals
from . import lcm_types, lcm_wait


class Logger:
    def __init__(self, lc, path, overwrite=False, stop_on_end=True, types=None):
        self.lc = lc
        self.log = lcm.EventLog(path, "w", overwrite=overwrite)
        self.types = types
        self.stop_on_end = stop_on_end
        self.count = 0
        self.channels = {}
        self.end_seen_at = None
        self.final_phase = None
        self.sub = self.lc.subscribe(".*", self._on_message)

    def _on_message(self, channel, data):
        utime = int(time.time() * 1e6)
        self.log.write_event(utime, channel, data)
        self.count += 1
        self.channels[channel] = self.channels.get(channel, 0) + 1
        if self.stop_on_end and channel == "HARVEST_EXEC_STATE" and self.types:
            st = self.types["exec_state_t"].decode(data)
            if st.phase in ("row_done", "safe", "stopped"):  # hv_exec_finished()
                self.final_phase = st.phase
                if self.end_seen_at is None:
                    self.end_seen_at = time.monotonic()

    def run(self, duration=None, grace=1.0, stop_flag=None):
        t0 = time.monotonic()
        stopped = stop_flag or (lambda: False)
        while lcm_wait.handle(self.lc, 100, stopped):
            now = time.monotonic()
            if stopped():
                break
            if duration is not None and now - t0 >= duration:
                break
            if self.end_seen_at is not None and now - self.end_seen_at >= grace:
                break

    def close(self):
        self.lc.unsubscribe(self.sub)
        self.log.close()


def run(args, prog):
    types = lcm_types.load(args.lcm_python) if args.until_done else None
    if os.path.exists(args.out) and not args.overwrite:
        error(prog, args.out, "exists (use --overwrite)")
        return EXIT_USAGE
    stopped = stop_on_signals()
    lc = open_lcm(prog, "--url", args.url)
    if lc is None:
        return EXIT_FAILURE
    try:
        lg = Logger(
            lc, args.out, overwrite=args.overwrite, stop_on_end=args.until_done, types=types
        )
    except OSError as e:  # LCM's writer names no file
        error(prog, args.out, f"cannot write the log: {e.strerror or e}")
        return EXIT_FAILURE
    if args.ready_file:
        # tell a caller (demo, tests) that we listen, so no early message is lost
        with open(args.ready_file, "w") as f:
            f.write(str(os.getpid()))
    try:
        lg.run(duration=args.duration, grace=args.grace, stop_flag=stopped)
    finally:
        lg.close()
    per = ", ".join(f"{k} {v}" for k, v in sorted(lg.channels.items()))
    print(
        f"telemetry log: {args.out}: {lg.count} messages ({per or 'none'})"
        + (f"; executor ended in {lg.final_phase}" if lg.final_phase else "")
    )
    return 0
