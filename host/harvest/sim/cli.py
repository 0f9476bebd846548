"""`harvest-stack sim`: the vehicle drive and both SCARA joint controllers on a CAN bus."""

import argparse
import signal
import sys
import threading
import time

import can

from harvest.canbus import buses
from harvest.cmdline import EXIT_FAILURE, EXIT_USAGE, Parser, error, os_error

from . import faults as faults_mod
from .clock import ScaledClock
from .model import ConfigError, Model
from .record import Record
from .runner import REJECT_REASONS, Options, Simulator

PROG = "harvest-stack sim"
EPILOG = """\
times: every duration below is simulated seconds except --exec-timeout and --duration
(wall). A --time-scale of 20 runs the physics, the periodic frames and the injected
faults 20 times faster; the nodes' heartbeats carry the factor for the executor.

faults (repeat --fault; same fields in a --scenario JSON file {"seed": N, "faults": [...]}):
  drop:fraction=F[,direction=tx|rx|both][,node=N]      drop a fraction of frames (seeded)
  delay:delay_s=S[,direction=tx|rx|both][,node=N]      hold frames back by S
  stall:node=ARM,joint=J[,setpoint=N][,fraction=F]     joint J stops at F of its way on the
                                                       N-th accepted setpoint: never reached
  joint_fault:node=ARM,joint=J,pick=K[,kind=following|limit]
  joint_fault:node=ARM,joint=J,setpoint=N[,at=F][,kind=...]
  joint_fault:node=ARM,joint=J,home=N[,at=F][,kind=...]
                                                       FAULT with joint J's bit at the K-th
                                                       CUT, or at F of setpoint N's or of
                                                       homing N's motion
  silent:after_s=S[,node=N][,frames=all|heartbeat][,for_s=D]
  silent:node=ARM,pick=K[,frames=...][,for_s=D]        stop sending after S, or just after
                                                       the arm's K-th pick (for D)
  reject:node=ARM,setpoint=N                           refuse the N-th setpoint (bit 11)
  estop:after_s=S[,node=N]                             the node's own e-stop trips at S
  estop:node=ARM,pick=K                                ... just after the arm's K-th pick;
                                                       latched until CLEAR_ESTOP
  nodes: vehicle, left_arm, right_arm, all (default); ARM: left_arm or right_arm

examples:
  harvest-stack sim --interface socketcan --channel vcan0 --time-scale 20
  harvest-stack sim --bus udp:239.74.163.2:43113 \\
      --fault drop:fraction=0.05 --fault joint_fault:node=left_arm,joint=2,pick=3 \\
      --record sim.jsonl
"""


def _scale(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    # the heartbeat carries it in 0.01 steps up to 655.35 (DBC TimeScale)
    if not 0.01 <= v <= 655.35 or abs(round(v, 2) - v) > 1e-9:
        raise argparse.ArgumentTypeError(f"{text!r}: must be in [0.01, 655.35] in steps of 0.01")
    return round(v, 2)


def _positive(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not v > 0 or v == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r}: must be > 0")
    return v


def _non_negative(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not v >= 0 or v == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r}: must be >= 0")
    return v


def build_parser():
    p = Parser(
        prog=PROG,
        description="Simulate the vehicle drive and the left and right SCARA joint controllers "
        "on a CAN bus (frames of executor/can/harvest.dbc), with a time scale, "
        "fault injection and a JSONL record of everything done.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    bus = p.add_argument_group("bus")
    bus.add_argument(
        "--bus",
        metavar="SPEC",
        help="socketcan:IFNAME or udp[:GROUP[:PORT]] (the specs of hv-can-tool); "
        "overrides --interface/--channel",
    )
    bus.add_argument(
        "--interface",
        default="socketcan",
        help="python-can interface: socketcan, udp_multicast, virtual (default socketcan)",
    )
    bus.add_argument(
        "--channel",
        default="vcan0",
        help="channel: vcan0, a multicast group (239.74.163.2), a virtual name",
    )
    bus.add_argument("--port", type=int, default=43113, help="udp_multicast port (43113)")
    sim = p.add_argument_group("simulation")
    sim.add_argument(
        "--time-scale",
        type=_scale,
        default=1.0,
        help="simulated seconds per wall second (default 1)",
    )
    sim.add_argument(
        "--rate",
        type=_positive,
        default=None,
        help="joint state, velocity and status rate, simulated Hz (default: the DBC's "
        "JointState cycle)",
    )
    sim.add_argument(
        "--heartbeat-period",
        type=_positive,
        default=None,
        help="simulated s between heartbeats (default: the DBC's cycle time)",
    )
    sim.add_argument(
        "--exec-timeout",
        type=_non_negative,
        default=None,
        help="wall s without executor heartbeat before COMM_TIMEOUT, armed by the "
        "first heartbeat; 0 disables (default: the DBC's TimeoutTime)",
    )
    sim.add_argument(
        "--cut-time",
        type=_non_negative,
        default=None,
        help="CUT duration, s (default: pick.cut_time of the config)",
    )
    sim.add_argument(
        "--release-time",
        type=_non_negative,
        default=None,
        help="RELEASE duration, s (default: pick.release_time of the config)",
    )
    sim.add_argument(
        "--arm-start",
        type=float,
        nargs=4,
        metavar="Q",
        help="joint positions (m rad rad rad) of both arms at start (default: home)",
    )
    sim.add_argument("--vehicle-start", type=float, default=0.0, help="vehicle position, m (0)")
    sim.add_argument(
        "--travel",
        type=float,
        nargs=2,
        metavar=("MIN", "MAX"),
        help="vehicle travel limits, m; moves outside are refused (default: none)",
    )
    sim.add_argument("--config", help="harvest.cfg (default: config/harvest.cfg of the tree)")
    sim.add_argument("--dbc", help="DBC file (default: executor/can/harvest.dbc)")
    cam = p.add_argument_group("online mode: the camera (DESIGN §5)")
    cam.add_argument(
        "--fruits",
        metavar="MAP.csv",
        help="reveal this fruit map ahead of the vehicle as the camera of the config "
        "sees it (camera.lead, camera.window): camera_frame_t on HARVEST_CAMERA",
    )
    cam.add_argument(
        "--lcm-url",
        default="udpm://239.255.76.67:7667?ttl=0",
        help="LCM URL of the camera (default udpm://239.255.76.67:7667?ttl=0)",
    )
    cam.add_argument(
        "--camera-period",
        type=_positive,
        default=0.5,
        help="simulated s between camera frames (0.5)",
    )
    cam.add_argument(
        "--camera-bad",
        type=int,
        default=0,
        metavar="N",
        help="also send N detections of each bad kind (outside the row, a fruit "
        "seen twice, a fruit behind the vehicle), spread over the row (0)",
    )
    f = p.add_argument_group("faults and record")
    f.add_argument(
        "--fault",
        action="append",
        default=[],
        metavar="TYPE:K=V,...",
        help="inject a fault (repeatable, see below)",
    )
    f.add_argument("--scenario", help="JSON file of faults (and a seed)")
    f.add_argument("--seed", type=int, default=None, help="seed of the random drops (0)")
    f.add_argument("--record", help="write the JSONL record here")
    f.add_argument(
        "--duration",
        type=_non_negative,
        default=0.0,
        help="stop after this many wall seconds (default: run until SIGINT/SIGTERM)",
    )
    f.add_argument(
        "--progress",
        type=_non_negative,
        default=0.0,
        help="print a progress line every this many wall s (default off)",
    )
    return p


def _options(args, model):
    faults = []
    seed = None
    if args.scenario:
        seed, faults = faults_mod.load_scenario(args.scenario)
    faults += [faults_mod.parse_flag(text) for text in args.fault]
    if args.seed is not None:
        seed = args.seed
    if args.arm_start:
        for j, (q, lim) in enumerate(zip(args.arm_start, model.joints), 1):
            if not lim.contains(q):
                raise ValueError(f"--arm-start: joint {j} = {q} outside [{lim.min}, {lim.max}]")
    if args.travel and args.travel[0] >= args.travel[1]:
        raise ValueError(f"--travel: MIN {args.travel[0]} must be below MAX {args.travel[1]}")
    if args.travel and not args.travel[0] <= args.vehicle_start <= args.travel[1]:
        raise ValueError(f"--vehicle-start {args.vehicle_start} outside --travel")
    return Options(
        time_scale=args.time_scale,
        rate_hz=args.rate,
        heartbeat_s=args.heartbeat_period,
        exec_timeout_s=args.exec_timeout,
        cut_s=args.cut_time,
        release_s=args.release_time,
        faults=faults,
        seed=seed or 0,
        arm_start=args.arm_start,
        vehicle_start_m=args.vehicle_start,
        travel=tuple(args.travel) if args.travel else None,
        progress_s=args.progress,
        camera=_camera(args),
    )


def _camera(args):
    """The camera's options (online mode), None without --fruits."""
    if not args.fruits:
        return None
    if args.camera_bad < 0:
        raise ValueError(f"--camera-bad {args.camera_bad}: must be >= 0")
    from harvest.scenario import fruit_map

    return {
        "fruits": fruit_map.read(args.fruits),
        "url": args.lcm_url,
        "period_s": args.camera_period,
        "bad": args.camera_bad,
    }


def bus_spec(args):
    """(description, spec for harvest.canbus.buses or None, python-can kwargs or None)."""
    if args.bus:
        return args.bus, args.bus, None
    if args.interface == "socketcan":
        spec = f"socketcan:{args.channel}"
        return spec, spec, None
    if args.interface == "udp_multicast":
        spec = f"udp:{args.channel}:{args.port}"
        return spec, spec, None
    return (
        f"{args.interface}:{args.channel}",
        None,
        {"interface": args.interface, "channel": args.channel},
    )


def open_bus(args):
    """The python-can bus: socketcan and udp_multicast through the CAN helpers (which give
    udp a hop limit of 0, so frames never leave the host), anything else as python-can's."""
    _, spec, kwargs = bus_spec(args)
    if spec is not None:
        return buses.open_bus(spec)
    return can.Bus(**kwargs)


def main(argv=None, stop_event=None):
    """Run the simulator; `stop_event` (a threading.Event) stops it from another thread."""
    args = build_parser().parse_args(argv)
    from harvest.canbus import protocol

    try:
        proto = protocol.load(args.dbc) if args.dbc else protocol.load()
    except Exception as e:  # cantools raises parser-specific errors for a malformed file
        error(PROG, args.dbc or protocol.DBC_PATH, f"cannot load the DBC: {e}")
        return EXIT_USAGE
    try:
        model = Model.load(args.config)
        options = _options(args, model)
    except OSError as e:
        error(PROG, os_error(e))
        return EXIT_USAGE
    except (ConfigError, faults_mod.FaultError, ValueError) as e:
        error(PROG, str(e))
        return EXIT_USAGE
    where = bus_spec(args)[0]
    try:
        bus = open_bus(args)
    except ValueError as e:  # a malformed --bus spec
        error(PROG, "--bus", str(e))
        return EXIT_USAGE
    except Exception as e:  # python-can raises interface-specific errors
        error(PROG, where, f"cannot open: {e}")
        return EXIT_FAILURE
    stop_event = stop_event or threading.Event()
    try:
        record = Record(args.record)
    except OSError as e:
        bus.shutdown()
        error(PROG, args.record, f"cannot write the record: {e.strerror}")
        return EXIT_FAILURE
    clock = ScaledClock(options.time_scale, time.monotonic)
    try:
        sim = Simulator(
            bus,
            proto,
            model,
            options,
            record,
            clock,
            stop_event,
            out=sys.stderr if options.progress_s else None,
        )
    except ValueError as e:  # the DBC's enums disagree with the simulator's
        record.close()
        bus.shutdown()
        error(PROG, args.dbc or protocol.DBC_PATH, str(e))
        return EXIT_USAGE
    old = {}
    if threading.current_thread() is threading.main_thread():
        for sig in (signal.SIGINT, signal.SIGTERM):
            old[sig] = signal.signal(sig, lambda *_: stop_event.set())
    timer = None
    if args.duration:
        timer = threading.Timer(args.duration, stop_event.set)
        timer.daemon = True
        timer.start()
    print(
        f"harvest sim: {where} x{options.time_scale:g} "
        f"rate {sim.rate_hz:g} Hz, {len(options.faults)} fault(s)"
        + (f", record {args.record}" if args.record else ""),
        file=sys.stderr,
        flush=True,
    )
    try:
        sim.run()
    finally:
        record.close()
        bus.shutdown()
        if timer:
            timer.cancel()
        for sig, handler in old.items():
            signal.signal(sig, handler)
    s = sim.stats
    rejected = sum(s[f"rx_{r}"] for r in REJECT_REASONS)
    camera = ""
    if sim.camera:
        c = sim.camera.stats()
        camera = (
            f"; camera revealed {c['revealed']} fruits, replayed them {c['replays']} times "
            f"({c['replayed']} detections)"
        )
    print(
        f"harvest sim: stopped at t={clock.sim():.2f} s simulated: sent {s['tx']} received "
        f"{s['rx']} dropped {s['tx_dropped']}+{s['rx_dropped']} rejected {rejected} picks "
        f"{sum(a.picks for a in sim.arms.values())}{camera}",
        file=sys.stderr,
    )
    return 0
