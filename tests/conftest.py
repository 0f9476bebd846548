"""Shared pytest settings for every Python suite under tests/.

A file whose tests were all skipped must not look like a pass to ctest: the session then
exits with 77, which ctest's SKIP_RETURN_CODE reports as "Skipped" with pytest's reason
printed by -rs above it.
"""

_SKIP_EXIT = 77


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    stats = reporter.stats
    ran = len(stats.get("passed", [])) + len(stats.get("failed", [])) + len(stats.get("error", []))
    if ran == 0 and stats.get("skipped"):
        session.exitstatus = _SKIP_EXIT
