"""`harvest-stack live`: serve the running robot to Foxglove, live, from the executor's LCM
telemetry (server.py has the channels, scene.py the 3D scene, layout.json the panels)."""

import argparse
import os
import shutil

from .. import generated
from ..cmdline import (
    EXIT_FAILURE,
    EXIT_USAGE,
    Parser,
    error,
    open_lcm,
    os_error,
    stop_on_signals,
)

PROG = "harvest-stack live"
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"
LAYOUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "layout.json")
SDK_PIN = "foxglove-sdk==0.30.3"  # host/requirements.txt


def _port(text):
    try:
        port = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a port number, got {text!r}") from None
    if not 0 <= port <= 65535:
        raise argparse.ArgumentTypeError(f"expected a port in [0, 65535], got {port}")
    return port


def _parser():
    p = Parser(
        prog=PROG,
        description="Serve the running robot to Foxglove over its WebSocket protocol, from the "
        "executor's LCM telemetry: the vehicle and both arms in a 3D scene (the row, each "
        "fruit planned, picked, failed or skipped, the arms' links from their joint states), "
        "the plan, the executor's state and its faults. In Foxglove: Open connection -> "
        "Foxglove WebSocket -> ws://HOST:PORT, then import the layout (--write-layout). "
        "Runs until SIGINT or SIGTERM.",
    )
    p.add_argument(
        "--lcm-url",
        default=DEFAULT_URL,
        help=f"LCM URL the executor publishes on (default {DEFAULT_URL}: never leaves the host)",
    )
    p.add_argument(
        "--host",
        default="127.0.0.1",
        help="address to serve on (default 127.0.0.1, this machine only; 0.0.0.0 for a "
        "viewer on another machine)",
    )
    p.add_argument(
        "--port", type=_port, default=8765, help="TCP port (default 8765, Foxglove's; 0: any free)"
    )
    p.add_argument(
        "--config",
        default=None,
        help="config the executor runs with, for the arms' and the row's geometry (default: "
        "the project's config/harvest.cfg)",
    )
    p.add_argument(
        "--lcm-python",
        default=None,
        help="folder of the lcm-gen Python output (default: as `harvest-stack telemetry`)",
    )
    p.add_argument(
        "--lcm-defs",
        default=None,
        help="folder of the .lcm definitions (default: as `harvest-stack telemetry mcap`)",
    )
    p.add_argument(
        "--ready-file",
        default=None,
        help="once serving and subscribed, write the port served on to this file (for scripts)",
    )
    p.add_argument(
        "--write-layout",
        metavar="FILE",
        default=None,
        help="write the Foxglove layout of the live view to FILE and exit (import it in "
        "Foxglove: Layouts -> Import from file)",
    )
    return p


def _write_layout(path):
    try:
        shutil.copyfile(LAYOUT, path)
    except OSError as e:
        error(PROG, os_error(e))
        return EXIT_FAILURE
    print(f"{PROG}: wrote {path}")
    return 0


def main(argv=None):
    args = _parser().parse_args(argv)
    if args.write_layout:
        return _write_layout(args.write_layout)
    from ..scenario.config import Config, ConfigError, default_config_path
    from ..telemetry import lcm_schema, lcm_types

    try:
        cfg = Config.load(args.config or default_config_path())
        types = lcm_types.load(args.lcm_python)
        structs = lcm_schema.load(args.lcm_defs)
    except lcm_types.LcmTypesMissing as e:
        error(PROG, str(e))
        return EXIT_FAILURE
    except OSError as e:  # the definitions' folder
        error(PROG, os_error(e))
        return EXIT_USAGE
    except (ConfigError, ValueError) as e:  # each names its file
        error(PROG, str(e))
        return EXIT_USAGE
    try:
        import foxglove  # noqa: F401
    except ImportError as e:
        error(PROG, "foxglove-sdk", f"not installed ({e}): pip install {SDK_PIN}")
        return EXIT_FAILURE
    return _serve(args, cfg, types, structs)


def _serve(args, cfg, types, structs):
    from ..canbus import enums
    from . import scene
    from .server import LiveServer

    try:
        geometry = scene.Geometry(cfg)
    except ValueError as e:  # ConfigError: names the file and key
        error(PROG, str(e))
        return EXIT_USAGE
    stopped = stop_on_signals()
    lc = open_lcm(PROG, "--lcm-url", args.lcm_url)
    if lc is None:
        return EXIT_FAILURE

    try:
        server = LiveServer(
            geometry,
            types,
            structs,
            lambda bits: enums.flag_names(enums.ArmFault, bits),
            lambda s: enums.label(enums.State, s),
            args.host,
            args.port,
        )
    except RuntimeError as e:  # the SDK's: the address in use or not ours
        error(PROG, f"--host {args.host} --port {args.port}", f"cannot serve: {e}")
        return EXIT_FAILURE
    try:
        server.listen(lc)
        print(f"{PROG}: serving ws://{args.host}:{server.port} from {args.lcm_url}", flush=True)
        if args.ready_file:
            try:  # whole or not at all: a script may read it the moment it appears
                generated.write(args.ready_file, f"{server.port}\n")
            except OSError as e:
                error(PROG, os_error(e))
                return EXIT_FAILURE
        server.run(lc, stopped)
    finally:
        server.stop()
    taken = ", ".join(f"{ch} {n}" for ch, n in sorted(server.counts.items())) or "none"
    print(f"{PROG}: stopped; messages {taken}")
    if server.others:
        other = ", ".join(f"{ch} {n}" for ch, n in sorted(server.others.items()))
        print(f"{PROG}: not telemetry, left out: {other}")
    bad = sum(server.undecodable.values())
    if bad:
        error(PROG, f"{bad} messages did not decode", "left out (see above)")
    return 0
