// Delaunay triangulation of points on the unit sphere, i.e. their convex
// hull, with triangles counter-clockwise seen from outside.
#pragma once
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

}  // namespace cmaps
