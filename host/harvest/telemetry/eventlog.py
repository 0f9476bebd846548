"""A strict reader of LCM event logs (the file `telemetry log` and lcm-logger write).

LCM's own reader skips what does not look like an event until it finds the next sync word,
so a file of another kind (a BLF trace, random bytes) reads as a log of no events. This one
refuses it, naming the file and the byte where the log format breaks. Format, big-endian:
per event the sync word 0xEDA1DA01, int64 event number, int64 timestamp (us), int32 channel
length, int32 data length, the channel name, the data.
"""

import os
import struct

SYNC = 0xEDA1DA01
_HEADER = struct.Struct(">Iqqii")
_CHANNEL_MAX = 63  # LCM_MAX_CHANNEL_NAME_LENGTH


class LogError(ValueError):
    """The file is not an LCM event log, or breaks the format at a named byte."""


class Event:
    __slots__ = ("eventnum", "timestamp", "channel", "data")

    def __init__(self, eventnum, timestamp, channel, data):
        self.eventnum, self.timestamp, self.channel, self.data = eventnum, timestamp, channel, data


class EventLog:
    """Iterate the events of `path` (an OSError names the file when it cannot be read).
    An event cut short at the very end (a logger stopped mid-write) ends the iteration and
    leaves `torn_at`, its byte offset, for the caller to report; anything else off the
    format raises LogError."""

    def __init__(self, path):
        self.path = path
        self.torn_at = None
        self._f = open(path, "rb")
        self._size = os.fstat(self._f.fileno()).st_size
        # refused at once, before a caller creates its output
        start = self._f.read(4)
        self._f.seek(0)
        if self._size == 0:
            self.close()
            self._refuse(0, "the file is empty")
        if len(start) == 4 and int.from_bytes(start, "big") != SYNC:
            self.close()
            self._refuse(0, f"it starts with 0x{start.hex()}, an event with 0x{SYNC:08x}")

    def close(self):
        self._f.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _refuse(self, offset, why):
        if offset == 0:
            raise LogError(f"{self.path}: not an LCM event log: {why}")
        raise LogError(f"{self.path}: byte {offset}: {why}")

    def __iter__(self):
        offset = 0
        while offset < self._size:
            head = self._f.read(_HEADER.size)
            sync = int.from_bytes(head[:4], "big") if len(head) >= 4 else None
            if sync is not None and sync != SYNC:
                self._refuse(offset, f"0x{sync:08x} where an event starts with 0x{SYNC:08x}")
            if len(head) < _HEADER.size:
                self._torn(offset)
                return
            _, num, timestamp, clen, dlen = _HEADER.unpack(head)
            if not 0 < clen <= _CHANNEL_MAX or dlen < 0:
                self._refuse(offset, f"channel length {clen}, data length {dlen}: not an event")
            end = offset + _HEADER.size + clen + dlen
            if end > self._size:
                self._torn(offset)
                return
            channel = self._f.read(clen)
            try:
                name = channel.decode("ascii")
            except UnicodeDecodeError:
                self._refuse(offset, f"channel name {channel!r} is not ASCII")
            yield Event(num, timestamp, name, self._f.read(dlen))
            offset = end

    def _torn(self, offset):
        if offset == 0:
            self._refuse(0, f"{self._size} bytes, shorter than one event")
        self.torn_at = offset
