"""Every program against docs/EXIT_CODES.md: its --help ends with the codes the table gives
it; an unknown option and a missing input file each exit 2 with one line
`PROGRAM: what: why` naming them, and leave no output behind; `telemetry mcap` refuses a
file that is not an LCM event log (a BLF trace, random bytes); the systemd units restart
and stop on the codes the table says. The C programs are this build's; a program the build
leaves out (HV_WITH_TOOLS, HV_WITH_GLPK, HV_WITH_LCM) is SKIPPED with the reason."""

import configparser
import os
import random
import re
import subprocess
import sys

import pytest

SRC = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD = os.environ.get("HV_BUILD_DIR", os.path.join(SRC, "build"))
CONFIG = os.path.join(SRC, "config", "harvest.cfg")
TABLE = os.path.join(SRC, "docs", "EXIT_CODES.md")

C_PROGRAMS = {
    "harvest-plan": "planner/harvest-plan",
    "harvest-plan-online": "planner/online/harvest-plan-online",
    "harvest-exec": "executor/harvest-exec",
    "hv-can-tool": "executor/can/hv-can-tool",
    "harvest-fw-plan": "firmware/harvest-fw-plan",
    "costgen": "tools/costgen",
    "mountopt": "tools/mountopt",
}
# installed from the tree as they are (the package's libexec)
SCRIPTS = {"harvest-can-up": "packaging/harvest-can-up"}
# harvest-stack and each of its commands, as their messages name them
PY_PROGRAMS = [
    "harvest-stack",
    "harvest-stack sim",
    "harvest-stack scenario",
    "harvest-stack experiments",
    "harvest-stack telemetry",
    "harvest-stack telemetry log",
    "harvest-stack telemetry gantt",
    "harvest-stack telemetry summary",
    "harvest-stack telemetry mcap",
    "harvest-stack live",
    "harvest-stack firmware",
    "harvest-stack firmware run",
]


def table():
    """{program: its codes} from the table of docs/EXIT_CODES.md; "every program" rows are
    under None."""
    codes = {}
    with open(TABLE, encoding="utf-8") as f:
        for line in f:
            m = re.match(r"\| (\d+) \| .* \| (.+) \|$", line.strip())
            if not m:
                continue
            code, who = int(m.group(1)), m.group(2)
            names = [None] if who == "every program" else re.findall(r"`([^`]+)`", who)
            for name in names:
                codes.setdefault(name, set()).add(code)
    return codes


def codes_of(program):
    t = table()
    return t[None] | t.get(program, set())


def command(program, *args):
    """argv of `program` (a name of C_PROGRAMS, SCRIPTS or PY_PROGRAMS) with `args`."""
    if program in SCRIPTS:
        return [os.path.join(SRC, SCRIPTS[program]), *args]
    if program in C_PROGRAMS:
        exe = os.path.join(BUILD, C_PROGRAMS[program])
        if not os.access(exe, os.X_OK):
            pytest.skip(f"SKIPPED: {program} not built in {BUILD}")
        return [exe, *args]
    return [sys.executable, "-m", "harvest", *program.split()[1:], *args]


def run(argv, **kw):
    return subprocess.run(argv, capture_output=True, text=True, timeout=120, **kw)


def one_line(p):
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    return lines[0]


def test_the_table_names_every_program_and_the_common_codes():
    t = table()
    assert t[None] == {0, 1, 2}
    assert set(t) - {None} <= set(C_PROGRAMS) | set(SCRIPTS) | set(PY_PROGRAMS), set(t)
    assert 3 in t["harvest-exec"] and 6 in t["harvest-exec"]  # the latched and clean stops


@pytest.mark.parametrize("program", list(C_PROGRAMS) + list(SCRIPTS) + PY_PROGRAMS)
def test_help_ends_with_the_codes_of_the_table(program):
    p = run(command(program, "--help"))
    assert p.returncode == 0, p.stderr
    last = " ".join(p.stdout.rstrip().split("\n\n")[-1].split())
    assert last.startswith("Exit codes: docs/EXIT_CODES.md (0 done, 1 runtime failure, 2 usage"), (
        last
    )
    listed = {int(c) for c in re.findall(r"(?:\(|, )(\d+) ", last)}
    assert listed == codes_of(program), last


# (program, args before --bogus, the program as the message names it): enough arguments
# that only the unknown option is wrong
BAD_OPTION = [(name, (), name) for name in list(C_PROGRAMS) + list(SCRIPTS)] + [
    ("harvest-stack", (), "harvest-stack"),
    ("harvest-stack sim", (), "harvest-stack sim"),
    ("harvest-stack scenario", ("--out", "m.csv"), "harvest-stack scenario"),
    ("harvest-stack experiments", ("--out", "x"), "harvest-stack experiments"),
    # argparse hands what a command leaves over to the parser above it
    ("harvest-stack telemetry summary", ("t.lcmlog",), "harvest-stack telemetry"),
    ("harvest-stack telemetry mcap", ("t.lcmlog", "--out", "t.mcap"), "harvest-stack telemetry"),
    ("harvest-stack live", ("--port", "0"), "harvest-stack live"),
    (
        "harvest-stack firmware run",
        ("--image", "e", "--plan", "p", "--plan-image", "i", "--out", "o"),
        "harvest-stack firmware",
    ),
]


@pytest.mark.parametrize("program,args,named", BAD_OPTION, ids=[b[0] for b in BAD_OPTION])
def test_an_unknown_option_is_usage(tmp_path, program, args, named):
    p = run(command(program, *args, "--bogus"), cwd=tmp_path)
    assert p.returncode == 2, p.stderr
    assert one_line(p) == f"{named}: --bogus: unknown option (see --help)"
    assert not os.listdir(tmp_path), os.listdir(tmp_path)


def _missing_input_cases():
    """(program, args, outputs that must not appear), {m} in args the missing file and {t}
    the test's folder."""
    fruits = ("--fruits", "{m}", "--method", "fov", "--out", "{t}/p.json")
    fw = ("--image", "{m}", "--plan", "{m}", "--plan-image", "{m}", "--out", "{t}/fw")
    return [
        ("harvest-plan", ("--config", CONFIG, *fruits), ("p.json",)),
        ("harvest-plan", ("check", "{m}"), ()),
        ("harvest-plan-online", ("--config", "{m}", "--lcm-url", "memq://"), ()),
        ("harvest-exec", ("--plan", "{m}", "--config", CONFIG, "--journal", "{t}/j"), ("j",)),
        ("harvest-exec", ("--plan", "{m}", "--config", CONFIG, "--check-plan"), ()),
        ("harvest-fw-plan", ("--plan", "{m}", "--config", CONFIG, "--out", "{t}/i"), ("i",)),
        ("costgen", ("--config", "{m}", "--out-dir", "{t}", "--quiet"), ()),
        ("mountopt", ("--config", "{m}", "--json", "{t}/s.json", "--quiet"), ("s.json",)),
        ("harvest-stack sim", ("--config", "{m}", "--record", "{t}/r.jsonl"), ("r.jsonl",)),
        ("harvest-stack scenario", ("--config", "{m}", "--out", "{t}/m.csv"), ("m.csv",)),
        ("harvest-stack experiments", ("report", "--config", "{m}", "--out", "{t}/x"), ("x",)),
        ("harvest-stack telemetry summary", ("{m}",), ()),
        ("harvest-stack telemetry gantt", ("{m}", "--out", "{t}/g.png"), ("g.png",)),
        ("harvest-stack telemetry mcap", ("{m}", "--out", "{t}/o.mcap"), ("o.mcap",)),
        ("harvest-stack live", ("--config", "{m}", "--ready-file", "{t}/r"), ("r",)),
        ("harvest-stack firmware run", fw, ("fw",)),
    ]


@pytest.mark.parametrize(
    "program,args,outputs",
    _missing_input_cases(),
    ids=[f"{c[0]}-{i}" for i, c in enumerate(_missing_input_cases())],
)
def test_a_missing_input_file_is_named(tmp_path, program, args, outputs):
    missing = str(tmp_path / "in" / "missing.file")
    argv = [a.format(m=missing, t=tmp_path) for a in args]
    p = run(command(program, *argv))
    assert p.returncode == 2, (p.returncode, p.stderr)
    line = one_line(p)
    assert line.startswith(f"{program}: {missing}: "), line
    assert re.search(r"[Nn]o such file", line), line
    for out in outputs:
        assert not (tmp_path / out).exists(), out


def test_hv_can_tool_refuses_a_frame_that_is_none():
    """hv-can-tool reads no file: its input is frames on stdin, a bad one exits 2."""
    p = run(command("hv-can-tool", "unpack"), input="7F0#0\n")
    assert p.returncode == 2 and p.stdout == "", p.stderr
    assert p.stderr.startswith("hv-can-tool: frame '7F0#0': "), p.stderr


def _blf(path):
    import can

    with can.BLFWriter(str(path)) as w:
        for i in range(20):
            w.on_message_received(
                can.Message(timestamp=1.0 + i, arbitration_id=0x100 + i, data=bytes([i] * 8))
            )


@pytest.mark.parametrize("kind", ["blf", "random", "empty"])
def test_mcap_refuses_what_is_no_lcm_log(tmp_path, kind):
    src = tmp_path / f"run.{kind}"
    if kind == "blf":
        _blf(src)
        assert src.read_bytes()[:4] == b"LOGG"
    else:
        src.write_bytes(random.Random(3).randbytes(4096 if kind == "random" else 0))
    out = tmp_path / "out" / "run.mcap"
    out.parent.mkdir()
    p = run(command("harvest-stack telemetry mcap", str(src), "--out", str(out)))
    assert p.returncode == 2, p.stderr
    assert one_line(p).startswith(f"harvest-stack telemetry mcap: {src}: not an LCM event log: ")
    assert not os.listdir(out.parent)  # nothing written, no temporary file left
    out.write_bytes(b"an earlier export")
    assert run(command("harvest-stack telemetry mcap", str(src), "--out", str(out))).returncode
    assert out.read_bytes() == b"an earlier export"  # an earlier file is left as it was


def _unit(name):
    """The unit's (RestartPreventExitStatus, SuccessExitStatus) as sets of codes."""
    u = configparser.ConfigParser(strict=False, interpolation=None)
    u.read(os.path.join(SRC, "packaging", "systemd", name + ".service.in"))
    service = u["Service"]
    return tuple(
        {int(c) for c in service.get(k, "").split()}
        for k in ("RestartPreventExitStatus", "SuccessExitStatus")
    )


@pytest.mark.parametrize("program", ["harvest-exec", "harvest-plan-online"])
def test_the_units_restart_on_the_codes_of_the_table(program):
    prevent, success = _unit(program)
    # a runtime failure is restarted, bad input is not; every code is the program's
    assert 2 in prevent and 1 not in prevent | success, (prevent, success)
    assert prevent | success <= codes_of(program), (prevent, success)
    # the page's Services table says the same
    with open(TABLE, encoding="utf-8") as f:
        row = next(ln for ln in f if ln.startswith(f"| `{program}.service` |"))
    cells = [{int(c) for c in re.findall(r"\d+", x)} for x in row.strip("| \n").split(" | ")[1:]]
    assert cells == [prevent, success], row
