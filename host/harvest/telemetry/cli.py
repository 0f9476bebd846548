"""`harvest-stack telemetry {log,gantt,summary,mcap}`: record the executor's LCM telemetry,
turn a log into a Gantt timeline of the vehicle and both arms, planned against actual,
with the faults marked, or export it to MCAP."""

import json

from ..cmdline import EXIT_FAILURE, EXIT_USAGE, Parser, error, os_error
from . import lcm_types

PROG = "harvest-stack telemetry"


def _parser():
    p = Parser(
        prog=PROG,
        description="Record the executor's LCM telemetry (channels HARVEST_*) into an LCM log, "
        "and turn a log into a Gantt timeline (PNG/SVG) of the vehicle and both arms per "
        "stop, planned against actual, faults marked with their names.",
    )
    p.add_argument(
        "--lcm-python",
        default=None,
        help="folder of the lcm-gen Python output (default: $HV_BUILD_DIR/lcm_types/python, "
        "else the source tree's build/lcm_types/python, else the installed package's copy)",
    )
    sub = p.add_subparsers(dest="cmd", required=True, metavar="COMMAND")
    lg = sub.add_parser("log", help="record every message on an LCM URL into a log file")
    lg.add_argument(
        "--url",
        default="udpm://239.255.76.67:7667?ttl=0",
        help="LCM URL (default udpm://239.255.76.67:7667?ttl=0: never leaves the host)",
    )
    lg.add_argument("--out", required=True, help="LCM log file to write")
    lg.add_argument("--overwrite", action="store_true", help="replace an existing log")
    lg.add_argument("--duration", type=float, default=None, help="stop after this many s")
    lg.add_argument(
        "--until-done",
        action="store_true",
        help="stop once the executor reports row_done or safe (plus --grace)",
    )
    lg.add_argument("--grace", type=float, default=1.0, help="s to keep logging after the end")
    lg.add_argument(
        "--ready-file",
        default=None,
        help="write this file once subscribed (for scripts that start the executor after)",
    )
    g = sub.add_parser("gantt", help="plot a log as a Gantt timeline (PNG or SVG by extension)")
    g.add_argument("log", help="LCM log written by `telemetry log`")
    g.add_argument(
        "--out", required=True, action="append", help="output file, .png or .svg (repeat for both)"
    )
    g.add_argument("--title", default=None)
    s = sub.add_parser("summary", help="print what a log says about the run, as JSON")
    s.add_argument("log")
    m = sub.add_parser(
        "mcap",
        help="export a log to MCAP (JSON messages, a JSON Schema per "
        "channel from the .lcm definitions) for robotics viewers",
    )
    m.add_argument("log", help="LCM log written by `telemetry log`")
    m.add_argument("--out", required=True, help="MCAP file to write")
    m.add_argument(
        "--lcm-defs",
        default=None,
        help="folder of the .lcm definitions (default: lcm_types/ of the source tree, "
        "else the installed package's copy)",
    )
    return p


def _torn(prog, path, torn_at):
    if torn_at is not None:
        error(prog, path, f"byte {torn_at}: the last event is cut short (left out)")


def main(argv=None):
    args = _parser().parse_args(argv)
    prog = f"{PROG} {args.cmd}"
    if args.cmd == "gantt":
        for out in args.out:
            if not out.endswith((".png", ".svg")):
                error(prog, f"--out {out}", "expected a .png or .svg file (see --help)")
                return EXIT_USAGE
    try:
        if args.cmd == "log":
            from . import logger

            return logger.run(args, prog)
        if args.cmd == "mcap":
            from . import mcap_export

            counts, torn_at = mcap_export.export(args.log, args.out, args.lcm_python, args.lcm_defs)
            _torn(prog, args.log, torn_at)
            print(
                f"telemetry mcap: wrote {args.out}: "
                + ", ".join(f"{ch} {n}" for ch, n in sorted(counts.items()))
            )
            return 0
        from . import timeline

        tl = timeline.read(args.log, args.lcm_python)
        _torn(prog, args.log, tl.torn_at)
        if tl.plan is None:
            error(prog, args.log, "no HARVEST_PLAN message in the log")
            return EXIT_USAGE
        if args.cmd == "summary":
            print(json.dumps(timeline.summary(tl), indent=2))
            return 0
        from . import gantt

        for out in args.out:
            gantt.plot(tl, out, args.title)
            print(f"telemetry gantt: wrote {out}")
        return 0
    except lcm_types.LcmTypesMissing as e:
        error(prog, str(e))
        return EXIT_FAILURE
    except ValueError as e:  # the log's content (eventlog.LogError too), naming the file
        error(prog, str(e))
        return EXIT_USAGE
    except OSError as e:  # the log not read is bad input; an output not written, a failure
        error(prog, os_error(e))
        return EXIT_USAGE if e.filename == getattr(args, "log", None) else EXIT_FAILURE
