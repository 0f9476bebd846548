"""The test-bed runner: a command's output and exit status come back from the guest,
vcan0 exists there with AF_CAN working, the host's files are visible read-only-below-an-
overlay, and --rw folders are shared both ways. One boot for all of it."""

import os
import subprocess
import sys

from harvest.canbus.guest import RUNNER, guest_or_skip, run_in_guest


def test_help():
    p = subprocess.run([RUNNER, "--help"], capture_output=True, text=True)
    assert p.returncode == 0 and "Usage:" in p.stdout and "SKIPPED" in p.stdout


def test_bad_option_is_usage_error():
    p = subprocess.run([RUNNER, "--bogus"], capture_output=True, text=True)
    assert p.returncode == 2 and "unknown option --bogus" in p.stderr


def test_guest_round_trip(tmp_path):
    marker = tmp_path / "from_host.txt"
    marker.write_text("hello guest\n")
    script = (
        "import socket, os, sys\n"
        "s = socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW); s.bind(('vcan0',))\n"
        "s.send(bytes.fromhex('2301000002000000aabb000000000000'))\n"
        f"print(open({str(marker)!r}).read().strip())\n"
        f"open({str(tmp_path / 'from_guest.txt')!r}, 'w').write('hello host')\n"
        "try:\n"
        "    open('/etc/hv_overlay_probe', 'w').write('x')\n"  # lands in the tmpfs overlay
        "    print('overlay writable')\n"
        "except OSError as e:\n"
        "    print('overlay not writable', e)\n"
        "print('to stderr', file=sys.stderr)\n"
        "sys.exit(5)\n"
    )
    proc = guest_or_skip(run_in_guest([sys.executable, "-c", script], rw=[tmp_path], timeout=300))
    assert proc.returncode == 5, proc.stderr
    assert "hello guest" in proc.stdout and "overlay writable" in proc.stdout, proc.stdout
    assert "to stderr" in proc.stderr
    assert (tmp_path / "from_guest.txt").read_text() == "hello host"
    assert not os.path.exists("/etc/hv_overlay_probe"), "guest wrote through to the host root"


def test_says_skipped_where_it_cannot_run(tmp_path):
    """Without dpkg/apt (a PATH holding only the shell tools) the runner cannot fetch a
    kernel: it must exit 77 with a SKIPPED line, never pretend to pass or crash."""
    import shutil

    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for tool in ("bash", "env", "dirname", "grep", "sed", "cat"):
        path = shutil.which(tool)
        assert path, tool
        (bin_dir / tool).symlink_to(path)
    p = subprocess.run(
        [str(bin_dir / "bash"), RUNNER, "--", "true"],
        capture_output=True,
        text=True,
        env={"PATH": str(bin_dir), "HV_TESTBED_CACHE": str(tmp_path / "cache")},
    )
    assert p.returncode == 77, p.stderr
    assert p.stderr.startswith("SKIPPED: testbed: not a Debian system"), p.stderr
    assert not (tmp_path / "cache").exists() or not any((tmp_path / "cache").iterdir())
