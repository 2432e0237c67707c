// Step 7 of a consistent parameterization (beyond the thesis; optional,
// ConsistentOptions::align): each member's map is refitted with a
// consistency term towards the reference member's (the one that seeded
// step 1), so the maps between members, composed through the sphere, slide
// less. The six steps place the features to suit every member, but each
// member's map stays its own stretch minimum, and on nearly isometric
// members (poses of one shape) those minima slide against each other
// between the features.
//
// Per member: the refit (coarse to fine, like the inter-surface map's) is
// tried along the member's own unconstrained map and along its current one,
// and kept only if it lowers the symmetric Dirichlet energy of the map
// between the member and the reference while keeping 85 % of the efficiency
// of the member's own unconstrained map (the set's target, which the
// consistency term would otherwise trade away). Features stay on their
// common points; members with holes keep their maps (the refit does not
// keep boundary vertices on their arcs). The price is some of each member's
// own efficiency (BENCHMARKS.md).
#pragma once
#include <vector>

#include "consistent_maps/consistent_parameterization.h"

namespace cmaps {

void align_members(const std::vector<ConsistentMember>& members, ConsistentResult& result,
                   const ConsistentOptions& options, const ProgressCallback& progress);

}  // namespace cmaps
