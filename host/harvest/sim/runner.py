"""The simulator program: three nodes on one python-can bus, driven by a scaled clock.

One thread does everything (receive, advance the nodes, send periodic frames), so the order
of events is simple to reason about. Motion is analytic (sim.profile), so the simulated time
of "target reached" or "arrived" is exact whatever the load; the loop only has to wake up
often enough to send the periodic frames, which it does by sleeping in bus.recv() until the
next deadline.

Faults on the wire (drop, delay, silent) sit between the nodes and the bus: outgoing frames
are encoded when a node emits them, then dropped, held back or sent; incoming frames are
decoded once and delivered to each addressed node, each delivery subject to that node's rx
faults. The executor's heartbeat watchdog runs in wall time: the DBC makes the executor's
TimeScale informational, so its heartbeat period is not scaled.
"""

import heapq
import random
import threading

import can

from harvest.canbus import buses
from harvest.canbus.enums import State, check_same

from .arm import ArmNode
from .faults import ARMS, NODES
from .vehicle import VehicleNode

MAX_SLEEP_WALL_S = 0.05  # longest recv() wait, so a stop request is seen promptly
# Input the simulator cannot take is counted and dropped, never fatal; these name why.
REJECT_REASONS = ("bad_datagram", "not_data_frame", "unknown_id", "wrong_length", "bad_value")
MAX_REJECT_RECORDS = (
    100  # record lines per reason (a flood must not fill the disk); stats count all
)


class Options:
    """Everything the command line sets, with the defaults of `python -m harvest sim`."""

    def __init__(self, **kw):
        self.time_scale = kw.pop("time_scale", 1.0)
        # joint state and status, simulated Hz; None: the DBC's JointState cycle
        self.rate_hz = kw.pop("rate_hz", None)
        self.heartbeat_s = kw.pop("heartbeat_s", None)  # None: the DBC's cycle time
        # wall s; None: the DBC's TimeoutTime of the executor's heartbeat; 0: no watchdog
        self.exec_timeout_s = kw.pop("exec_timeout_s", None)
        self.cut_s = kw.pop("cut_s", None)  # s; None: the config's pick.cut_time
        self.release_s = kw.pop("release_s", None)  # s; None: the config's pick.release_time
        self.faults = kw.pop("faults", [])
        self.seed = kw.pop("seed", 0)
        self.arm_start = kw.pop("arm_start", None)  # joint positions, None: home pose
        self.vehicle_start_m = kw.pop("vehicle_start_m", 0.0)
        self.travel = kw.pop("travel", None)  # (min, max) m, None: unlimited
        self.progress_s = kw.pop("progress_s", 0.0)  # wall s between progress lines, 0: off
        self.camera = kw.pop("camera", None)  # {fruits, url, period_s, bad}: online
        if kw:
            raise TypeError(f"unknown options: {', '.join(sorted(kw))}")


class Simulator:
    def __init__(self, bus, proto, model, options, record, clock, stop_event=None, out=None):
        self.bus, self.proto, self.model, self.opt = bus, proto, model, options
        missing = [n for n in ("executor",) + NODES if n not in proto.nodes]
        if missing:
            raise ValueError(f"{proto.path}: no node {missing[0]} (the simulator's nodes)")
        self.prefix = {n: proto.nodes[n].prefix for n in NODES}
        self.exec_timeout_s = (
            proto.timeout_s("heartbeat")
            if options.exec_timeout_s is None
            else options.exec_timeout_s
        )
        self.rate_hz = options.rate_hz or 1.0 / proto.cycle_s("joint_state")
        cut_s = model.cut_s if options.cut_s is None else options.cut_s
        release_s = model.release_s if options.release_s is None else options.release_s
        self.record, self.clock = record, clock
        self.stop_event = stop_event or threading.Event()
        self.out = out
        check_same(proto)  # the nodes use the value tables of the DBC read at import
        self.stats = {
            "tx": 0,
            "rx": 0,
            "tx_dropped": 0,
            "rx_dropped": 0,
            "tx_delayed": 0,
            "rx_delayed": 0,
            "tx_silenced": 0,
            "tx_errors": 0,
            "ignored": 0,
            **{f"rx_{r}": 0 for r in REJECT_REASONS},
        }
        self.vehicle = VehicleNode(
            model, self._logger("vehicle"), options.vehicle_start_m, options.travel
        )
        vpos = lambda t: self.vehicle.positions(t)[0]  # noqa: E731
        self.arms = {
            name: ArmNode(
                name,
                model,
                self._logger(name),
                options.faults,
                options.arm_start,
                cut_s,
                release_s,
                vpos,
            )
            for name in ARMS
        }
        self.nodes = {"vehicle": self.vehicle, **self.arms}
        self.camera = None
        if options.camera:
            from .camera import Camera

            c = options.camera
            self.camera = Camera(
                c["fruits"],
                model.camera_lead,
                model.camera_window,
                model.row_length,
                c["url"],
                self._logger("camera"),
                c.get("period_s", 0.5),
                c.get("bad", 0),
            )
        self._build_wire_faults()
        self._build_schedule()
        self._tx_queue = []  # (release sim t, order, can.Message)
        self._rx_queue = []  # (release sim t, order, node, name, signals)
        self._order = 0
        self._last_hb_wall = {n: None for n in self.nodes}  # executor heartbeat seen per node
        self._hb_tripped = {n: False for n in self.nodes}
        self._warned = set()

    # -- set-up -------------------------------------------------------------------------------
    def _logger(self, node):
        def log(t, event, **fields):
            self.record.write(t, self.clock.wall(), node, event, **fields)

        return log

    def _build_wire_faults(self):
        self._drops, self._delays, self._silent = [], [], []
        self._timed_estops = []  # [(sim t, node)] still to trip, soonest first
        for i, f in enumerate(self.opt.faults):
            nodes = NODES if f.get("node", "all") == "all" else (f["node"],)
            if f["type"] == "drop":
                # one generator per fault, so one fault's draws do not shift another's
                rng = random.Random(f"{self.opt.seed}:{i}")
                self._drops.append((f, set(nodes), rng))
            elif f["type"] == "delay":
                self._delays.append((f, set(nodes)))
            elif f["type"] == "silent":
                self._silent.append((f, set(nodes), i))
            elif f["type"] == "estop" and "after_s" in f:
                self._timed_estops += [(f["after_s"], n) for n in nodes]
        self._timed_estops.sort()
        self._silent_logged = set()
        self._silent_ended = set()

    def _silence_start(self, f, node):
        """Simulated time a silent fault starts on `node`, None while its pick is to come."""
        if "after_s" in f:
            return f["after_s"]
        times = self.arms[node].pick_times
        return times[f["pick"] - 1] if len(times) >= f["pick"] else None

    def _silenced(self, t, node, kind):
        """Whether a silent fault holds back this frame; records where a silence starts and ends."""
        for f, nodes, i in self._silent:
            if node not in nodes or (f["frames"] != "all" and kind != "Heartbeat"):
                continue
            start = self._silence_start(f, node)
            if start is None or t < start:
                continue
            if "for_s" in f and t >= start + f["for_s"]:
                if (i, node) not in self._silent_ended:
                    self._silent_ended.add((i, node))
                    self.record.write(
                        start + f["for_s"],
                        self.clock.wall(),
                        node,
                        "fault_ended",
                        fault="silent",
                        frames=f["frames"],
                    )
                continue
            if (i, node) not in self._silent_logged:
                self._silent_logged.add((i, node))
                self.record.write(
                    start,
                    self.clock.wall(),
                    node,
                    "fault_injected",
                    fault="silent",
                    frames=f["frames"],
                    for_s=f.get("for_s"),
                )
            return True
        return False

    def _trip_timed_estops(self, t):
        while self._timed_estops and self._timed_estops[0][0] <= t:
            at, node = self._timed_estops.pop(0)
            n = self.nodes[node]
            n.update(at)
            self.record.write(at, self.clock.wall(), node, "fault_injected", fault="estop")
            n.estop(at, "injected e-stop")

    def _build_schedule(self):
        period = 1.0 / self.rate_hz
        self._periodic = []  # [next sim t, period, node, kind]
        for name in NODES:
            hb = self.opt.heartbeat_s
            if hb is None:
                hb = self.proto.cycle_s("heartbeat")
            self._periodic.append([0.0, hb, name, "heartbeat"])
            self._periodic.append([0.0, period, name, "feedback"])
        self._hb_counter = {n: 0 for n in NODES}
        self._js_counter = {n: 0 for n in NODES}

    # -- output path --------------------------------------------------------------------------
    def _wire_match(self, faults, node, direction):
        return [x for x in faults if node in x[1] and x[0]["direction"] in (direction, "both")]

    def emit(self, t, node, kind, signals):
        name = f"{self.prefix[node]}{kind}"
        if self._silenced(t, node, kind):
            self.stats["tx_silenced"] += 1
            return
        for f, _, rng in self._wire_match(self._drops, node, "tx"):
            if rng.random() < f["fraction"]:
                self.stats["tx_dropped"] += 1
                return
        msg_def = self.proto.message(name)
        data = self.proto.encode(name, signals)
        msg = can.Message(arbitration_id=msg_def.frame_id, data=data, is_extended_id=False)
        delay = sum(f["delay_s"] for f, _ in self._wire_match(self._delays, node, "tx"))
        if delay > 0:
            self.stats["tx_delayed"] += 1
            self._order += 1
            heapq.heappush(self._tx_queue, (t + delay, self._order, msg))
            return
        self._send(t, msg)

    def _send(self, t, msg):
        try:
            self.bus.send(msg, timeout=0.1)
            self.stats["tx"] += 1
        except can.CanError as e:
            self.stats["tx_errors"] += 1
            if "tx_error" not in self._warned:
                self._warned.add("tx_error")
                self.record.write(t, self.clock.wall(), None, "tx_error", error=str(e))

    def _feedback(self, t, node):
        n = self.nodes[node]
        if node == "vehicle":
            self.emit(t, node, "Status", n.status_signals(t))
            n.changed = False
            return
        self._js_counter[node] = (self._js_counter[node] + 1) % 32
        self.emit(t, node, "JointState", n.joint_state_signals(t, self._js_counter[node]))
        self.emit(t, node, "JointVelocity", n.joint_velocity_signals(t))
        self.emit(t, node, "Status", n.status_signals())
        self.emit(t, node, "EeStatus", n.ee_status_signals())
        n.changed = n.ee_changed = False

    def _heartbeat(self, t, node):
        self._hb_counter[node] = (self._hb_counter[node] + 1) % 256
        self.emit(
            t,
            node,
            "Heartbeat",
            {
                "Counter": self._hb_counter[node],
                "Health": self.nodes[node].health(),
                "TimeScale": round(self.opt.time_scale, 2),
                "ProtocolVersion": self.proto.version,
            },
        )

    def _send_changes(self, t):
        """Status at once when State, TargetReached, FaultBits or an echoed seq changed."""
        for name, n in self.nodes.items():
            if n.changed:
                n.changed = False
                if name == "vehicle":
                    self.emit(t, name, "Status", n.status_signals(t))
                else:
                    self.emit(t, name, "Status", n.status_signals())
            if name != "vehicle" and n.ee_changed:
                n.ee_changed = False
                self.emit(t, name, "EeStatus", n.ee_status_signals())

    # -- input path ---------------------------------------------------------------------------
    def reject(self, t, reason, **fields):
        """Count and drop input the simulator cannot take; the first MAX_REJECT_RECORDS of
        each reason go to the record as `rx_rejected`."""
        key = f"rx_{reason}"
        self.stats[key] += 1
        if self.stats[key] <= MAX_REJECT_RECORDS:
            self.record.write(t, self.clock.wall(), None, "rx_rejected", reason=reason, **fields)

    def recv(self, timeout):
        """The next frame, or None after `timeout` s; a datagram python-can could not
        unpack (udp_multicast) is rejected here and None returned."""
        try:
            return self.bus.recv(timeout=timeout)
        except can.CanOperationError as e:
            if not buses.is_undecodable_datagram(e):
                raise
            self.reject(
                self.clock.sim(),
                "bad_datagram",
                error=f"{e}: {type(e.__cause__).__name__}: {e.__cause__}",
            )
            return None

    def _check(self, msg, t):
        """(cantools message, signals) of a frame the nodes take; None when it is ours or
        another node's (ignored), or rejected: not a data frame, an id the DBC does not
        have, a length other than the DBC's, a value the DBC does not decode or list."""
        data = bytes(msg.data)
        if msg.is_error_frame or msg.is_remote_frame:
            self.reject(
                t,
                "not_data_frame",
                id=msg.arbitration_id,
                error_frame=msg.is_error_frame,
                remote_frame=msg.is_remote_frame,
            )
            return None
        m = None if msg.is_extended_id else self.proto.by_id(msg.arbitration_id)
        if m is None:
            self.reject(
                t, "unknown_id", id=msg.arbitration_id, extended=msg.is_extended_id, data=data.hex()
            )
            return None
        if self.proto.nodes["executor"].prefix not in m.senders:
            self.stats["ignored"] += 1  # the nodes' own frames: udp loops them back
            return None
        if len(data) != m.length:
            self.reject(
                t,
                "wrong_length",
                name=m.name,
                length=len(data),
                dbc_length=m.length,
                data=data.hex(),
            )
            return None
        try:
            signals = m.decode(data, decode_choices=False)
        except Exception as e:  # cantools raises several types for a payload it cannot read
            self.reject(t, "bad_value", name=m.name, data=data.hex(), error=str(e))
            return None
        unlisted = self.proto.unlisted_choice(m.name, signals)
        if unlisted is not None:
            self.reject(
                t,
                "bad_value",
                name=m.name,
                data=data.hex(),
                signal=unlisted[0],
                value=unlisted[1],
                error="value not among the DBC's choices",
            )
            return None
        return m, signals

    def receive(self, msg, t):
        """Check one frame from the bus and deliver it to the nodes it addresses."""
        checked = self._check(msg, t)
        if checked is None:
            return
        m, signals = checked
        self.stats["rx"] += 1
        if m.name in ("Estop", "ExecutorHeartbeat"):
            targets = NODES
        else:
            targets = [n for n, p in self.prefix.items() if m.name.startswith(p)]
        for node in targets:
            if any(
                rng.random() < f["fraction"]
                for f, _, rng in self._wire_match(self._drops, node, "rx")
            ):
                self.stats["rx_dropped"] += 1
                if m.name != "ExecutorHeartbeat":
                    self.record.write(
                        t, self.clock.wall(), node, "rx_dropped", name=m.name, signals=signals
                    )
                continue
            delay = sum(f["delay_s"] for f, _ in self._wire_match(self._delays, node, "rx"))
            if delay > 0:
                self.stats["rx_delayed"] += 1
                self._order += 1
                heapq.heappush(self._rx_queue, (t + delay, self._order, node, m.name, signals))
                continue
            self.deliver(t, node, m.name, signals)

    def deliver(self, t, node, name, s):
        n = self.nodes[node]
        prefix = self.prefix[node]
        kind = name[len(prefix) :] if name.startswith(prefix) else name
        if name == "ExecutorHeartbeat":
            self._executor_heartbeat(t, node, s)
        elif name == "Estop":
            self.record.write(
                t,
                self.clock.wall(),
                node,
                "estop_frame",
                active=int(s["EstopActive"]),
                counter=int(s["Counter"]),
            )
            if s["EstopActive"]:
                n.estop(t, "Estop frame")
        elif kind == "Command":
            n.on_command(t, int(s["Command"]), int(s["CommandSeq"]))
        elif kind == "Setpoint":
            q = [float(s[f"Joint{j}Position"]) for j in range(1, 5)]
            n.on_setpoint(t, q, int(s["SetpointSeq"]))
        elif kind == "EeCommand":
            n.on_ee(t, int(s["Action"]), int(s["EeSeq"]))
        elif kind == "Move":
            n.on_move(t, float(s["TargetPosition"]), float(s["MaxSpeed"]), int(s["MoveSeq"]))

    def _executor_heartbeat(self, t, node, s):
        if int(s["ProtocolVersion"]) != self.proto.version:
            if "version" not in self._warned:
                self._warned.add("version")
                self.record.write(
                    t,
                    self.clock.wall(),
                    node,
                    "executor_version_mismatch",
                    got=int(s["ProtocolVersion"]),
                    want=self.proto.version,
                )
            return
        if self._last_hb_wall[node] is None:
            self.record.write(
                t, self.clock.wall(), node, "executor_seen", time_scale=float(s["TimeScale"])
            )
        self._last_hb_wall[node] = self.clock.wall()
        self._hb_tripped[node] = False

    def _watchdog(self, t):
        limit = self.exec_timeout_s
        if not limit:
            return None
        wall = self.clock.wall()
        soonest = None
        for node, last in self._last_hb_wall.items():
            if last is None or self._hb_tripped[node]:
                continue
            if wall - last > limit:
                self._hb_tripped[node] = True
                self.record.write(t, wall, node, "comm_timeout", silent_wall_s=wall - last)
                self.nodes[node].comm_timeout(t)
            else:
                due = last + limit
                soonest = due if soonest is None else min(soonest, due)
        return soonest

    # -- the loop --------------------------------------------------------------------------------
    def step(self, t):
        """Everything due at simulated time t; returns the next simulated deadline."""
        for n in self.nodes.values():
            n.update(t)
        self._trip_timed_estops(t)
        while self._rx_queue and self._rx_queue[0][0] <= t:
            _, _, node, name, s = heapq.heappop(self._rx_queue)
            self.nodes[node].update(t)
            self.deliver(t, node, name, s)
        self._send_changes(t)
        for entry in self._periodic:
            if entry[0] <= t:
                if entry[3] == "heartbeat":
                    self._heartbeat(t, entry[2])
                else:
                    self._feedback(t, entry[2])
                # keep the phase, but never send a burst to catch up after a stall
                entry[0] = max(entry[0] + entry[1], t)
        self._send_changes(t)
        while self._tx_queue and self._tx_queue[0][0] <= t:
            self._send(t, heapq.heappop(self._tx_queue)[2])
        if self.camera:
            self.camera.step(t, self.vehicle.positions(t)[0])
        deadlines = [e[0] for e in self._periodic]
        if self.camera:
            deadlines.append(self.camera.next_event())
        deadlines += [x for x in (n.next_event() for n in self.nodes.values()) if x is not None]
        deadlines += [at for at, _ in self._timed_estops[:1]]
        for q in (self._tx_queue, self._rx_queue):
            if q:
                deadlines.append(q[0][0])
        return min(deadlines)

    def run(self):
        opt = self.opt
        self.record.write(
            0.0,
            self.clock.wall(),
            None,
            "start",
            time_scale=opt.time_scale,
            rate_hz=self.rate_hz,
            faults=opt.faults,
            seed=opt.seed,
            config=self.model.path,
            dbc=self.proto.path,
            channel=str(getattr(self.bus, "channel_info", "")),
            home=self.model.home,
            arm_start=opt.arm_start,
            vehicle_start=opt.vehicle_start_m,
            cut_s=self.arms[ARMS[0]].cut_s,
            release_s=self.arms[ARMS[0]].release_s,
        )
        next_progress = opt.progress_s
        reason = "stop requested"
        try:
            while not self.stop_event.is_set():
                t = self.clock.sim()
                wd_due = self._watchdog(t)
                deadline = self.step(t)
                wait = self.clock.to_wall(deadline - self.clock.sim())
                if wd_due is not None:
                    wait = min(wait, wd_due - self.clock.wall())
                wait = min(max(wait, 0.0), MAX_SLEEP_WALL_S)
                msg = self.recv(wait)
                while msg is not None:
                    t = self.clock.sim()
                    for n in self.nodes.values():
                        n.update(t)
                    self.receive(msg, t)
                    msg = self.recv(0.0)
                if opt.progress_s and self.out and self.clock.wall() >= next_progress:
                    next_progress += opt.progress_s
                    self._progress()
        except Exception as e:
            reason = f"error: {type(e).__name__}: {e}"
            raise
        finally:
            self.record.write(
                self.clock.sim(),
                self.clock.wall(),
                None,
                "stop",
                reason=reason,
                stats=self.stats,
                pending_tx=len(self._tx_queue),
                pending_rx=len(self._rx_queue),
                picks={n: a.picks for n, a in self.arms.items()},
                vehicle_position=self.vehicle.positions(self.clock.sim())[0],
                **({"camera": self.camera.stats()} if self.camera else {}),
            )

    def _progress(self):
        t = self.clock.sim()
        states = " ".join(f"{n}={State(self.nodes[n].state).name}" for n in NODES)
        print(
            f"sim t={t:.1f}s vehicle={self.vehicle.positions(t)[0]:.3f}m "
            f"tx={self.stats['tx']} rx={self.stats['rx']} states[{states}]",
            file=self.out,
            flush=True,
        )
