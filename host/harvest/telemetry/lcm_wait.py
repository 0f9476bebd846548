"""Waiting on LCM in a command that runs until SIGINT or SIGTERM (cmdline.stop_on_signals):
the signal cuts the wait short, and LCM reports that as an error (OSError, "returned -1")."""


def handle(lc, timeout_ms, stopped):
    """lc.handle_timeout(timeout_ms); False when a signal that asked to stop (stopped() is
    true) cut the wait short, True otherwise. Any other failure raises as LCM's."""
    try:
        lc.handle_timeout(timeout_ms)
    except OSError:
        if stopped():
            return False
        raise
    return True
