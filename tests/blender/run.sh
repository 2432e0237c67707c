#!/usr/bin/env bash
# Runs the add-on suite (tests/blender/test_addon.py) twice: inside Debian's Blender 3.4
# application and under the bpy module from PyPI (4.x, pinned in requirements-bpy.txt,
# installed into .venv-bpy), then, when xvfb-run exists, the interactive check (gui_check.py:
# modal Compute, panels, overlay; screenshots in out/blender/). Builds the add-on zip first
# (CMake target package_addon).
#
#   tests/blender/run.sh            # both
#   tests/blender/run.sh blender    # only the Blender application ($BLENDER, default: blender)
#   tests/blender/run.sh bpy        # only the bpy module
#   CMAPS_BLENDER_TESTS=compute tests/blender/run.sh    # only tests whose name contains "compute"
#
# Prints "N passed, M failed" per run and exits non-zero if anything failed.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
which=${1:-all}
BLENDER=${BLENDER:-blender}
VENV=${CMAPS_BPY_VENV:-$PWD/.venv-bpy}
PYTHON=${PYTHON:-python3}
NOISE='^(Read blend: |Blender quit|Saved: | Time: |EGL Error|Info: |Warning: Window system)'
failed=()

if [[ -n ${CMAPS_ADDON_ZIP:-} ]]; then
  echo "==> add-on zip: $CMAPS_ADDON_ZIP"
elif [[ -f build/CMakeCache.txt ]]; then
  echo "==> packaging the add-on (cmake --build build --target package_addon)"
  cmake --build build --target package_addon >build/package_addon.log 2>&1 \
    || { tail -n 30 build/package_addon.log; failed+=("package_addon"); }
else
  echo "build/ is not configured (run scripts/setup.sh): the zip tests will fail"
fi

run_blender() {
  echo "==> add-on tests in the Blender application ($BLENDER)"
  if ! command -v "$BLENDER" >/dev/null; then
    echo "'$BLENDER' not found: apt-get install blender (or set BLENDER=/path/to/blender)"
    return 1
  fi
  if ! "$BLENDER" -b --factory-startup --python-exit-code 1 --python-expr "import numpy" >/dev/null 2>&1; then
    local py
    py=$("$BLENDER" -b --factory-startup --python-expr "import sys; print('PY=' + sys.executable)" 2>/dev/null \
         | sed -n 's/^PY=//p')
    if [[ $(id -u) == 0 ]] && command -v apt-get >/dev/null; then
      echo "Blender's Python ($py) lacks numpy: installing python3-numpy"
      apt-get install -y -q python3-numpy >/dev/null || return 1
    else
      echo "Blender's Python ($py) lacks numpy. Install it with:  sudo apt-get install python3-numpy"
      return 1
    fi
  fi
  "$BLENDER" -b --factory-startup --python-exit-code 1 -P tests/blender/run_tests.py 2>&1 | grep -Ev "$NOISE"
}

run_gui() {
  echo "==> interactive check in the Blender application under Xvfb (tests/blender/gui_check.py)"
  local empty output code attempt
  empty=$(mktemp -d)/empty.blend
  "$BLENDER" -b --factory-startup --python-expr "import bpy; bpy.ops.wm.save_as_mainfile(filepath='$empty')" \
    >/dev/null 2>&1 || return 1
  # A second attempt only when the first gave no verdict at all (Xvfb or the window never came up):
  # a verdict or a traceback is the add-on's, and fails at once.
  for attempt in 1 2; do
    output=$(timeout 300 xvfb-run -a -s "-screen 0 1300x1300x24" \
             "$BLENDER" --factory-startup --python-exit-code 1 "$empty" -P tests/blender/gui_check.py 2>&1)
    code=$?
    grep -Ev "$NOISE" <<<"$output" | grep -E "GUI CHECK|Traceback|Error" || true
    if grep -q Traceback <<<"$output"; then
      grep -A12 Traceback <<<"$output"
      code=1
      break
    fi
    grep -q "GUI CHECK" <<<"$output" && break
    echo "(attempt $attempt: no verdict, exit code $code; the last lines it printed:)"
    grep -Ev "$NOISE" <<<"$output" | tail -25
  done
  rm -rf "$(dirname "$empty")"
  ((code == 0)) && grep -q "GUI CHECK OK" <<<"$output"
}

run_bpy() {
  echo "==> add-on tests under the bpy module ($VENV)"
  if [[ ! -x $VENV/bin/python ]]; then
    if ! "$PYTHON" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
      echo "the bpy module and the compiled add-on need Python 3.11: set PYTHON=python3.11"
      return 1
    fi
    "$PYTHON" -m venv "$VENV" || return 1
    echo '*' >"$VENV/.gitignore"  # keep the environment out of git
  fi
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check -r tests/blender/requirements-bpy.txt || return 1
  "$VENV/bin/python" tests/blender/run_tests.py 2>&1 | grep -Ev "$NOISE"
}

if [[ $which == all || $which == blender ]]; then
  run_blender || failed+=("blender")
  if command -v xvfb-run >/dev/null; then
    run_gui || failed+=("gui")
  else
    echo "(xvfb-run not found: interactive check skipped; apt-get install xvfb to run it)"
  fi
fi
if [[ $which == all || $which == bpy ]]; then run_bpy || failed+=("bpy"); fi

if ((${#failed[@]})); then
  echo "blender suite FAILED: ${failed[*]}"
  exit 1
fi
echo "blender suite passed"
