#!/usr/bin/env bash
# Install exactly what is missing for building, the demo and the tests, idempotently:
# Debian packages with apt-get, Python packages into the project virtualenv (.venv).
# Usage: scripts/setup.sh [--help]
set -euo pipefail
if [[ "${1:-}" == "--help" || "${1:-}" == "-h" ]]; then
  sed -n '2,4p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
root=$(cd "$(dirname "$0")/.." && pwd)

# Debian packages, one line each with why.
apt_pkgs=(
  build-essential cmake ninja-build pkg-config   # C/C++ toolchain and build
  libeigen3-dev                                  # tools/: cost table generator, mount search
  libglpk-dev glpk-utils                         # planner/: the MILP (C API; glpsol to cross-check)
  libjansson-dev                                 # plan files: the JSON reader
  clang-format                                   # tests/lint: the C/C++ format check
  libcmocka-dev                                  # C unit tests
  clang libclang-rt-14-dev                       # fuzz/: clang, its libFuzzer + ASan/UBSan runtimes (HV_FUZZ)
  libglib2.0-dev                                 # telemetry: glib for liblcm.a (LCM itself: pip, requirements.txt)
  libmsgpack-dev                                 # CAN over UDP, python-can's udp_multicast format
  python3 python3-venv python3-dev               # host/ package and pytest
  iproute2 can-utils                             # network namespaces, vcan tools
  qemu-system-x86 busybox-static cpio kmod       # the vcan test-bed guest (DESIGN §6)
  gcc-arm-none-eabi libnewlib-arm-none-eabi      # firmware/: the Cortex-M4F cross build
  qemu-system-arm                                # firmware/: harvest-fw.elf on mps2-an386
  dpkg-dev systemd                               # the .deb: cpack's dpkg-shlibdeps; systemd-analyze verify of its units
)
missing=()
for p in "${apt_pkgs[@]}"; do
  [[ "$p" == \#* ]] && continue
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing Debian packages: ${missing[*]}"
  sudo_cmd=(); [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: Debian packages present"
fi

# Python: a virtualenv of the project, on Debian's python3.
venv="$root/.venv"
if [[ ! -x "$venv/bin/python" ]]; then
  echo "setup: creating virtualenv $venv"
  /usr/bin/python3 -m venv "$venv"
fi
# The pinned dependencies, then host/ itself as the package harvest-stack (editable: the
# venv runs this checkout's code, `python -m harvest` and `harvest-stack` alike).
req="$root/host/requirements.txt"
stamp="$venv/.requirements.sha256"
want=$( (cat "$req" "$root/host/pyproject.toml"; echo "$root") | sha256sum | cut -d' ' -f1)
if [[ ! -f "$stamp" || "$(cat "$stamp")" != "$want" ]]; then
  echo "setup: installing Python packages from host/requirements.txt and host/ (harvest-stack)"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$req"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check --no-deps -e "$root/host"
  echo "$want" > "$stamp"
else
  echo "setup: Python packages present"
fi
