"""Files generated from the project's sources of truth (the DBC, the config key table, the
file-format tables): written whole or not at all, and compared with what is in the tree
(`--check`), so a generated document the repository carries cannot go stale unnoticed."""

import os


def write(path, text):
    """Replace `path` with `text` atomically (a reader never sees half a file)."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def stale(path, text):
    """None when `path` holds exactly `text`, else why not (for --check)."""
    try:
        with open(path, encoding="utf-8") as f:
            if f.read() == text:
                return None
    except OSError as e:
        return f"{path}: cannot read: {e.strerror}"
    return f"{path}: not what its source gives; regenerate it"


def emit(path, text, check):
    """Write `path`, or with `check` only compare it; returns the exit status (0 current/
    written, 1 stale) and prints why on failure."""
    if not check:
        write(path, text)
        return 0
    why = stale(path, text)
    if why:
        import sys

        print(why, file=sys.stderr)
        return 1
    return 0
