"""The bus suite (test_sim_bus.py) once more, over python-can's udp_multicast, inside a
private network namespace of its own: the multicast group is routed to `lo` there and the
namespace has no other interface, so no frame can leave the machine.
"""

import os
import re
import sys

import pytest

from harvest.canbus import netns

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.environ.get("HV_SOURCE_DIR", os.path.dirname(os.path.dirname(HERE)))
SUITE = os.path.join(HERE, "test_sim_bus.py")


def _in_namespace(cmd, env, timeout):
    """Run cmd in a fresh namespace (the CAN helper's), or SKIP when none can be made."""
    try:
        probe = netns.run_in_netns(["true"], capture_output=True, text=True)
    except netns.NetnsUnavailable as e:
        pytest.skip(f"SKIPPED: no private network namespace: {e}")
    if probe.returncode != 0:
        pytest.skip(f"SKIPPED: cannot create a network namespace: {probe.stderr.strip()}")
    return netns.run_in_netns(cmd, env=env, capture_output=True, text=True, timeout=timeout)


def test_bus_suite_over_udp_multicast_in_a_private_namespace():
    env = dict(
        os.environ, HV_SIM_BUS="udp_multicast", HV_SOURCE_DIR=SRC, PYTHONDONTWRITEBYTECODE="1"
    )
    cmd = [sys.executable, "-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider", SUITE]
    r = _in_namespace(cmd, env, timeout=800)
    out = r.stdout + r.stderr
    print(out)
    assert r.returncode == 0, f"suite failed over udp_multicast:\n{out[-6000:]}"
    summary = r.stdout.strip().splitlines()[-1]
    # every test of the suite ran and passed: none skipped, failed or deselected
    m = re.search(r"(\d+) passed", summary)
    assert m and int(m.group(1)) > 0, summary
    assert not re.search(r"skipped|failed|deselected|error", summary), summary
