"""The firmware's journal across a power cut: harvest-fw.elf in QEMU on the simulator's
bus, QEMU killed (SIGKILL) in the middle of a short row just after a cut, started again
on the same journal file (semihosting, the board's flash), the plan uploaded again, and
the row finished. Judged by the simulator's record: every planned fruit cut once and
released into the container by the arm that cut it, none lost, none cut twice. And a
journal of another plan refused by its name; a plan refused for its parameters writes
nothing to the journal."""

import collections
import os
import time

import fw_hil
import fw_qemu
import pytest
from fw_hil import H, uart_phases, upload

# Time scale 1, as test_fw_row.py: the serial line carries every frame of the bus.
SCALE = 1.0


@pytest.fixture
def rig_factory(tmp_path):
    yield from fw_hil.rigs(tmp_path, SCALE)


def journal_lines(rig):
    """The firmware's 'journal' lines (one per plan started), as dicts."""
    return [
        fw_qemu.status_fields(ln)
        for ln in fw_qemu.uart_lines(rig.qemu.uart_log)
        if ln.startswith("harvest-fw: journal")
    ]


def count(plan, sim):
    """From the simulator's record: fruits cut, each known by forward kinematics of the
    recorded joints as the planned fruit there (a cut at no planned fruit fails), and
    those released into the container by the arm holding them."""
    events = sim.events()
    ids = iter(
        H.fk_check.Judge.for_plan(plan).cut_fruits(
            plan, [e for e in events if e["event"] == "pick"]
        )
    )
    cuts, released, held = collections.Counter(), set(), {}
    for e in events:
        if e["event"] == "pick":
            key = next(ids)
            cuts[key] += 1
            held[e["node"]] = key
        elif e["event"] == "release" and e.get("fruit") and e["node"] in held:
            released.add(held.pop(e["node"]))
    return cuts, released


def test_sigkill_mid_row_resumes_from_the_journal(tmp_path, rig_factory):
    plan = H.make_plan(tmp_path / "plan.json", stops=2, per_arm=2, seed=5)
    planned = sum(len(s["left"]) + len(s["right"]) for s in plan["stops"])
    image = fw_hil.plan_image(tmp_path, tmp_path / "plan.json", SCALE)
    rig = rig_factory()
    assert upload(image)[0] == "RUNNING"
    # the power cut: just after the simulator's second cut, the fruit still in the gripper
    second_cut = fw_hil.wait_until(lambda: len(H.sim_picks(rig.sim)) >= 2, 240, period=0.05)
    assert second_cut, fw_hil.diagnosis(rig)
    rig.kill_firmware()
    cuts_before, _ = count(plan, rig.sim)
    journal_bytes = os.path.getsize(rig.qemu.journal)
    assert 2 <= sum(cuts_before.values()) < planned
    # the nodes notice the executor's silence (FAULT, comm bit), as after any crash
    time.sleep(H.HEARTBEAT_TIMEOUT_S + 1.0)
    rig.start_firmware()
    assert upload(image)[0] == "RUNNING"
    assert fw_hil.wait_until(lambda: H.row_end_reached(plan, rig.sim), 300), fw_hil.diagnosis(rig)
    assert fw_hil.wait_until(lambda: "row_done" in uart_phases(rig), 10)
    # the second boot replayed the journal the first one left: every record it held
    first, second = journal_lines(rig)[-2:]
    assert first["records"] == "1" and first["outcomes"] == "0"
    assert int(second["records"]) > 1, second  # more than the header: the row resumed
    assert int(second["records"]) == journal_bytes // 16, (second, journal_bytes)
    # judged by the simulator's record
    cuts, released = count(plan, rig.sim)
    twice = sum(1 for n in cuts.values() if n > 1)
    lost = planned - len(released)
    print(
        f"resume: planned {planned}, cut before the kill {sum(cuts_before.values())}, "
        f"journal {journal_bytes} B at the kill, replayed {second}, picked {len(released)}, "
        f"lost {lost}, twice {twice}"
    )
    assert (len(released), lost, twice) == (planned, 0, 0), cuts
    H.assert_every_fruit_cut_once(plan, rig.sim)
    assert "safe" not in uart_phases(rig)


def test_a_journal_of_another_plan_is_refused_by_name(tmp_path, rig_factory):
    from harvest.canbus import plan_upload

    H.make_plan(tmp_path / "a.json", stops=2, per_arm=1, seed=6)
    H.make_plan(tmp_path / "b.json", stops=2, per_arm=1, seed=7)
    image_a = fw_hil.plan_image(tmp_path, tmp_path / "a.json", SCALE)
    image_b = fw_hil.plan_image(tmp_path, tmp_path / "b.json", SCALE)
    assert image_a != image_b
    rig = rig_factory(sim=False)
    assert upload(image_a)[0] == "RUNNING"
    rig.kill_firmware()
    with open(rig.qemu.journal, "rb") as f:
        journal = f.read()
    rig.start_firmware()
    with pytest.raises(plan_upload.UploadError, match="refused"):
        upload(image_b, timeout=20.0)
    errors = [ln for ln in fw_qemu.uart_lines(rig.qemu.uart_log) if "error" in ln]
    assert any(ln.endswith("HV_ERR_FW_JOURNAL_PLAN") for ln in errors), errors
    with open(rig.qemu.journal, "rb") as f:
        assert f.read() == journal, "the refused plan changed the journal"
    # the journal is the first plan's still: after a reset, that plan runs from it
    rig.kill_firmware()
    rig.start_firmware()
    assert upload(image_a)[0] == "RUNNING"
    assert fw_hil.wait_until(lambda: len(journal_lines(rig)) == 2, 10), journal_lines(rig)


def test_a_plan_refused_for_its_parameters_leaves_the_journal_fresh(tmp_path, rig_factory):
    """A plan the state machine refuses (here a heartbeat timeout of 0) writes nothing, so
    the corrected plan that follows runs on the same journal instead of being taken for
    another plan's."""
    from harvest.canbus import plan_upload

    H.make_plan(tmp_path / "plan.json", stops=2, per_arm=1, seed=8)
    bad = fw_hil.plan_image(tmp_path, tmp_path / "plan.json", SCALE, heartbeat_timeout=0)
    good = fw_hil.plan_image(tmp_path, tmp_path / "plan.json", SCALE)
    rig = rig_factory(sim=False)
    with pytest.raises(plan_upload.UploadError, match="refused"):
        upload(bad, timeout=20.0)
    errors = [ln for ln in fw_qemu.uart_lines(rig.qemu.uart_log) if "error" in ln]
    assert any(ln.endswith("HV_ERR_EXEC_PARAMS") for ln in errors), errors
    assert os.path.getsize(rig.qemu.journal) == 0
    # after a reset (the firmware keeps announcing the refusal until then), the good plan
    rig.kill_firmware()
    rig.start_firmware()
    assert upload(good)[0] == "RUNNING"
    assert fw_hil.wait_until(lambda: len(journal_lines(rig)) == 1, 10), journal_lines(rig)
    assert journal_lines(rig)[0]["records"] == "1"
