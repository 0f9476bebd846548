"""scripts/check_cycles.py: the repository passes it, and it catches what it is for (a
cycle between modules, a file over the limit) on a small tree of its own."""

import os
import subprocess
import sys

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
SCRIPT = os.path.join(SRC, "scripts", "check_cycles.py")


def run(*args):
    return subprocess.run(
        [sys.executable, SCRIPT, *args], capture_output=True, text=True, timeout=120
    )


def test_repository_has_no_new_cycle_or_long_file():
    p = run("--root", SRC)
    assert p.returncode == 0, p.stdout + p.stderr
    assert " 0 problems" in p.stdout


def write(root, path, text):
    full = os.path.join(root, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "w") as f:
        f.write(text)


def test_a_call_back_up_is_a_cycle(tmp_path):
    # top.c implements top.h and calls down into sub.h; sub.c calls top_solve back
    write(tmp_path, "m/include/hv/top.h", "int top_solve(int x);\n")
    write(tmp_path, "m/include/hv/sub.h", "int sub_solve(int x);\n")
    write(
        tmp_path,
        "m/src/top.c",
        '#include "hv/top.h"\n#include "hv/sub.h"\n'
        "int top_solve(int x)\n{\n    return sub_solve(x);\n}\n",
    )
    write(
        tmp_path,
        "m/src/sub.c",
        '#include "hv/sub.h"\n#include "hv/top.h"\n'
        "int sub_solve(int x)\n{\n    return x > 0 ? top_solve(x - 1) : 0;\n}\n",
    )
    p = run("--root", str(tmp_path), "m")
    assert p.returncode == 1
    assert "cycle between 2 modules" in p.stdout
    assert "m/src/sub.c" in p.stdout and "m/src/top.c" in p.stdout
    # the same call through a callback the caller hands down: no cycle
    write(tmp_path, "m/include/hv/sub.h", "int sub_solve(int x, int (*back)(int));\n")
    write(
        tmp_path,
        "m/src/top.c",
        '#include "hv/top.h"\n#include "hv/sub.h"\n'
        "int top_solve(int x)\n{\n    return sub_solve(x, top_solve);\n}\n",
    )
    write(
        tmp_path,
        "m/src/sub.c",
        '#include "hv/sub.h"\n'
        "int sub_solve(int x, int (*back)(int))\n{\n    return x > 0 ? back(x - 1) : 0;\n}\n",
    )
    p = run("--root", str(tmp_path), "m")
    assert p.returncode == 0, p.stdout


def test_a_long_file_fails(tmp_path):
    write(tmp_path, "m/src/long.c", "int x;\n" * 30)
    assert run("--root", str(tmp_path), "--limit", "30", "m").returncode == 0
    p = run("--root", str(tmp_path), "--limit", "29", "m")
    assert p.returncode == 1
    assert "m/src/long.c: 30 lines, over the limit of 29" in p.stdout
