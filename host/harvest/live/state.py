"""What the live view knows of the running robot, from decoded telemetry messages
(harvest.telemetry.lcm_types): the plan (its stops and fruits, from plan_t offline or
plan_commit_t online, and the camera's fruits not planned yet), each fruit's outcome, the
vehicle's position, both arms' joints and node states, the executor's state, and the faults
seen. `apply()` says which parts a message changed, so the server redraws only those, and
what is worth a line in the viewer's log."""

SIDES = ("left", "right")
LOG_INFO, LOG_WARNING, LOG_ERROR = "info", "warning", "error"


class Fruit:
    """One fruit: where it hangs (row frame, m; None until a plan or the camera gives it),
    and how far it got: seen, planned, picked, failed or skipped."""

    __slots__ = ("fruit_id", "side", "pos", "status")

    def __init__(self, fruit_id, side, pos=None, status="planned"):
        self.fruit_id, self.side, self.pos, self.status = fruit_id, side, pos, status


class Change:
    """What one message changed: `parts` of {"plan", "robot", "faults"}, and `logs`,
    (level, source, text) lines for the viewer's log."""

    def __init__(self):
        self.parts = set()
        self.logs = []


class LiveState:
    def __init__(self, fault_names=None, state_names=None):
        # fault_names(bits) -> [names], state_names(state) -> name: the DBC's ArmFault bit
        # table and State value table (harvest.canbus.enums); numbers when not given
        self.fault_names = fault_names or (lambda bits: [f"0x{bits:x}"])
        self.state_names = state_names or str
        self.fruits = {}  # (side, fruit_id) -> Fruit
        self.stops = []  # y of each stop (m), in driving order
        self.course = None  # (start, end) along the row (m), online: from plan_commit_t
        self.exec_state = None  # the last exec_state_t
        self.arms = [None, None]  # the last arm_joint_state_t of the left and right arm
        self.working_on = [None, None]  # the fruit id each arm is picking
        self.faults = []  # dicts: t_s, utime, source, name, detail

    @property
    def vehicle_y(self):
        return self.exec_state.vehicle_position_m if self.exec_state else 0.0

    def _fruit(self, side, fruit_id):
        return self.fruits.setdefault((side, fruit_id), Fruit(fruit_id, side))

    def _plan_fruit(self, side, fruit_id, pos):
        f = self._fruit(side, fruit_id)
        f.pos = pos
        if f.status == "seen":
            f.status = "planned"

    def _fault(self, change, utime, t_s, source, name, detail, level=LOG_WARNING):
        self.faults.append(
            {"t_s": t_s, "utime": utime, "source": source, "name": name, "detail": detail}
        )
        change.parts.add("faults")
        change.logs.append((level, source, f"fault {name}: {detail}" if detail else name))

    def apply(self, channel, msg):
        """Take one decoded message of `channel`; returns its Change."""
        change = Change()
        handler = getattr(self, "_on_" + channel.lower(), None)
        if handler is not None:
            handler(msg, change)
        return change

    def _on_harvest_plan(self, m, change):
        self.stops = [s.y_m for s in m.stops]
        for k in m.picks:
            self._plan_fruit(k.side, k.fruit_id, (k.x_m, k.y_m, k.z_m))
        change.parts.add("plan")
        what = f"plan {m.plan_path}: {m.n_stops} stops, {m.n_picks} picks"
        change.logs.append((LOG_INFO, "executor", what))

    def _on_harvest_plan_commit(self, m, change):
        # sent whole each time: the committed stops replace those known
        self.stops = list(m.stop_y_m)
        start = m.row_start_m - m.stop_margin_m
        self.course = (start, m.row_start_m + m.row_length_m + m.stop_margin_m)
        for d in m.picks:
            self._plan_fruit(d.side, d.fruit_id, (d.x_m, d.y_m, d.z_m))
        change.parts.add("plan")

    def _on_harvest_camera(self, m, change):
        for d in m.fruits:
            f = self._fruit(d.side, d.fruit_id)
            if f.pos is None:
                f.pos, f.status = (d.x_m, d.y_m, d.z_m), "seen"
                change.parts.add("plan")

    def _on_harvest_fruit(self, m, change):
        if m.side not in (0, 1):
            change.logs.append((LOG_WARNING, "live", f"fruit event of side {m.side}: left out"))
            return
        f = self._fruit(m.side, m.fruit_id)
        side = SIDES[m.side]
        if m.event == "approach":
            self.working_on[m.side] = m.fruit_id
            change.parts.add("robot")
        elif m.event == "outcome":
            f.status = m.outcome
            self.working_on[m.side] = None
            change.parts.update(("plan", "robot"))
            if m.outcome != "picked":
                level = LOG_WARNING if m.outcome == "failed" else LOG_INFO
                change.logs.append((level, f"{side} arm", f"{m.fruit_id} {m.outcome}: {m.reason}"))
        elif m.event == "fault":
            detail = f"fruit {m.fruit_id}, attempt {m.attempt}"
            self._fault(change, m.utime, m.t_s, f"{side} arm", m.reason, detail)

    def _on_harvest_exec_state(self, m, change):
        before = self.exec_state
        self.exec_state = m
        change.parts.add("robot")
        if before is not None and before.stop != m.stop:
            change.parts.add("plan")  # the stop the vehicle is at is drawn with the plan
        if before is None or before.phase != m.phase:
            change.logs.append((LOG_INFO, "executor", f"phase {m.phase} (stop {m.stop})"))
            if m.phase == "safe":
                self._fault(
                    change, m.utime, m.t_s, "executor", m.safe_reason, "safe state", LOG_ERROR
                )

    def _on_arm(self, side, m, change):
        before = self.arms[side]
        self.arms[side] = m
        change.parts.add("robot")
        had = before.fault_bits if before is not None else 0
        if m.fault_bits and m.fault_bits != had:
            names = "+".join(self.fault_names(m.fault_bits))
            state = self.state_names(m.state)
            t_s = self.exec_state.t_s if self.exec_state else 0.0
            self._fault(change, m.utime, t_s, f"{SIDES[side]} arm", names, f"node state {state}")

    def _on_harvest_arm_left(self, m, change):
        self._on_arm(0, m, change)

    def _on_harvest_arm_right(self, m, change):
        self._on_arm(1, m, change)
