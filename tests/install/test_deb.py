"""The Debian package: `cpack -G DEB` run in the build folder the test runs in (a sanitized
Debug build packs sanitized programs: what the package holds is the same), then the
package read with dpkg-deb: its programs, libraries, headers, DBC and config, the conffiles
in /etc/harvest, the maintainer scripts that make the `harvest` user (run against stand-in
commands that record what they were asked), and the systemd units, which must pass
`systemd-analyze verify` with their programs taken from the unpacked package.

Not here: installing the package where systemd is the init and running a row through its
units (that needs a machine or test-bed guest booted with systemd)."""

import os
import re
import shutil
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from install_tree import BUILD_DIR, PROGRAMS, SOURCE_DIR  # noqa: E402
from install_tree import cache as _cache  # noqa: E402
from install_tree import run as _run  # noqa: E402

UNITS = ["harvest-can.service", "harvest-exec.service", "harvest-plan-online.service"]
UNIT_DIRS = ("lib/systemd/system", "usr/lib/systemd/system")


@pytest.fixture(scope="module")
def deb(tmp_path_factory):
    """(path of the .deb, its files unpacked, its control files unpacked)"""
    for tool in ("cpack", "dpkg-deb"):
        if shutil.which(tool) is None:
            pytest.skip(f"SKIPPED: {tool} not on PATH")
    if _cache("HV_WITH_EXECUTOR") != "ON" or _cache("HV_WITH_GLPK") != "ON":
        pytest.skip("SKIPPED: the build leaves out the executor or the planner")
    tmp = tmp_path_factory.mktemp("deb")
    config = os.path.join(BUILD_DIR, "CPackConfig.cmake")
    _run(["cpack", "-G", "DEB", "--config", config, "-B", str(tmp / "out")], cwd=BUILD_DIR)
    debs = list((tmp / "out").glob("*.deb"))
    assert len(debs) == 1, debs
    _run(["dpkg-deb", "-x", str(debs[0]), str(tmp / "root")])
    _run(["dpkg-deb", "-e", str(debs[0]), str(tmp / "control")])
    return debs[0], tmp / "root", tmp / "control"


def _unit_dir(root):
    found = [root / d for d in UNIT_DIRS if (root / d).is_dir()]
    assert len(found) == 1, f"units in {found}, expected one of {UNIT_DIRS}"
    return found[0]


def _unit(root, name):
    """{(section, key): [values]} of a unit file, in order."""
    out, section = {}, ""
    for line in (_unit_dir(root) / name).read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith("["):
            section = line.strip("[]")
            continue
        key, value = line.split("=", 1)
        out.setdefault((section, key), []).append(value)
    return out


def test_the_package_carries_the_projects_name_and_version(deb):
    path, _, _ = deb
    with open(os.path.join(SOURCE_DIR, "VERSION"), encoding="ascii") as f:
        version = f.readline().strip()
    fields = {
        f: _run(["dpkg-deb", "-f", str(path), f]).strip()
        for f in ("Package", "Version", "Architecture", "Depends")
    }
    assert fields["Package"] == "harvest" and fields["Version"] == version
    assert fields["Architecture"] == _run(["dpkg", "--print-architecture"]).strip()
    depends = [d.split()[0] for d in fields["Depends"].split(",")]
    # the maintainer scripts' adduser, the CAN bring-up's ip, the planner's GLPK
    assert "adduser" in depends and "iproute2" in depends
    assert any(d.startswith("libglpk") for d in depends), depends


def test_programs_libraries_headers_and_data_under_usr(deb):
    path, root, _ = deb
    listing = _run(["dpkg-deb", "-c", str(path)])
    names = {line.split()[-1].lstrip(".") for line in listing.splitlines()}
    for prog in PROGRAMS:
        assert f"/usr/bin/{prog}" in names and os.access(root / "usr/bin" / prog, os.X_OK), prog
    assert any(re.fullmatch(r"/usr/lib/.*libhv_core\.a", n) for n in names)
    assert any(re.fullmatch(r"/usr/lib/.*cmake/harvest/harvestConfig\.cmake", n) for n in names)
    assert "/usr/include/hv/version.h" in names and "/usr/include/harvest_can.h" in names
    share = root / "usr/share/harvest"
    with open(os.path.join(SOURCE_DIR, "executor/can/harvest.dbc"), "rb") as f:
        assert (share / "harvest.dbc").read_bytes() == f.read()
    assert (share / "harvest.cfg").is_file() and list((share / "lcm").glob("*.lcm"))
    # the page every program's --help points to, beside the install guide
    assert {"/usr/share/doc/harvest/EXIT_CODES.md", "/usr/share/doc/harvest/INSTALL.md"} <= names
    # the package's prefix is /usr: nothing of the build's own prefix or folders
    assert not [n for n in names if n.startswith("/usr/local")]
    assert not [n for n in names - {"/"} if not n.startswith(("/usr/", "/etc/", "/lib/"))]
    assert BUILD_DIR not in _unit_dir(root).joinpath("harvest-exec.service").read_text()


def test_the_config_in_etc_harvest_is_the_conffiles(deb):
    _, root, control = deb
    etc = sorted("/" + str(p.relative_to(root)) for p in (root / "etc").rglob("*") if p.is_file())
    conffiles = sorted((control / "conffiles").read_text().split())
    assert etc == conffiles and "/etc/harvest/harvest.cfg" in etc, (etc, conffiles)
    with open(os.path.join(SOURCE_DIR, "config/harvest.cfg"), "rb") as f:
        assert (root / "etc/harvest/harvest.cfg").read_bytes() == f.read()
    # every variable the units expand is set in the settings file they read
    env = dict(
        line.split("=", 1)
        for line in (root / "etc/harvest/harvest.env").read_text().splitlines()
        if line and not line.startswith("#")
    )
    for name in UNITS:
        text = (_unit_dir(root) / name).read_text()
        assert "EnvironmentFile=/etc/harvest/harvest.env" in text, name
        for var in re.findall(r"\$\{?(HV_[A-Z_]+)", text):
            assert var in env, (name, var)
    assert env["HV_CAN_INTERFACE"] == "can0"


def _stub_commands(folder, log, getent_finds_harvest):
    """Stand-ins for what the maintainer scripts call: each records its arguments."""
    folder.mkdir()
    codes = {"getent": 0 if getent_finds_harvest else 2}
    for cmd in ("getent", "adduser", "useradd", "mkdir", "chown", "chmod", "systemctl"):
        stub = folder / cmd
        stub.write_text(f'#!/bin/sh\necho "{cmd} $*" >> "{log}"\nexit {codes.get(cmd, 0)}\n')
        stub.chmod(0o755)


def _postinst(control, tmp_path, user_exists):
    log = tmp_path / "calls.log"
    log.write_text("")
    _stub_commands(tmp_path / "bin", log, user_exists)
    res = subprocess.run(
        ["/bin/sh", str(control / "postinst"), "configure", ""],
        capture_output=True,
        text=True,
        env={"PATH": str(tmp_path / "bin")},
    )
    assert res.returncode == 0, res.stderr
    return log.read_text().splitlines()


def test_postinst_makes_the_harvest_system_user_and_its_state_folder(deb, tmp_path):
    _, _, control = deb
    assert os.access(control / "postinst", os.X_OK)
    calls = _postinst(control, tmp_path, user_exists=False)
    made = [c.split() for c in calls if c.startswith(("adduser ", "useradd "))]
    assert len(made) == 1 and "--system" in made[0] and made[0][-1] == "harvest", calls
    assert "chown harvest:harvest /var/lib/harvest" in calls, calls


def test_postinst_keeps_a_harvest_user_that_exists(deb, tmp_path):
    _, _, control = deb
    calls = _postinst(control, tmp_path, user_exists=True)
    assert not [c for c in calls if c.startswith(("adduser ", "useradd "))], calls
    assert "chown harvest:harvest /var/lib/harvest" in calls, calls


def test_the_units_pass_systemd_analyze_verify(deb, tmp_path):
    if shutil.which("systemd-analyze") is None:
        pytest.skip("SKIPPED: systemd-analyze not on PATH (Debian package systemd)")
    _, root, _ = deb
    # verify checks that each Exec command exists: copies of the units whose commands are
    # the unpacked package's; nothing else changes
    for name in UNITS:
        text = (_unit_dir(root) / name).read_text()
        copy = re.sub(r"^(Exec\w*=[-@:+!]*)/", rf"\g<1>{root}/", text, flags=re.M)
        assert copy != text, name
        (tmp_path / name).write_text(copy)
    res = subprocess.run(
        ["systemd-analyze", "verify", "--man=no", *(str(tmp_path / n) for n in UNITS)],
        capture_output=True,
        text=True,
    )
    # verify exits 0 on an unknown key or a bad value, but says so: nothing must be said
    assert res.returncode == 0 and not (res.stdout + res.stderr).strip(), res.stdout + res.stderr


def test_the_executor_unit_restarts_a_crash_but_not_a_latched_estop(deb):
    _, root, _ = deb
    u = _unit(root, "harvest-exec.service")
    assert u[("Service", "User")] == ["harvest"] and u[("Service", "Restart")] == ["on-failure"]
    prevent = " ".join(u[("Service", "RestartPreventExitStatus")]).split()
    assert "3" in prevent and "4" in prevent, prevent  # the e-stop latches (harvest-exec --help)
    assert "6" in " ".join(u[("Service", "SuccessExitStatus")]).split()  # a controlled stop
    exec_start = u[("Service", "ExecStart")][0].split()
    assert exec_start[0] == "/usr/bin/harvest-exec"
    assert exec_start[exec_start.index("--transport") + 1] == "socketcan"
    assert exec_start[exec_start.index("--journal") + 1].startswith("/var/lib/harvest/")
    assert exec_start[exec_start.index("--config") + 1] == "/etc/harvest/harvest.cfg"
    assert "harvest-can.service" in u[("Unit", "Requires")][0].split()
    assert "harvest-can.service" in u[("Unit", "After")][0].split()
    planner = _unit(root, "harvest-plan-online.service")
    assert planner[("Service", "User")] == ["harvest"]
    assert planner[("Service", "ExecStart")][0].startswith("/usr/bin/harvest-plan-online ")


def test_the_can_bring_up_sets_the_dbcs_bit_rate(deb):
    import cantools

    _, root, _ = deb
    dbc = cantools.database.load_file(os.path.join(SOURCE_DIR, "executor/can/harvest.dbc"))
    bitrate = dbc.dbc.attributes["Baudrate"].value
    exec_start = _unit(root, "harvest-can.service")[("Service", "ExecStart")][0].split()
    script = root / exec_start[0].lstrip("/")
    assert exec_start[1:] == ["${HV_CAN_INTERFACE}", str(bitrate)], exec_start
    assert "--help" in _run([str(script), "--help"])
    bad = subprocess.run([str(script), "can0", "fast"], capture_output=True, text=True)
    assert bad.returncode == 2 and "BITRATE" in bad.stderr
