"""`cmake --install` into a temporary prefix, then an out-of-tree consumer built against it
twice: with CMake's find_package(harvest) and with pkg-config. The installed tree is then
moved, and the pkg-config build repeated, so the .pc files must not keep the prefix.
The programs carry LCM (linked statically) and the tree names no LCM path; a consumer of
the telemetry sink brings LCM of the build's version itself (docs/INSTALL.md), here the
prefix the build used.
"""

import os
import shutil
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from install_tree import BUILD_DIR, PROGRAMS, SOURCE_DIR  # noqa: E402
from install_tree import cache as _cache  # noqa: E402
from install_tree import run as _run  # noqa: E402

CONSUMER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "consumer")


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    for tool in ("cmake", "pkg-config", "cc"):
        if shutil.which(tool) is None:
            pytest.skip(f"SKIPPED: {tool} not on PATH")
    if _cache("HV_WITH_EXECUTOR") != "ON" or _cache("HV_WITH_GLPK") != "ON":
        pytest.skip("SKIPPED: the build leaves out the executor or the planner")
    root = tmp_path_factory.mktemp("install")
    _run(["cmake", "--install", BUILD_DIR, "--prefix", str(root / "opt")])
    return root / "opt"


def _lcm_root():
    # the prefix of the build's LCM (cmake/HvLcm.cmake), as a consumer would name it
    inc = _cache("LCM_INCLUDE_DIR")
    return os.path.dirname(inc) if _cache("HV_WITH_LCM") == "ON" and inc else ""


def _sanitize_flags():
    # a sanitized build installs sanitized libraries: their consumer needs the runtimes
    return ["-fsanitize=address,undefined"] if _cache("HV_SANITIZE") == "ON" else []


def _check_output(out, telemetry=0):
    import cantools

    estop = cantools.database.load_file(
        os.path.join(SOURCE_DIR, "executor", "can", "harvest.dbc")
    ).get_message_by_name("Estop")
    fields = out.split()
    assert fields[0] == "stop_margin_m" and float(fields[1]) > 0.0
    assert fields[3] in ("cycle", "one_way")
    assert int(fields[5]) == estop.length and fields[7] == "HV_OK"
    assert fields[8] == "telemetry" and int(fields[9]) == telemetry


def test_install_tree_holds_what_a_vehicle_needs(prefix):
    for prog in PROGRAMS:
        assert os.access(prefix / "bin" / prog, os.X_OK), prog
    share = prefix / "share" / "harvest"
    assert (share / "harvest.dbc").is_file() and (share / "harvest.cfg").is_file()
    assert sorted(p.name for p in (share / "lcm").iterdir()) == sorted(
        p for p in os.listdir(os.path.join(SOURCE_DIR, "lcm_types")) if p.endswith(".lcm")
    )
    cmake_dir = next(prefix.glob("lib*/cmake/harvest"))
    targets = "".join(p.read_text() for p in cmake_dir.glob("harvestTargets*.cmake"))
    assert "harvest::hv_exec_can" in targets and "harvest::hv_planner" in targets
    # dependencies are imported targets, resolved on the consumer's machine
    assert "libglpk" not in targets and "liblcm" not in targets and SOURCE_DIR not in targets
    installed = "".join(p.read_text() for p in cmake_dir.glob("*.cmake"))
    installed += "".join(p.read_text() for p in prefix.glob("lib*/pkgconfig/*.pc"))
    assert not _lcm_root() or _lcm_root() not in installed
    # the programs carry LCM: no liblcm to find at run time, none installed
    for prog in ("harvest-exec", "harvest-plan-online"):
        needed = _run(["readelf", "-d", str(prefix / "bin" / prog)])
        assert "liblcm" not in needed and "RPATH" not in needed and "RUNPATH" not in needed
    assert not list(prefix.rglob("liblcm*")) and not (prefix / "include" / "lcm").exists()


def test_every_program_prints_the_one_version(prefix):
    with open(os.path.join(SOURCE_DIR, "VERSION"), encoding="ascii") as f:
        version = f.readline().strip()
    for prog in PROGRAMS:
        out = _run([str(prefix / "bin" / prog), "--version"])
        assert out == f"{prog} {version}\n", (prog, out)
        assert "--version" in _run([str(prefix / "bin" / prog), "--help"]), prog
    header = (prefix / "include" / "hv" / "version.h").read_text()
    assert f'#define HV_VERSION "{version}"' in header


def test_installed_tools_find_the_installed_config(prefix, tmp_path):
    """costgen and mountopt, run from an empty folder with no --config, read
    PREFIX/share/harvest/harvest.cfg (found from the program's own path)."""
    cfg = str(prefix / "share" / "harvest" / "harvest.cfg")
    for tool in ("costgen", "mountopt"):
        assert f"(default: {cfg})" in _run([str(prefix / "bin" / tool), "--help"]), tool
    import subprocess

    res = subprocess.run(
        [str(prefix / "bin" / "costgen"), "--side", "left", "--out-dir", str(tmp_path), "--quiet"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert res.returncode == 0, res.stderr
    assert f"config {cfg}," in res.stdout + res.stderr
    assert (tmp_path / "costtab_left.bin").stat().st_size > 0


def _cmake_consumer(prefix, build, *extra):
    flags = " ".join(_sanitize_flags())
    _run(
        [
            "cmake",
            "-S",
            CONSUMER,
            "-B",
            str(build),
            f"-DCMAKE_PREFIX_PATH={prefix}",
            f"-DCMAKE_C_FLAGS={flags}",
            f"-DCMAKE_EXE_LINKER_FLAGS={flags}",
            *extra,
        ]
    )
    _run(["cmake", "--build", str(build)])
    return _run([str(build / "consumer"), str(prefix / "share" / "harvest" / "harvest.cfg")])


def test_cmake_consumer(prefix, tmp_path):
    _check_output(_cmake_consumer(prefix, tmp_path / "b"))


def test_cmake_consumer_of_telemetry(prefix, tmp_path):
    if not _lcm_root():
        pytest.skip("SKIPPED: the build has no LCM telemetry (HV_WITH_LCM=OFF)")
    out = _cmake_consumer(
        prefix, tmp_path / "b", "-DCONSUMER_TELEMETRY=ON", f"-DLCM_ROOT={_lcm_root()}"
    )
    _check_output(out, telemetry=1)


def _lcm_flags():
    # what docs/INSTALL.md tells a pkg-config consumer of the telemetry sink to add
    root = _lcm_root()
    glib = _run(["pkg-config", "--cflags", "--libs", "glib-2.0"]).split()
    return ["-DCONSUMER_TELEMETRY", f"-I{root}/include", f"{root}/lib/liblcm.a", *glib, "-pthread"]


def _pkgconfig_build(prefix, out, telemetry=False):
    env = dict(os.environ, PKG_CONFIG_PATH=str(next(prefix.glob("lib*/pkgconfig"))))
    pc = _run(
        ["pkg-config", "--cflags", "--libs", "harvest-planner", "harvest-executor"], env=env
    ).split()
    src = os.path.join(CONSUMER, "consumer.c")
    _run(["cc", *_sanitize_flags(), "-o", str(out), src, *pc, *(_lcm_flags() if telemetry else [])])
    _check_output(
        _run([str(out), str(prefix / "share" / "harvest" / "harvest.cfg")]), int(telemetry)
    )


def test_pkgconfig_consumer_after_moving_the_tree(prefix, tmp_path):
    _pkgconfig_build(prefix, tmp_path / "consumer_pc")
    moved = tmp_path / "moved"
    shutil.copytree(prefix, moved, symlinks=True)
    for pc in moved.glob("lib*/pkgconfig/*.pc"):
        assert str(prefix) not in pc.read_text(), pc.name
    _pkgconfig_build(moved, tmp_path / "consumer_moved")
    if _lcm_root():
        _pkgconfig_build(moved, tmp_path / "consumer_moved_telemetry", telemetry=True)
