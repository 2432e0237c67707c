// The coarse-to-fine stage shared by every spherical parameterization:
// replay a progressive mesh's vertex splits on the sphere, placing each new
// vertex inside its 1-ring kernel and optimizing it and its neighbours, with
// global optimization passes as the mesh grows and at the end.
#pragma once
#include <vector>

#include "consistent_maps/progress.h"
#include "consistent_maps/progressive_mesh.h"
#include "consistent_maps/spherical_parameterization.h"

namespace cmaps {

// Same shape centred at the area centroid and scaled to total area 4 pi, so
// energies and tolerances do not depend on the input's position or scale.
std::vector<Vec3> normalized_positions(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles);

// `sphere` holds valid positions for the base vertices of `pm` on entry (the
// base triangles positively oriented) and every vertex's position on exit.
// `geometries` are the surfaces whose summed stretch is minimized (one per
// shape sharing the connectivity); `fixed` vertices (may be empty) never move.
// Progress is reported through `progress` as "refine" then "optimize".
void refine_on_sphere(const ProgressiveMesh& pm, const std::vector<const std::vector<Vec3>*>& geometries,
                      const std::vector<char>& fixed, const SphereOptions& options, std::vector<Vec3>& sphere,
                      const ProgressSlice& progress);

}  // namespace cmaps
