// Genus 0 through the sphere: the composition of a consistent spherical
// parameterization of the pair (thesis 3.2), refitted and optimized for the
// symmetric distortion of both directions, restarted from several layouts.
#pragma once
#include <vector>

#include "consistent_maps/intersurface_map.h"

namespace cmaps {

// Genus 0 through the sphere: options.restarts maps, the least distorted
// kept. The optimization ends in a different local minimum from
// each start; restarts cycle through three layouts of the pair's consistent
// parameterization, the seed advancing after each cycle; each starts some
// pairs in a better basin and others in a worse one.
void map_through_sphere_restarts(const TriangleMesh& a, const TriangleMesh& b, const std::vector<FeaturePair>& features,
                                 IntersurfaceResult& result, const IntersurfaceOptions& options,
                                 const ProgressCallback& progress);

}  // namespace cmaps
