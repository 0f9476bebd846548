"""scripts/check_one_source.py: the repository restates no constant that has a source of
its own (the DBC), and the check catches a copy planted in a small tree of its own."""

import os
import subprocess
import sys

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
SCRIPT = os.path.join(SRC, "scripts", "check_one_source.py")


def run(*args):
    return subprocess.run(
        [sys.executable, SCRIPT, *args], capture_output=True, text=True, timeout=120
    )


def test_the_repository_restates_no_constant():
    p = run("--root", SRC)
    assert p.returncode == 0, p.stdout + p.stderr


def write(root, path, text):
    full = os.path.join(root, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "w") as f:
        f.write(text)


def test_a_planted_copy_fails_and_is_counted(tmp_path):
    write(tmp_path, "host/harvest/x.py", "PROTOCOL_VERSION = 1  # the heartbeat's\n")
    write(tmp_path, "executor/src/y.c", "int f(int b) { return b & 0x07; }\n")
    write(tmp_path, "executor/src/z.c", "int g(int fault_bits) { return fault_bits & 0x07; }\n")
    p = run("--root", str(tmp_path))
    assert p.returncode == 1
    assert "host/harvest/x.py:1: restates the CAN protocol version" in p.stderr
    assert "executor/src/z.c:1: restates the FaultBits" in p.stderr
    assert "y.c" not in p.stderr  # a mask of no FaultBits is none of its business
    count = run("--root", str(tmp_path), "--count")
    assert "hand-written copies (constant, file): 2" in count.stdout
