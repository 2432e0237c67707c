// The direct map of a pair through a consistent partition into patches
// (Schreiner et al. 2004, thesis chapter 5): every pair of genus >= 1, genus
// 0 on request or to compare with the sphere's map.
#pragma once
#include "consistent_maps/intersurface_map.h"

namespace cmaps {

// The direct map. A pair given no features and without holes has an
// automatic first pair, which decides how the partition pairs the surfaces'
// handles and parts; between different shapes the maps from different first
// pairs differ widely (kitten - rocker-arm, four: summed medians 22.0, 20.2,
// 14.3, 32.4), and they rank alike before the optimization (28.6, 25.7,
// 18.3, 40.6). So options.starts first pairs are each mapped without
// optimization, and the options.restarts least distorted of them are
// optimized, the least distorted kept.
void map_directly(const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                  const IntersurfaceOptions& options, const ProgressCallback& progress);

}  // namespace cmaps
