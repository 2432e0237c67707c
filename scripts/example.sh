#!/usr/bin/env bash
# End-to-end example on the meshes in examples/meshes: check each genus-0 mesh
# and map it onto the sphere; map Spot with ten features pinned to the sphere;
# put the two tessellations of Spot into correspondence (consistent maps,
# consistent remeshes, geometry images); map the kitten and the torus (genus 1)
# onto each other directly and remesh them consistently through that map;
# then, in headless Blender through the add-on's API,
# Spot and the penguin (features, consistent set, animated morph, texture and
# normal bakes) and the kitten and the torus (inter-surface map, colour
# transfer, morph, consistent remeshes): .blend files and renders
# (examples/blender_example.py).
# Results go to out/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
mkdir -p out
cmaps=build/cmaps

for mesh in examples/meshes/{spot_low,spot,penguin}.obj; do
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
echo "==> kitten and torus (genus 1, no features) mapped onto each other directly, without the sphere,"
echo "    and remeshed consistently through that map (--remesh 32: 1,026 vertices each, one connectivity)"
"$cmaps" intersurface examples/meshes/kitten.off examples/meshes/torus.obj -o out/kitten_torus --remesh 32 --json |
  tee out/kitten_torus.json

echo
echo "==> Blender: spot and penguin (examples/spot_penguin_features.json), kitten and torus, through consistent_maps.api"
rm -rf out/blender_example
if ! blender -b --factory-startup --python-exit-code 1 -P examples/blender_example.py -- out/blender_example \
  >out/blender_example.log 2>&1; then
  tail -n 40 out/blender_example.log >&2
  echo "the Blender example failed (full log: out/blender_example.log)" >&2
  exit 1
fi
grep '^\[blender example\]' out/blender_example.log
for file in example.blend morph_contact_sheet.png texture_transfer.png normal_transfer.png kitten_torus.blend \
  colour_transfer.png pair_morph_contact_sheet.png pair_distortion.png pair_remeshes.png; do
  test -s "out/blender_example/$file" || { echo "missing out/blender_example/$file" >&2; exit 1; }
done

echo
echo "Written to out/: *_sphere.obj (input triangles on the unit sphere), spot_constrained_* (features"
echo "pinned to the sphere, refined mesh with its Steiner vertices), spot_set/ (consistent maps, remeshes"
echo "with one connectivity, geometry images, feature locations), kitten_torus/ (the kitten's and the"
echo "torus's vertices on each other: A_to_B.txt, B_to_A.txt, A_on_B.obj, B_on_A.obj; consistent remeshes"
echo "A_remesh.obj, B_remesh.obj), blender_example/"
echo "(example.blend with the animated morph, the baked texture and normal map, morph_contact_sheet.png,"
echo "texture_transfer.png, normal_transfer.png; kitten_torus.blend with the kitten's colours on the torus"
echo "and the kitten morphing into it, colour_transfer.png, pair_morph_contact_sheet.png, pair_distortion.png"
echo "(both coloured by where the map stretches them), pair_remeshes.png)."
