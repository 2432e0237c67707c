// parameterize_to_locations (consistent_parameterization.h) with a
// consistency term towards another member's map (sphere/correspondence_term.h)
// and optionally a guide for the paths (sphere/consistent_constrained_parameterization.h).
#pragma once
#include <vector>

#include "consistent_maps/consistent_parameterization.h"
#include "sphere/correspondence_term.h"

namespace cmaps {

ConstrainedResult parameterize_to_locations(const ConsistentMember& member, const std::vector<Vec3>& locations,
                                            const SphereOptions& options, const ProgressCallback& progress,
                                            const ReferenceMap& reference,
                                            const std::vector<Vec3>* guide = nullptr);

}  // namespace cmaps
