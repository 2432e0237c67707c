// A vertex's image on the other surface of an inter-surface map, as both map
// optimizers (the sphere's and the partition's) keep it: the point, and the
// other surface's normal there, which tells a folded image triangle (one
// facing against the surface it lies on) from a sound one.
#pragma once
#include "consistent_maps/mesh.h"

namespace cmaps {

struct Image {
  Vec3 position = Vec3::Zero(), normal = Vec3::Zero();
};

// The surface's normal under a chord triangle of three images: the sum of
// the normals there. A chord triangle whose normal points against it is a
// fold, as measure_intersurface_map counts them.
inline Vec3 surface_normal(const Image* const* corners) {
  return corners[0]->normal + corners[1]->normal + corners[2]->normal;
}

}  // namespace cmaps
