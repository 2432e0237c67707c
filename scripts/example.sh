#!/usr/bin/env bash
# End-to-end example on the meshes in examples/meshes: check each mesh and map
# it onto the sphere; map Spot with ten features pinned to the sphere; put the
# two tessellations of Spot into correspondence (consistent maps, consistent
# remeshes, geometry images). Results go to out/.
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
echo "==> spot with features (examples/spot_features.json: name -> vertex, at the mesh's extremes)"
"$cmaps" constrained examples/meshes/spot.obj --features examples/spot_features.json \
  -o out/spot_constrained_sphere.obj --refined-mesh out/spot_constrained_refined.obj --json |
  tee out/spot_constrained.json

echo
echo "==> spot_low and spot in correspondence (examples/spot_set_features.json: name -> [vertex per mesh])"
"$cmaps" consistent examples/meshes/spot_low.obj examples/meshes/spot.obj \
  --features examples/spot_set_features.json -o out/spot_set --remesh 32 --json | tee out/spot_set.json

echo
echo "Written to out/: *_sphere.obj (input triangles on the unit sphere), spot_constrained_* (features"
echo "pinned to the sphere, refined mesh with its Steiner vertices), spot_set/ (consistent maps, remeshes"
echo "with one connectivity, geometry images, feature locations)."
