"""The firmware's cross build (Cortex-M4F, -Werror -Wdouble-promotion) and what its image
must not contain: no heap anywhere in harvest-fw.elf, no stdio in the state machine."""

import os

import fw_build

HEAP = {
    "malloc",
    "free",
    "calloc",
    "realloc",
    "_malloc_r",
    "_free_r",
    "_calloc_r",
    "_realloc_r",
    "_sbrk",
    "_sbrk_r",
}
STDIO = {
    "printf",
    "fprintf",
    "sprintf",
    "snprintf",
    "vsnprintf",
    "puts",
    "fputs",
    "putchar",
    "fopen",
    "fwrite",
    "fread",
    "fflush",
    "perror",
    "_printf_r",
    "_vfprintf_r",
    "_svfprintf_r",
    "iprintf",
    "siprintf",
    "sniprintf",
}


def test_cross_build_makes_the_image():
    fw_build.require_cross_compiler()
    done = fw_build.build()
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-4000:]
    assert os.path.isfile(fw_build.IMAGE)
    text, data, bss = fw_build.size(fw_build.IMAGE)
    print(f"harvest-fw.elf: text {text} data {data} bss {bss} bytes")
    # the linker script's budget (64 KiB code, 32 KiB RAM with the stack) held at link time
    assert text + data <= 64 * 1024 and data + bss <= 32 * 1024


def test_image_has_no_heap():
    image = fw_build.require_image()
    present = fw_build.symbols(image, defined_only=True) & HEAP
    assert not present, f"heap functions linked into {image}: {sorted(present)}"


def test_state_machine_uses_no_stdio():
    fw_build.require_image()
    lib = os.path.join(fw_build.FW_BUILD, "executor", "libhv_exec.a")
    wanted = fw_build.symbols(lib) & STDIO
    assert not wanted, f"the state machine (hv_exec) calls stdio: {sorted(wanted)}"
