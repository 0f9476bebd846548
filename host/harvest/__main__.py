"""`harvest-stack <command> [args]` (or `python -m harvest ...`): dispatch to
harvest.<command>.cli:main(argv)."""

import importlib
import sys

from .cmdline import EXIT_USAGE, error, exit_codes_help

COMMANDS = {
    "sim": "simulated vehicle drive and SCARA joint controllers on python-can",
    "scenario": "generate fruit maps (paper's uniform rows, clusters, gradients, long rows)",
    "experiments": "run the paper's comparison (FOV, Serial, MILP), plots and report",
    "telemetry": "log LCM telemetry and turn a log into a timeline plot",
    "live": "serve the running robot to Foxglove (WebSocket) from its LCM telemetry",
    "firmware": "a row with harvest-fw.elf in QEMU on the simulator's bus",
}


def _usage(stream):
    print(
        "usage: harvest-stack <command> [--help] [args...]   (or: python -m harvest ...)\n"
        "       harvest-stack --version\n\n"
        "commands:",
        file=stream,
    )
    for name, what in COMMANDS.items():
        print(f"  {name:<12} {what}", file=stream)
    print("\n" + exit_codes_help("a command's higher ones in its --help"), file=stream)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv:
        error("harvest-stack", "COMMAND", f"missing, one of {', '.join(COMMANDS)} (see --help)")
        return EXIT_USAGE
    if argv[0] in ("-h", "--help"):
        _usage(sys.stdout)
        return 0
    if argv[0] == "--version":
        from importlib.metadata import version

        print(f"harvest-stack {version('harvest-stack')}")
        return 0
    name, rest = argv[0], argv[1:]
    if name not in COMMANDS:
        why = "unknown option" if name.startswith("-") else "unknown command"
        error("harvest-stack", name, f"{why} (see --help)")
        return EXIT_USAGE
    module = importlib.import_module(f"harvest.{name}.cli")
    return module.main(rest)


if __name__ == "__main__":
    sys.exit(main())
