"""Formatting and lint belong to the test command: every tracked C/C++ file is as
clang-format (.clang-format) writes it, and every Python file passes ruff's checks and is
as ruff's formatter writes it (ruff.toml). A failure prints the files and the command that
fixes them."""

import os
import shutil
import subprocess
import sys

import pytest

SOURCE = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
RUFF = os.path.join(os.path.dirname(sys.executable), "ruff")  # beside the venv's python


def tracked(*patterns):
    out = subprocess.run(
        ["git", "-C", SOURCE, "ls-files", *patterns], capture_output=True, text=True, check=True
    ).stdout.split()
    return [os.path.join(SOURCE, f) for f in out]


def test_c_sources_are_clang_formatted():
    if shutil.which("clang-format") is None:
        pytest.skip("SKIPPED: clang-format not installed (scripts/setup.sh installs it)")
    files = tracked("*.c", "*.h", "*.cpp", "*.hpp")
    assert files
    bad = []
    for i in range(0, len(files), 50):
        r = subprocess.run(
            ["clang-format", "--dry-run", "--Werror", *files[i : i + 50]],
            capture_output=True,
            text=True,
            cwd=SOURCE,
        )
        bad += sorted({line.split(":")[0] for line in r.stderr.splitlines() if ": error:" in line})
    assert not bad, "not clang-formatted (fix: clang-format -i FILE):\n" + "\n".join(bad)


def test_python_passes_ruff():
    if not os.access(RUFF, os.X_OK):
        pytest.skip(f"SKIPPED: ruff not installed at {RUFF} (scripts/setup.sh installs it)")
    files = tracked("*.py")
    assert files
    check = subprocess.run(
        [RUFF, "check", "--no-cache", *files], capture_output=True, text=True, cwd=SOURCE
    )
    assert check.returncode == 0, check.stdout + check.stderr
    fmt = subprocess.run(
        [RUFF, "format", "--no-cache", "--check", *files],
        capture_output=True,
        text=True,
        cwd=SOURCE,
    )
    assert fmt.returncode == 0, "fix: ruff format FILE\n" + fmt.stdout + fmt.stderr
