// Edge flips of the feature layout before any path is traced (thesis 3.3.2):
// a Delaunay triangulation of the targets can join features that are close on
// the sphere but far apart on the surface (the hooves of a horse whose legs
// map to small caps). An arc is replaced by the other diagonal of its two
// triangles when that diagonal's shortest surface path is shorter and both
// new spherical triangles are positively oriented.
#pragma once
#include <array>
#include <vector>

#include "paths/editable_mesh.h"

namespace cmaps {

// Returns the number of flips made on `triangles` (indices into `targets`);
// `fixed` arcs (feature index pairs, either order) are never flipped.
int flip_layout_to_shorter_paths(const EditableMesh& mesh, const std::vector<int>& features,
                                 const std::vector<Vec3>& targets, std::vector<Triangle>& triangles,
                                 const std::vector<std::array<int, 2>>& fixed = {});

}  // namespace cmaps
