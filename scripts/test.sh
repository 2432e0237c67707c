#!/usr/bin/env bash
# Builds, then runs the C++ tests (ctest), the add-on's tests inside Blender
# (tests/blender/run.sh) and the Python tests (pytest).
# Exits non-zero if anything fails; pytest's summary line is printed last.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh || exit 1
PYTHON=${PYTHON:-python3}

echo "==> C++ tests"
if ctest --test-dir build --output-on-failure -j"${CMAPS_JOBS:-$(nproc)}" >build/ctest.log 2>&1; then
  native=0
  grep "tests passed" build/ctest.log
else
  native=1
  tail -n 300 build/ctest.log  # ctest prints the failing tests' output and the list of failures last
fi

echo "==> Blender tests (Debian's Blender 3.4 and the bpy module)"
bash tests/blender/run.sh
blender=$?

echo "==> Python tests"
"$PYTHON" -m pytest -q -p no:cacheprovider tests/python
python=$?

((native == 0 && blender == 0 && python == 0))
