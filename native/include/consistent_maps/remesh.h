// Remeshing through a spherical parameterization: the surface point at any
// sphere sample is found by locating the sample on the parameterized mesh
// and interpolating the 3D positions barycentrically, so sampling a grid's
// vertices gives a remesh with the grid's connectivity.
#pragma once
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// `sphere` holds one unit vector per mesh vertex (a bijective
// parameterization); returns one surface position per sample. Throws
// InvalidInput for mismatched sizes or a parameterization SphereLocator rejects.
std::vector<Vec3> resample(const TriangleMesh& mesh, const std::vector<Vec3>& sphere,
                           const std::vector<Vec3>& samples, int threads = 2);

// `samples` are unit vectors. For each feature direction, moves the nearest
// sample exactly onto it (the direction normalized) and returns that
// sample's index, so every remesh carries feature k at the same vertex.
// Throws InvalidInput for a zero or non-finite direction, or when two
// features would need the same sample (the grid is too coarse for them);
// `samples` is then unchanged.
std::vector<int> snap_features(std::vector<Vec3>& samples, const std::vector<Vec3>& feature_directions);

}  // namespace cmaps
