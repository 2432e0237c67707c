// A point strictly inside the kernel of a spherical star polygon: where a
// vertex can sit so that every triangle of its star is positively oriented.
#pragma once
#include <optional>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// `ring` lists the star's outer vertices counter-clockwise (as unit vectors).
// The kernel is intersected with the open hemisphere around `center` (which
// must see part of it) through the gnomonic projection at `center`, where
// every constraint is a half-plane; the result is the centroid of that convex
// polygon. Empty when the kernel is empty or numerically too thin.
std::optional<Vec3> kernel_point(const std::vector<Vec3>& ring, const Vec3& center);

}  // namespace cmaps
