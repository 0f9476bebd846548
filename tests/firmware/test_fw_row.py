"""harvest-fw.elf in QEMU on the simulator's bus (python-can slcan over socket:// and
can.bridge to udp_multicast, in a private network namespace): the plan uploaded over the
bus, a short row picked in full (judged by the simulator's record), an e-stop on the bus
bringing the firmware to its safe state, and bad uploads refused with their named error."""

import time
import zlib

import can
import fw_hil
import fw_qemu
import pytest
from fw_hil import H, uart_phases, upload

# Time scale 1: the serial line carries every frame of the bus, and the simulator sends
# its status and joint frames at rates that grow with the time scale.
SCALE = 1.0


@pytest.fixture
def rig_factory(tmp_path):
    yield from fw_hil.rigs(tmp_path, SCALE)


def test_short_row_picks_every_planned_fruit(tmp_path, rig_factory):
    plan = H.make_plan(tmp_path / "plan.json", stops=2, per_arm=1, seed=2)
    image = fw_hil.plan_image(tmp_path, tmp_path / "plan.json", SCALE)
    rig = rig_factory()
    state = upload(image)
    assert state[0] == "RUNNING" and state[1] == len(image)
    assert fw_hil.wait_until(lambda: H.row_end_reached(plan, rig.sim), 240), (
        f"the vehicle never reached the row end; {fw_hil.diagnosis(rig)}"
    )
    assert fw_hil.wait_until(lambda: "row_done" in uart_phases(rig), 10)
    # the simulator's own record: every planned fruit cut once, none twice
    H.assert_every_fruit_cut_once(plan, rig.sim)
    assert "safe" not in uart_phases(rig)


def test_estop_on_the_bus_brings_the_firmware_to_safe(tmp_path, rig_factory):
    plan = H.make_plan(tmp_path / "plan.json", stops=2, per_arm=1, seed=3)
    image = fw_hil.plan_image(tmp_path, tmp_path / "plan.json", SCALE)
    rig = rig_factory()
    upload(image)
    assert fw_hil.wait_until(lambda: "driving" in uart_phases(rig), 60), uart_phases(rig)
    proto = H_proto()
    estop = proto.message("Estop")
    hb = proto.message("ExecutorHeartbeat")
    from harvest.canbus.buses import open_bus

    with open_bus("udp") as bus:
        # an e-stop button's node: one Estop frame; every node latches and reports it
        bus.send(
            can.Message(
                arbitration_id=estop.frame_id,
                is_extended_id=False,
                data=estop.encode({"EstopActive": 1, "Counter": 200}),
            )
        )
        health, end = None, time.monotonic() + 15
        while time.monotonic() < end and health != 3:
            m = bus.recv(1.0)
            if m is not None and m.arbitration_id == hb.frame_id:
                health = hb.decode(m.data, decode_choices=False)["Health"]
    assert health == 3, "the firmware's heartbeat never said ESTOP"
    assert fw_hil.wait_until(lambda: "safe" in uart_phases(rig), 10), uart_phases(rig)
    # the reason on its status line: a node reported the e-stop
    assert fw_qemu.last_status(rig.qemu.uart_log)["safe_reason"] == "estop"
    # its own Estop frames, repeated (the one the test sent had counter 200)
    assert fw_hil.wait_until(
        lambda: len([e for e in rig.sim.events("estop_frame") if e["counter"] != 200]) >= 3, 10
    )
    assert not H.row_end_reached(plan, rig.sim)


def H_proto():
    from harvest.canbus import load

    return load()


@pytest.mark.parametrize("damage", ["crc", "truncated", "order"])
def test_bad_upload_is_refused_by_name(tmp_path, rig_factory, damage):
    H.make_plan(tmp_path / "plan.json", stops=2, per_arm=1, seed=4)
    image = fw_hil.plan_image(tmp_path, tmp_path / "plan.json", SCALE)
    rig = rig_factory(sim=False)
    from harvest.canbus import plan_upload
    from harvest.canbus.buses import open_bus

    proto = H_proto()
    frames = list(plan_upload.frames(image))
    if damage == "crc":
        begin = ("ExecutorPlanBegin", {"TotalBytes": len(image), "Crc32": zlib.crc32(image) ^ 1})
        frames = [begin] + frames[1:]
        want = "HV_ERR_FW_UPLOAD_CRC"
    elif damage == "truncated":
        frames = frames[: len(frames) // 2] + frames  # a new begin halfway: the first dropped
        want = "HV_ERR_FW_UPLOAD_TRUNCATED"
    else:
        frames = frames[:5] + frames[6:]  # a lost data frame
        want = "HV_ERR_FW_UPLOAD_ORDER"
    with open_bus("udp") as bus:
        plan_upload.wait_status(bus, ("IDLE",), 20)  # the firmware is on the bus
        for name, signals in frames:
            m = proto.message(name)
            bus.send(
                can.Message(arbitration_id=m.frame_id, data=m.encode(signals), is_extended_id=False)
            )
            time.sleep(0.0005)
        if damage == "truncated":
            # the second, whole upload runs: the first one's error was named on the way
            assert plan_upload.wait_status(bus, ("RUNNING",), 20)[0] == "RUNNING"
        else:
            with pytest.raises(plan_upload.UploadError, match="refused"):
                plan_upload.wait_status(bus, ("RUNNING",), 20)
    errors = [ln for ln in fw_qemu.uart_lines(rig.qemu.uart_log) if "error" in ln]
    assert any(ln.endswith(want) for ln in errors), errors
    if damage != "truncated":
        # the first status line the firmware wrote after naming the error: still no plan
        def phases_after_the_error():
            lines = fw_qemu.uart_lines(rig.qemu.uart_log)
            at = max(i for i, ln in enumerate(lines) if ln.endswith(want))
            return [
                fw_qemu.status_fields(ln)["phase"]
                for ln in lines[at + 1 :]
                if ln.startswith("harvest-fw: status")
            ]

        assert fw_hil.wait_until(phases_after_the_error, 30, period=0.1), "no status line came"
        assert phases_after_the_error()[0] == "NO_PLAN", phases_after_the_error()
