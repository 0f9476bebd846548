"""The live view's server: the executor's LCM telemetry in, Foxglove's WebSocket protocol out
(foxglove-sdk's server).

Channels (all made at start, so a client sees every one advertised at once):
- each telemetry channel under its LCM name (HARVEST_EXEC_STATE, HARVEST_PLAN, ...), the
  decoded message as JSON with its JSON Schema from the .lcm definitions, as the MCAP
  export writes them (telemetry mcap): the layout's panels read both alike;
- SCENE_PLAN and SCENE_ROBOT (foxglove.SceneUpdate), TF (foxglove.FrameTransforms): the 3D
  scene of scene.py, redrawn when a message changes what it shows;
- FAULTS: every fault seen so far, as one JSON list; LOG (foxglove.Log): faults, phase
  changes and failed picks as they happen.
The last message of each channel but LOG is sent again when a client subscribes, so a
viewer that connects mid-row still gets the plan, which the executor sends once.
"""

import json
import queue
import struct
import sys
import time

import foxglove
from foxglove.channels import FrameTransformsChannel, LogChannel, SceneUpdateChannel
from foxglove.messages import Timestamp
from foxglove.websocket import ServerListener

from ..telemetry import lcm_schema, lcm_types, lcm_wait
from . import scene
from .state import LiveState

SCENE_PLAN = "/harvest/scene/plan"
SCENE_ROBOT = "/harvest/scene/robot"
TF = "/tf"
FAULTS = "/harvest/faults"
LOG = "/harvest/log"
FAULTS_SCHEMA = {
    "type": "object",
    "title": "harvest.faults",
    "description": "every fault the live view has seen, oldest first",
    "properties": {
        "faults": {
            "type": "array",
            "items": {
                "type": "object",
                "properties": {
                    "t_s": {"type": "number", "description": "plan time (s)"},
                    "utime": {"type": "integer", "description": "wall clock (us)"},
                    "source": {"type": "string", "description": "left arm, right arm, executor"},
                    "name": {"type": "string", "description": "the fault or safe reason"},
                    "detail": {"type": "string"},
                },
            },
        }
    },
}


class _Listener(ServerListener):
    """Its callbacks run on the server's thread, so a subscribe is only queued here and
    answered by the LCM loop; the other callbacks are ServerListener's, which do nothing."""

    def __init__(self):
        self.subscribed = queue.SimpleQueue()

    def on_subscribe(self, client, channel):
        self.subscribed.put(channel.topic)


class LiveServer:
    def __init__(self, geometry, types, structs, fault_names, state_names, host, port):
        self.geo = geometry
        self.types = types
        self.state = LiveState(fault_names, state_names)
        self.channels = {}
        for channel, type_name in lcm_types.CHANNELS.items():
            name, schema = lcm_schema.schema_of(structs, type_name)
            self.channels[channel] = foxglove.Channel(
                channel,
                schema=foxglove.Schema(name=name, encoding="jsonschema", data=schema),
                message_encoding="json",
            )
        self.channels[SCENE_PLAN] = SceneUpdateChannel(SCENE_PLAN)
        self.channels[SCENE_ROBOT] = SceneUpdateChannel(SCENE_ROBOT)
        self.channels[TF] = FrameTransformsChannel(TF)
        self.channels[FAULTS] = foxglove.Channel(FAULTS, schema=FAULTS_SCHEMA)
        self.channels[LOG] = LogChannel(LOG)
        self.latest = {}  # topic -> (message, log time ns): sent again on a subscribe
        self.counts = {}  # LCM channel -> messages taken
        self.undecodable = {}  # LCM channel -> messages that did not decode
        self.others = {}  # channel -> messages of channels the telemetry does not define
        self.listener = _Listener()
        self.server = foxglove.start_server(
            name="harvest-stack live", host=host, port=port, server_listener=self.listener
        )

    @property
    def port(self):
        return self.server.port

    def stop(self):
        self.server.stop()

    def _send(self, topic, msg, t_ns, latch=True):
        self.channels[topic].log(msg, log_time=t_ns)
        if latch:
            self.latest[topic] = (msg, t_ns)

    def on_lcm(self, channel, data):
        """One LCM message: forwarded as JSON, then what it changed redrawn."""
        t_ns = time.time_ns()
        try:
            msg = lcm_types.decode(channel, data, self.types)
        except (ValueError, IndexError, struct.error) as e:
            n = self.undecodable.get(channel, 0)
            self.undecodable[channel] = n + 1
            if n == 0:  # once per channel: a publisher of another version floods otherwise
                why = f"a message did not decode ({e}); later ones are counted"
                print(f"harvest-stack live: {channel}: {why}", file=sys.stderr)
            return
        if msg is None:  # not a telemetry channel: counted, reported at the end
            self.others[channel] = self.others.get(channel, 0) + 1
            return
        self.counts[channel] = self.counts.get(channel, 0) + 1
        self._send(channel, lcm_schema.message_json(msg), t_ns)
        change = self.state.apply(channel, msg)
        ts = Timestamp(t_ns // 1_000_000_000, t_ns % 1_000_000_000)
        if "plan" in change.parts:
            self._send(SCENE_PLAN, scene.plan_update(self.state, self.geo, ts), t_ns)
        if "robot" in change.parts:
            self._send(TF, scene.transforms(self.state, ts), t_ns)
            self._send(SCENE_ROBOT, scene.robot_update(self.state, self.geo, ts), t_ns)
        if "faults" in change.parts:
            self._send(FAULTS, json.dumps({"faults": self.state.faults}).encode(), t_ns)
        for level, source, text in change.logs:
            self._send(LOG, scene.log_message(level, source, text, ts), t_ns, latch=False)

    def answer_subscribes(self):
        """Send the last message of each channel a client subscribed to since the last call."""
        while True:
            try:
                topic = self.listener.subscribed.get_nowait()
            except queue.Empty:
                return
            if topic in self.latest:
                msg, t_ns = self.latest[topic]
                self.channels[topic].log(msg, log_time=t_ns)

    def listen(self, lc):
        """Subscribe to every channel of LCM `lc`."""
        self.subscription = lc.subscribe(".*", self.on_lcm)

    def run(self, lc, stop_flag):
        """Serve until stop_flag() is true: LCM handled in 100 ms slices."""
        try:
            while not stop_flag() and lcm_wait.handle(lc, 100, stop_flag):
                self.answer_subscribes()
        finally:
            lc.unsubscribe(self.subscription)
