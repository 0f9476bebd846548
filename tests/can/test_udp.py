"""C udp transport <-> python-can udp_multicast, every message type both ways, filters,
timeout, malformed datagrams. Runs in a private network namespace of its own, with
224.0.0.0/4 routed to lo, so no datagram can leave the machine."""

import os
import socket
import sys

import msgpack
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import can_checks as cc  # noqa: E402

from harvest.canbus.netns import NetnsUnavailable, enter_private_netns, in_private_netns  # noqa: E402

SPEC = "udp:239.74.163.2:43113"


@pytest.fixture(scope="module", autouse=True)
def private_netns():
    if not os.path.exists(cc.tool_path()):
        pytest.fail(f"hv-can-tool not built at {cc.tool_path()}")
    try:
        enter_private_netns()
    except NetnsUnavailable as e:
        pytest.skip(f"SKIPPED: no private network namespace: {e}")
    assert in_private_netns(), "namespace has interfaces besides lo"


def test_python_to_c_every_message():
    cc.check_python_to_c(SPEC)


def test_c_to_python_every_message():
    cc.check_c_to_python(SPEC)


def test_filters():
    cc.check_filters(SPEC)


def test_receive_timeout():
    cc.check_timeout(SPEC)


def _valid(**override):
    d = {
        "timestamp": 1.5,
        "arbitration_id": 0x123,
        "is_extended_id": False,
        "is_remote_frame": False,
        "is_error_frame": False,
        "channel": None,
        "dlc": 2,
        "data": b"\x01\x02",
        "is_fd": False,
        "bitrate_switch": False,
        "error_state_indicator": False,
    }
    d.update(override)
    return msgpack.packb({k: v for k, v in d.items() if v is not KeyError}, use_bin_type=True)


GARBAGE = [
    b"",  # empty datagram
    b"\xc1",  # never-used msgpack byte
    b"hello, not msgpack at all",
    _valid()[:-3],  # truncated map
    _valid() + b"\x00",  # trailing byte
    b"\xdf\xff\xff\xff\xff",  # map claiming 2^32 entries in 5 bytes
    b"\xdd\x7f\xff\xff\xff" + b"\x00" * 8,  # array claiming 2^31 items
    msgpack.packb([1, 2, 3]),  # not a map
    _valid(arbitration_id=0x800),  # standard id too wide
    _valid(arbitration_id=-1),  # negative id
    _valid(dlc=9, data=b"\x00" * 9),  # classic frame with 9 bytes
    _valid(dlc=3),  # dlc disagrees with data
    _valid(data="text"),  # data as str instead of bin
    _valid(is_extended_id=1),  # int instead of bool
    _valid(unknown_key=1),  # python-can would reject it too
    _valid(arbitration_id=KeyError),  # arbitration_id missing
    _valid(is_remote_frame=True, is_error_frame=True, data=b"", dlc=0),
    _valid(bitrate_switch=True),  # BRS on a classic frame
    msgpack.packb({"arbitration_id": 1, "arbitration_id ": 2, 3: 4}),  # non-str key
]
FD_FRAME = _valid(is_fd=True, dlc=12, data=bytes(12))  # valid, but CAN FD: unsupported


def test_garbage_datagrams_counted_and_dropped():
    rx = cc.start_tool(["--bus", SPEC, "recv", "--count", "1", "--timeout-ms", "5000"])
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
    for g in GARBAGE + [FD_FRAME]:
        s.sendto(g, ("239.74.163.2", 43113))
    s.sendto(_valid(arbitration_id=0x321, data=b"\xaa", dlc=1), ("239.74.163.2", 43113))
    s.close()
    rc, out, err = cc.finish(rx)
    assert rc == 0, err
    assert out.split() == ["321#AA"], "the valid frame after the garbage must come through"
    st = cc.stats_of(err)
    assert st["malformed"] == len(GARBAGE), st
    assert st["unsupported"] == 1 and st["rx"] == 1, st
