"""pytest's side of harvest.firmware.rig: skips with the reason when QEMU or a private
network namespace is missing, QEMU on the image the cross build test made."""

import shutil

import fw_build
import pytest

from harvest.firmware import rig
from harvest.firmware.rig import last_status, status_fields, uart_lines  # noqa: F401


def require_qemu():
    if shutil.which("qemu-system-arm") is None:
        pytest.skip("SKIPPED: qemu-system-arm not installed (scripts/setup.sh installs it)")


def enter_netns():
    from harvest.canbus import netns

    try:
        netns.enter_private_netns()
    except netns.NetnsUnavailable as e:
        pytest.skip(f"SKIPPED: no private network namespace: {e}")


def Qemu(workdir, **kwargs):
    return rig.Qemu(fw_build.require_image(), workdir, **kwargs)
