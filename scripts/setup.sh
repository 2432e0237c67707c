#!/usr/bin/env bash
# Installs what is missing (Debian packages, Python packages) and builds the
# project incrementally in build/. Shared by scripts/example.sh and
# scripts/test.sh; safe to run repeatedly, non-interactive (CI=true or no tty).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

step() { printf '==> %s\n' "$*"; }

# --- Debian packages --------------------------------------------------------
# xvfb: the add-on's interactive check runs Blender with a window (tests/blender/gui_check.py).
packages=(g++ make libopenmesh-dev libeigen3-dev pybind11-dev libgtest-dev blender xvfb)
command -v cmake >/dev/null 2>&1 || packages+=(cmake)  # a pip-installed cmake is fine too
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  if [[ $(id -u) -eq 0 ]]; then
    step "installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    apt-get install -y -q "${missing[@]}"
  else
    echo "setup: missing Debian packages: ${missing[*]}" >&2
    echo "setup: install them with:  sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

# --- Python packages ----------------------------------------------------------
PYTHON=${PYTHON:-python3}
if ! "$PYTHON" - <<'EOF' 2>/dev/null; then
import numpy, pytest, pybind11
major, minor = (int(x) for x in pybind11.__version__.split(".")[:2])
assert (major, minor) >= (2, 12)
EOF
  step "installing Python packages from requirements-dev.txt"
  "$PYTHON" -m pip install --quiet --disable-pip-version-check -r requirements-dev.txt
fi

# --- Configure (once) and build (incremental) ----------------------------------
if [[ ! -f build/CMakeCache.txt ]]; then
  step "configuring build/"
  # pip's pybind11 (>= 2.12) rather than Debian's 2.10: only the former supports numpy 2.
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_POLICY_VERSION_MINIMUM=3.5 \
    -DPython3_EXECUTABLE="$(command -v "$PYTHON")" \
    -Dpybind11_DIR="$("$PYTHON" -m pybind11 --cmakedir)" >/dev/null
fi
step "building"
log=build/build.log
if ! cmake --build build -j"${CMAPS_JOBS:-$(nproc)}" >"$log" 2>&1; then
  grep -Ev '^\[ *[0-9]+%\]' "$log" >&2 || true  # the compiler's messages without progress lines
  echo "setup: build failed (full log: $log)" >&2
  exit 1
fi
