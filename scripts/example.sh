#!/usr/bin/env bash
# End-to-end example on the meshes in examples/meshes: check each mesh, then
# map it onto the sphere. Results go to out/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
mkdir -p out
cmaps=build/cmaps

for mesh in examples/meshes/*.obj; do
  name=$(basename "$mesh" .obj)
  echo
  echo "==> $name"
  "$cmaps" check "$mesh"
  "$cmaps" sphere "$mesh" -o "out/${name}_sphere.obj" --json | tee "out/${name}_sphere.json"
done
echo
echo "Spherical parameterizations written to out/ (*_sphere.obj: input triangles, unit-sphere positions)."
