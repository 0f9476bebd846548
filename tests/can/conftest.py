"""The vcan checks run one way per machine: directly where this machine has a usable vcan
(a developer's laptop, the vehicle, inside the test-bed guest), else once through the guest.
The way a machine does not take is deselected, not skipped, so a file that ran every check
the one way reports no skip (tests/conftest.py turns any skip into ctest's Skipped)."""

from harvest.canbus.guest import local_vcan


def pytest_configure(config):
    config.addinivalue_line("markers", "vcan_direct: needs a usable vcan on this machine")
    config.addinivalue_line("markers", "vcan_via_guest: runs the vcan checks in the guest")


def pytest_collection_modifyitems(config, items):
    here = local_vcan() is not None
    drop = "vcan_via_guest" if here else "vcan_direct"
    kept = [i for i in items if i.get_closest_marker(drop) is None]
    gone = [i for i in items if i.get_closest_marker(drop) is not None]
    if gone:
        config.hook.pytest_deselected(items=gone)
        items[:] = kept
