// parameterize_to_locations (consistent_parameterization.h) with a
// consistency term towards another member's map (sphere/correspondence_term.h).
#pragma once
#include <vector>

#include "consistent_maps/consistent_parameterization.h"
#include "sphere/correspondence_term.h"

namespace cmaps {

ConstrainedResult parameterize_to_locations(const ConsistentMember& member, const std::vector<Vec3>& locations,
                                            const SphereOptions& options, const ProgressCallback& progress,
                                            const ReferenceMap& reference);

}  // namespace cmaps
