// Delaunay triangulation of points on the unit sphere, i.e. their convex
// hull, with triangles counter-clockwise seen from outside.
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// Empty when the points are coplanar. Ties between cocircular points are
// broken by a tiny deterministic perturbation.
std::optional<std::vector<Triangle>> convex_hull_on_sphere(const std::vector<Vec3>& points);

// A point that, added to `points`, moves the origin towards the inside of
// their convex hull; empty when the origin is already strictly inside, i.e.
// when every hull triangle is positively oriented as a chordal triangle.
std::optional<Vec3> point_to_enclose_origin(const std::vector<Vec3>& points);

// Flips edges of `triangles` (a triangulation of `points`, counter-clockwise
// chordal triangles) until every `required` edge (pairs of point indices,
// not crossing each other) is an edge; false when that fails. Required edges
// already present are never flipped.
bool force_edges(const std::vector<Vec3>& points, std::vector<Triangle>& triangles,
                 const std::vector<std::array<int, 2>>& required);

}  // namespace cmaps
