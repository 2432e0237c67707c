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

// The chord triangle's normal (the cross product of its edges) against the
// surface's normals at its corners: negative for a fold, as
// measure_intersurface_map counts them.
inline double facing(const Vec3& chord_normal, const Image* const* corners) {
  return chord_normal.dot(corners[0]->normal + corners[1]->normal + corners[2]->normal);
}

}  // namespace cmaps
