// Edge flips that unfold a triangulation laid over several geometries at
// once (a pair remesh: one connectivity, each vertex on A and on B). Where
// the carrier's vertices sample a surface too sparsely, a chord triangle can
// face against that surface although its quad, split along the other
// diagonal, faces the right way on both: a non-convex quad split outside
// itself. Flips change no vertex, so every vertex stays exactly on its surface.
#pragma once
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// One geometry of the triangulation: a position and a reference normal per
// vertex (the surface's normal there). A triangle folds when it faces against
// the sum of its corners' normals (or has no area).
struct FoldGeometry {
  const std::vector<Vec3>& positions;
  const std::vector<Vec3>& normals;
};

bool folds(const FoldGeometry& geometry, const Triangle& t);

// Flips interior edges of folded triangles while a flip lowers the count of
// (triangle, geometry) folds of the two triangles it replaces, or a flip
// that keeps the count is followed by one of its new triangles' that lowers
// it (a fold walked onto another; torus - knot's remesh with nothing to
// simplify: 123 folded triangles, 48 after single flips, 35 with pairs). The
// edge's two triangles must both be `flippable` (a hole's temporary fan is
// not) and the new edge must not exist, so the surface stays manifold with
// its genus and holes. Returns the number of flips; `triangles` keep their slots.
int unfold_by_flips(std::vector<Triangle>& triangles, const std::vector<char>& flippable,
                    const std::vector<FoldGeometry>& geometries);

}  // namespace cmaps
