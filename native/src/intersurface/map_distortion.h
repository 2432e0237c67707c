// The distortion measure of intersurface_map.h for a caller that knows how
// the two meshes face: measuring many maps of one pair need not check both
// meshes and close their holes each time to find out.
#pragma once
#include <vector>

#include "consistent_maps/intersurface_map.h"

namespace cmaps {

// +1 when the two meshes, their holes closed, list their triangles the same
// way round (both outwards or both inwards), -1 otherwise: the sign that
// turns the target's normals to face like the source's.
double facing(const TriangleMesh& closed_source, const TriangleMesh& closed_target);

// triangle_distortion and measure_intersurface_map with that sign given
// (`facing` of the meshes with their holes closed); the meshes are not checked.
TriangleDistortion triangle_distortion(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image, double facing);
MapDistortion measure_intersurface_map(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image, double facing);

}  // namespace cmaps
