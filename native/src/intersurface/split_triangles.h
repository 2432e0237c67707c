// The input triangles the partition's paths cut into pieces. The map is
// optimized on the pieces, but what it gives back is sampled at the input
// vertices (cmaps intersurface writes one image per vertex), so an input
// triangle cut by a path is seen through the chord of its three corners'
// images, which skips the path's own vertices: its pieces can all be fine
// while that chord is a needle or faces backwards (on feline -> skull the
// cut triangles are 14 % of the feline's and held 43 % of its sampled folds).
// The optimization across the paths charges these chords as well
// (cross_patch_optimization.h, with chord_energy.h's energy).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "intersurface/chord_energy.h"

namespace cmaps {

// A hole's fan triangles are never among them.
struct SplitTriangles {
  std::vector<Triangle> corners;            // per cut input triangle: its input vertices, turning as its pieces
  std::vector<SourceTriangle> shape;        // and its shape
  std::vector<std::vector<int>> of_vertex;  // per mesh vertex: the cut triangles it is a corner of
};

SplitTriangles split_triangles(const PartitionSide& side);

// Per input triangle (holes' fans left out), where it lies against the
// side's paths: 0 away from them, 1 a corner on a path, 2 cut by one (its
// pieces in two patches). What IntersurfaceResult::a_along_paths reports.
std::vector<std::int8_t> along_paths(const PartitionSide& side);

// Cut triangle s's chord energy (triangle_energy) with its corners' images
// in `images` (per mesh vertex), vertex v's replaced by *q (none when v < 0);
// *folded as triangle_energy raises it.
inline double split_energy(const SplitTriangles& split, int s, const std::vector<Image>& images, int v,
                           const Image* q, double* folded = nullptr) {
  const Triangle& t = split.corners[s];
  const Image* image[3];
  for (int k = 0; k < 3; ++k) image[k] = t[k] == v ? q : &images[t[k]];
  return triangle_energy(split.shape[s], image, folded);
}

}  // namespace cmaps
