#!/usr/bin/env bash
# End-to-end example on the meshes in examples/meshes: check each mesh and map
# it onto the sphere; map Spot with ten features pinned to the sphere; put the
# two tessellations of Spot into correspondence (consistent maps, consistent
# remeshes, geometry images); then, in headless Blender through the add-on's API,
# Spot and the penguin: features, consistent set, animated morph, texture bake, a
# .blend and renders (examples/blender_example.py). Results go to out/.
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
echo "==> Blender: spot and penguin (examples/spot_penguin_features.json) through consistent_maps.api"
rm -rf out/blender_example
if ! blender -b --factory-startup --python-exit-code 1 -P examples/blender_example.py -- out/blender_example \
  >out/blender_example.log 2>&1; then
  tail -n 40 out/blender_example.log >&2
  echo "the Blender example failed (full log: out/blender_example.log)" >&2
  exit 1
fi
grep '^\[blender example\]' out/blender_example.log
for file in example.blend morph_contact_sheet.png texture_transfer.png normal_transfer.png; do
  test -s "out/blender_example/$file" || { echo "missing out/blender_example/$file" >&2; exit 1; }
done

echo
echo "Written to out/: *_sphere.obj (input triangles on the unit sphere), spot_constrained_* (features"
echo "pinned to the sphere, refined mesh with its Steiner vertices), spot_set/ (consistent maps, remeshes"
echo "with one connectivity, geometry images, feature locations), blender_example/ (example.blend with the"
echo "animated morph, the baked texture and normal map, morph_contact_sheet.png, texture_transfer.png,"
echo "normal_transfer.png)."
