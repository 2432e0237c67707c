#!/usr/bin/env bash
# Builds, then runs the C++ tests (ctest), the add-on's tests inside Blender
# (tests/blender/run.sh) and the Python tests (pytest).
# Exits non-zero if anything fails, and then names the failures last.
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
bash tests/blender/run.sh 2>&1 | tee build/blender.log
blender=${PIPESTATUS[0]}

echo "==> Python tests"
"$PYTHON" -m pytest -q -p no:cacheprovider tests/python
python=$?

# The failures again, last, where a truncated log still shows them.
((native)) && { echo "C++ tests FAILED:"; grep -E "^\s+[0-9]+ - " build/ctest.log; }
((blender)) && { echo "Blender tests FAILED:"; grep -E "^(FAIL|GUI CHECK|\(attempt|blender suite)" build/blender.log; }
((python)) && echo "Python tests FAILED (above)"
((native == 0 && blender == 0 && python == 0))
