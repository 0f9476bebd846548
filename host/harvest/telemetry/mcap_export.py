"""Export an executor telemetry log (LCM event log) to MCAP, the container robotics viewers
open: one channel per LCM channel, JSON messages, and per channel the JSON Schema of its
LCM type (lcm_schema), so every field is typed and documented in the viewer. The log time
of each message is the LCM log's receive time.
"""

import os
import tempfile

from . import eventlog, lcm_schema, lcm_types


def export(log_path, out_path, python_dir=None, lcm_defs=None):
    """Write `out_path`; return ({channel: messages written}, the log's torn_at). Channels
    the telemetry does not define are refused (ValueError naming the channel), not dropped;
    an empty file, or one that is no LCM event log, too (eventlog.LogError), before the
    output is created. The MCAP file appears whole or not at all: written beside, renamed at
    the end."""
    with eventlog.EventLog(log_path) as log:
        types = lcm_types.load(python_dir)
        structs = lcm_schema.load(lcm_defs)
        try:
            fd, tmp = tempfile.mkstemp(
                prefix=os.path.basename(out_path) + ".", dir=os.path.dirname(out_path) or "."
            )
        except OSError as e:  # named by its temporary name: name the file asked for
            raise OSError(e.errno, e.strerror, out_path) from None
        try:
            with os.fdopen(fd, "wb") as f:
                counts = _write(log, f, types, structs)
            os.chmod(tmp, 0o644)
            os.replace(tmp, out_path)
        except BaseException:
            os.unlink(tmp)
            raise
        return counts, log.torn_at


def _write(log, f, types, structs):
    from mcap.writer import Writer

    counts = {}
    writer = Writer(f)
    writer.start(profile="", library="harvest telemetry mcap")
    schema_ids, channel_ids = {}, {}
    for ev in log:
        type_name = lcm_types.CHANNELS.get(ev.channel)
        if type_name is None:
            raise ValueError(
                f"{log.path}: channel {ev.channel!r} is not a telemetry channel "
                f"({', '.join(sorted(lcm_types.CHANNELS))})"
            )
        if type_name not in schema_ids:
            name, schema = lcm_schema.schema_of(structs, type_name)
            schema_ids[type_name] = writer.register_schema(
                name=name, encoding="jsonschema", data=schema
            )
        if ev.channel not in channel_ids:
            channel_ids[ev.channel] = writer.register_channel(
                topic=ev.channel, message_encoding="json", schema_id=schema_ids[type_name]
            )
        msg = types[type_name].decode(ev.data)
        t_ns = int(ev.timestamp) * 1000
        writer.add_message(
            channel_ids[ev.channel],
            log_time=t_ns,
            publish_time=t_ns,
            data=lcm_schema.message_json(msg),
            sequence=counts.get(ev.channel, 0),
        )
        counts[ev.channel] = counts.get(ev.channel, 0) + 1
    writer.finish()
    return counts
