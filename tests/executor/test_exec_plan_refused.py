"""harvest-exec refuses a bad plan file before it touches the journal or the bus: stops out
of driving order and fruit ids outside the id set (docs/PLAN_FORMAT.md), each with one line
naming the file and the field. No bus is opened, so no network namespace is needed."""

import json
import os
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exec_hil as H  # noqa: E402

_missing = [m for m in H.missing_pieces() if "simulator" not in m]
pytestmark = pytest.mark.skipif(bool(_missing), reason="SKIPPED: " + "; ".join(_missing))


def _exec(plan, journal):
    return subprocess.run(
        [
            H.EXEC,
            "--plan",
            str(plan),
            "--config",
            H.CONFIG,
            "--journal",
            str(journal),
            "--transport",
            "udp",
            "--channel",
            H.GROUP,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )


def _edited(tmp_path, edit):
    plan = H.make_plan(tmp_path / "good.json", stops=3, per_arm=2, seed=2)
    edit(plan)
    path = tmp_path / "plan.json"
    path.write_text(json.dumps(plan))
    return path


def _swap_first_two(plan):
    plan["stops"][0], plan["stops"][1] = plan["stops"][1], plan["stops"][0]


def _repeat_last(plan):
    plan["stops"].append(json.loads(json.dumps(plan["stops"][-1])))


def _newline_in_id(plan):
    plan["stops"][1]["left"][0]["id"] += "\nF L 0 picked ok a=1 t=0"


def _space_in_id(plan):
    plan["stops"][2]["right"][1]["id"] = "fruit 9"


CASES = {
    "stops_swapped": (_swap_first_two, "stops[1].y_m: "),
    "stop_listed_twice": (_repeat_last, "stops[3].y_m: "),
    "newline_in_id": (_newline_in_id, "stops[1].left[0].id: character 0x0a"),
    "space_in_id": (_space_in_id, "stops[2].right[1].id: character 0x20 at position 6"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_bad_plan_refused_before_the_journal(tmp_path, name):
    edit, needle = CASES[name]
    plan = _edited(tmp_path, edit)
    journal = tmp_path / "j.journal"
    p = _exec(plan, journal)
    assert p.returncode == 2, (p.returncode, p.stderr)
    assert f"harvest-exec: {plan}: {needle}" in p.stderr, p.stderr
    assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert not journal.exists()


def test_the_unedited_plan_passes_the_reader(tmp_path):
    """The same plan unedited gets past the reader, and fails later on the journal path: a
    journal that cannot be created is a runtime failure (docs/EXIT_CODES.md), not bad input."""
    plan = _edited(tmp_path, lambda p: None)
    p = _exec(plan, tmp_path / "no" / "such" / "dir" / "j.journal")
    assert p.returncode == 1 and "j.journal" in p.stderr and str(plan) not in p.stderr, p.stderr
