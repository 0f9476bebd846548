"""Shared pytest settings for every Python suite under tests/.

A file whose tests were all skipped must not look like a pass to ctest: the session then
exits with 77, which ctest's SKIP_RETURN_CODE reports as "Skipped" with pytest's reason
printed by -rs above it.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.environ.get("HV_SOURCE_DIR", os.path.dirname(HERE))
BUILD_DIR = os.environ.get("HV_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
HOST_DIR = os.path.join(SOURCE_DIR, "host")
if HOST_DIR not in sys.path:
    sys.path.insert(0, HOST_DIR)

_SKIP_EXIT = 77


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    stats = reporter.stats
    ran = len(stats.get("passed", [])) + len(stats.get("failed", [])) + len(stats.get("error", []))
    if ran == 0 and stats.get("skipped"):
        session.exitstatus = _SKIP_EXIT
