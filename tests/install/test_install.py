"""`cmake --install` into a temporary prefix, then an out-of-tree consumer built against it
twice: with CMake's find_package(harvest) and with pkg-config. The installed tree is then
moved, and the pkg-config build repeated, so the .pc files must not keep the prefix.
The programs carry LCM (linked statically) and the tree names no LCM path; a consumer of
the telemetry sink brings LCM of the build's version itself (docs/INSTALL.md), here the
prefix the build used. A consumer of the CMake package's component core alone is built
where jansson, msgpack-c and GLPK cannot be found, and the installed FindMsgpackC.cmake is
run among stand-ins of msgpack's packages under their names before and since 6.0.
"""

import json
import os
import shutil
import subprocess
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


def _version():
    with open(os.path.join(SOURCE_DIR, "VERSION"), encoding="ascii") as f:
        return f.readline().strip()


def test_install_tree_holds_what_a_vehicle_needs(prefix):
    for prog in PROGRAMS:
        assert os.access(prefix / "bin" / prog, os.X_OK), prog
    share = prefix / "share" / "harvest"
    assert (share / "harvest.dbc").is_file() and (share / "harvest.cfg").is_file()
    assert sorted(p.name for p in (share / "lcm").iterdir()) == sorted(
        p for p in os.listdir(os.path.join(SOURCE_DIR, "lcm_types")) if p.endswith(".lcm")
    )
    cmake_dir = next(prefix.glob("lib*/cmake/harvest"))
    targets = "".join(p.read_text() for p in cmake_dir.glob("harvest-*-targets*.cmake"))
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
    version = _version()
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
    res = subprocess.run(
        [str(prefix / "bin" / "costgen"), "--side", "left", "--out-dir", str(tmp_path), "--quiet"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert res.returncode == 0, res.stderr
    assert f"config {cfg}," in res.stdout + res.stderr
    assert (tmp_path / "costtab_left.bin").stat().st_size > 0


def _configure_consumer(prefix, build, *extra):
    flags = " ".join(_sanitize_flags())
    return [
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


def _cmake_consumer(prefix, build, *extra, env=None):
    _run(_configure_consumer(prefix, build, *extra), env=env)
    _run(["cmake", "--build", str(build)])
    return _run([str(build / "consumer"), str(prefix / "share" / "harvest" / "harvest.cfg")])


def test_cmake_consumer(prefix, tmp_path):
    _check_output(_cmake_consumer(prefix, tmp_path / "b"))


def test_cmake_consumer_of_telemetry(prefix, tmp_path):
    if not _lcm_root():
        pytest.skip("SKIPPED: the build has no LCM telemetry (HV_WITH_LCM=OFF)")
    out = _cmake_consumer(
        prefix,
        tmp_path / "b",
        "-DCONSUMER_COMPONENTS=planner;telemetry",
        f"-DLCM_ROOT={_lcm_root()}",
    )
    _check_output(out, telemetry=1)


def _hidden_dependencies(prefix, tmp_path):
    """cmake arguments and an environment under which CMake looks for packages, headers and
    libraries only inside the installed tree, and pkg-config only in an empty folder: this
    machine's jansson, msgpack-c and GLPK are installed, but cannot be found."""
    empty = tmp_path / "no-pkgconfig"
    empty.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PKG_CONFIG_PATH"}
    env["PKG_CONFIG_LIBDIR"] = str(empty)
    modes = [
        f"-DCMAKE_FIND_ROOT_PATH_MODE_{kind}=ONLY" for kind in ("PACKAGE", "LIBRARY", "INCLUDE")
    ]
    return [f"-DCMAKE_FIND_ROOT_PATH={prefix}", *modes, "--no-warn-unused-cli"], env


def _lookups(trace):
    """(command, first argument) of every package, library, header and pkg-config lookup
    in a configure's JSON trace (--trace-format=json-v1 --trace-expand)."""
    kinds = ("find_package", "find_library", "find_path", "pkg_check_modules", "pkg_search_module")
    calls = [json.loads(line) for line in trace.read_text().splitlines()]
    return [(c["cmd"].lower(), c["args"][0]) for c in calls if c.get("cmd", "").lower() in kinds]


def test_core_consumer_needs_no_jansson_msgpack_glpk(prefix, tmp_path):
    """find_package(harvest COMPONENTS core) looks for no dependency: with jansson, msgpack-c
    and GLPK hidden, a consumer of core configures (looking up nothing but harvest), builds
    and runs; hidden the same way, each component that needs one of them is refused, the
    message naming it, so the hiding does hide them."""
    hide, env = _hidden_dependencies(prefix, tmp_path)
    for component, dependency in (
        ("plan", "jansson"),
        ("planner", "GLPK"),
        ("executor", "msgpack-c"),
    ):
        cmd = _configure_consumer(
            prefix, tmp_path / component, f"-DCONSUMER_COMPONENTS={component}"
        )
        res = subprocess.run([*cmd, *hide], capture_output=True, text=True, env=env)
        assert res.returncode != 0, res.stdout
        assert f"{component}: {dependency} not found" in " ".join(res.stderr.split()), res.stderr
    trace = tmp_path / "core.trace.json"
    out = _cmake_consumer(
        prefix,
        tmp_path / "core",
        "-DCONSUMER_COMPONENTS=core",
        *hide,
        "--trace-expand",
        "--trace-format=json-v1",
        f"--trace-redirect={trace}",
        env=env,
    )
    assert _lookups(trace) == [("find_package", "harvest")]
    fields = out.split()
    assert fields[0] == "stop_margin_m" and float(fields[1]) > 0.0
    assert fields[3] == "HV_OK" and fields[5] == _version()


def test_unknown_component_is_refused_by_name(prefix, tmp_path):
    cmd = _configure_consumer(prefix, tmp_path / "b", "-DCONSUMER_COMPONENTS=core;solver")
    res = subprocess.run(cmd, capture_output=True, text=True)
    assert res.returncode != 0
    assert "solver: no such component" in res.stderr, res.stderr


# Stand-ins for msgpack's CMake packages, each defining the target the real one does:
# msgpack-c from 6.0 (package msgpack-c), before it (package msgpack, in lib/cmake/msgpack),
# and msgpack-cxx before 6.0, whose package is also msgpack (in lib/cmake/msgpackc-cxx)
# with no C target; and msgpack-c 6's pkg-config file.
_MSGPACK = {
    "c6": (
        "lib/cmake/msgpack-c/msgpack-c-config.cmake",
        "add_library(msgpack-c INTERFACE IMPORTED)",
    ),
    "c4": ("lib/cmake/msgpack/msgpack-config.cmake", "add_library(msgpackc INTERFACE IMPORTED)"),
    "cxx4": (
        "lib/cmake/msgpackc-cxx/msgpack-config.cmake",
        "add_library(msgpackc-cxx INTERFACE IMPORTED)",
    ),
    "pc6": (
        "lib/pkgconfig/msgpack-c.pc",
        "Name: msgpack-c\nDescription: stand-in\nVersion: 6.0.0\nLibs: -lmsgpackc\nCflags:",
    ),
}


@pytest.mark.parametrize(
    "present, found",
    [
        (("c6",), "msgpack-c"),
        (("c4",), "msgpack"),
        (("c4", "c6"), "msgpack-c"),
        (("cxx4", "c4"), "msgpack"),
        (("cxx4", "pc6"), "pkg-config msgpack-c"),
        (("cxx4",), None),
    ],
    ids=["6.0-name", "older-name", "both-names", "cxx-beside-c", "cxx-and-pkg-config", "cxx-only"],
)
def test_installed_find_module_takes_msgpack_c_under_either_name(prefix, tmp_path, present, found):
    """The installed FindMsgpackC.cmake, among stand-in packages only: msgpack-c's package
    under its 6.0 name first, then its older name, never msgpack-cxx's, then pkg-config."""
    root = tmp_path / "root"
    (root / "lib" / "pkgconfig").mkdir(parents=True)
    for name in present:
        path, text = _MSGPACK[name]
        (root / path).parent.mkdir(parents=True, exist_ok=True)
        (root / path).write_text(text + "\n")
    probe = tmp_path / "probe"
    probe.mkdir()
    (probe / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.20)\nproject(probe C)\nfind_package(MsgpackC REQUIRED)\n"
        'message(STATUS "as ${MsgpackC_PACKAGE}, .pc ${MsgpackC_PKG_CONFIG_NAME}")\n'
    )
    env = dict(os.environ, PKG_CONFIG_LIBDIR=str(root / "lib" / "pkgconfig"), PKG_CONFIG_PATH="")
    cmake_dir = next(prefix.glob("lib*/cmake/harvest"))
    res = subprocess.run(
        [
            "cmake",
            "-S",
            str(probe),
            "-B",
            str(tmp_path / "b"),
            f"-DCMAKE_MODULE_PATH={cmake_dir}",
            f"-DCMAKE_FIND_ROOT_PATH={root}",
            "-DCMAKE_FIND_ROOT_PATH_MODE_PACKAGE=ONLY",
        ],
        capture_output=True,
        text=True,
        env=env,
    )
    if found is None:
        assert res.returncode != 0 and "libmsgpack-dev" in res.stderr, res.stderr
    elif found.startswith("pkg-config"):
        assert res.returncode == 0, res.stderr
        assert f"as {found}, .pc msgpack-c" in res.stdout, res.stdout
    else:
        assert res.returncode == 0, res.stderr
        assert f"as CMake package {found} ({root}/lib/cmake/{found}), .pc {found}" in res.stdout


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
