"""The firmware's cross build, shared by the tests of tests/firmware: where it lives and
how to make it. The build is a separate CMake tree (HV_FIRMWARE=ON with
cmake/arm-none-eabi.cmake) inside the host build: <HV_BUILD_DIR>/firmware-cross."""

import os
import shutil
import subprocess

import pytest

SOURCE_DIR = os.environ.get(
    "HV_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
)
BUILD_DIR = os.environ.get("HV_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
FW_BUILD = os.path.join(BUILD_DIR, "firmware-cross")
IMAGE = os.path.join(FW_BUILD, "firmware", "harvest-fw.elf")
TOOLCHAIN = os.path.join(SOURCE_DIR, "cmake", "arm-none-eabi.cmake")


def require_cross_compiler():
    for tool in ("arm-none-eabi-gcc", "arm-none-eabi-nm", "arm-none-eabi-size"):
        if shutil.which(tool) is None:
            pytest.skip(
                f"SKIPPED: {tool} not installed (scripts/setup.sh installs "
                "gcc-arm-none-eabi and libnewlib-arm-none-eabi)"
            )


def require_image():
    """The image the cross build test made (ctest runs that test first: FIXTURES)."""
    require_cross_compiler()
    if not os.path.isfile(IMAGE):
        pytest.fail(f"{IMAGE} missing: the firmware_cross_build test builds it")
    return IMAGE


def build():
    """Configure and build the firmware tree; returns the completed process of the build."""
    import sys

    cfg = subprocess.run(
        [
            "cmake",
            "-S",
            SOURCE_DIR,
            "-B",
            FW_BUILD,
            "-G",
            "Ninja",
            f"-DCMAKE_TOOLCHAIN_FILE={TOOLCHAIN}",
            "-DHV_FIRMWARE=ON",
            f"-DHV_PYTHON={sys.executable}",
        ],
        capture_output=True,
        text=True,
    )
    assert cfg.returncode == 0, cfg.stdout + cfg.stderr
    return subprocess.run(["cmake", "--build", FW_BUILD, "-j2"], capture_output=True, text=True)


def symbols(path, defined_only=False):
    """Symbol names of an ELF image or archive (arm-none-eabi-nm)."""
    args = ["arm-none-eabi-nm", "--defined-only" if defined_only else "-u", path]
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    return {line.split()[-1] for line in out.splitlines() if line.strip() and ":" not in line}


def size(path):
    """(text, data, bss) of the image, bytes (arm-none-eabi-size, Berkeley format)."""
    out = subprocess.run(
        ["arm-none-eabi-size", path], capture_output=True, text=True, check=True
    ).stdout.splitlines()
    text, data, bss = (int(v) for v in out[1].split()[:3])
    return text, data, bss
