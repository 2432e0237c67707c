// The constrained parameterization of constrained_parameterization.h with a
// consistency term towards another surface's map (correspondence_term.h): the
// features still land exactly on their targets and the map stays
// stretch-minimizing, but the correspondence with the reference induced
// through the sphere is pulled towards an isometry as the map is refined.
// `guide`, when given, replaces the mesh's own unconstrained map in laying
// out the paths (one unit vector per vertex of the mesh with its holes
// closed, centres last): the map then keeps the guide's homotopy class
// around the features; a guide need not be an embedding.
#pragma once
#include <vector>

#include "consistent_maps/constrained_parameterization.h"
#include "sphere/correspondence_term.h"

namespace cmaps {

ConstrainedResult constrained_spherical_parameterization(const TriangleMesh& mesh, const std::vector<int>& features,
                                                         const std::vector<Vec3>& targets,
                                                         const SphereOptions& options,
                                                         const ProgressCallback& progress,
                                                         const ReferenceMap& reference,
                                                         const std::vector<Vec3>* guide = nullptr);

}  // namespace cmaps
