// Carrying per-vertex and per-corner values of one mesh to points on it: the
// interpolation behind attribute transfer through an inter-surface map
// (intersurface_map gives each point as a triangle and barycentric weights).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "consistent_maps/errors.h"
#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/mesh.h"
#include "consistent_maps/obj_attributes.h"

namespace cmaps {

// Per point: the values of the corners of its triangle weighted by its
// barycentric coordinates, with value(triangle, corner) giving a corner's value.
template <std::size_t N, class CornerValue>
std::vector<std::array<double, N>> interpolate_at(const std::vector<SurfacePoint>& points, std::size_t triangles,
                                                  CornerValue value) {
  std::vector<std::array<double, N>> result(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& p = points[i];
    if (p.triangle < 0 || std::size_t(p.triangle) >= triangles)
      throw InvalidInput("point " + std::to_string(i) + " lies on triangle " + std::to_string(p.triangle) + " of " +
                         std::to_string(triangles));
    result[i].fill(0);
    for (int k = 0; k < 3; ++k) {
      const std::array<double, N>& v = value(p.triangle, k);
      for (std::size_t d = 0; d < N; ++d) result[i][d] += p.barycentric[k] * v[d];
    }
  }
  return result;
}

// Per-vertex values of `mesh` (one per vertex) at the points.
template <std::size_t N>
std::vector<std::array<double, N>> interpolate_vertex_values(const TriangleMesh& mesh,
                                                             const std::vector<std::array<double, N>>& values,
                                                             const std::vector<SurfacePoint>& points) {
  if (values.size() != mesh.vertices.size())
    throw InvalidInput(std::to_string(values.size()) + " values for " + std::to_string(mesh.vertices.size()) +
                       " vertices");
  return interpolate_at<N>(points, mesh.triangles.size(),
                           [&](int t, int k) -> const std::array<double, N>& { return values[mesh.triangles[t][k]]; });
}

// Per-corner values (corner k of triangle t has values[corner_index[t][k]], e.g. OBJ
// texture coordinates) at the points: each point takes the values of its own
// triangle's corners, so values that differ across a seam come from the right side.
template <std::size_t N>
std::vector<std::array<double, N>> interpolate_corner_values(const std::vector<std::array<int, 3>>& corner_index,
                                                             const std::vector<std::array<double, N>>& values,
                                                             const std::vector<SurfacePoint>& points) {
  for (const auto& corners : corner_index)
    for (int c : corners)
      if (c < 0 || std::size_t(c) >= values.size())
        throw InvalidInput("corner value " + std::to_string(c) + " out of range (" + std::to_string(values.size()) +
                           ")");
  return interpolate_at<N>(points, corner_index.size(),
                           [&](int t, int k) -> const std::array<double, N>& { return values[corner_index[t][k]]; });
}

// Texture coordinates (u, v) at points of a mesh with per-corner coordinates
// (corner k of triangle t has uvs[triangle_uvs[t][k]]): values[i], computed
// in the chart of point i's own triangle point_triangle[i], expressed in the
// chart of the triangle of point reference[i] (e.g. the first corner of the
// same target face), by composing, along the fewest triangles between the
// two, the similarity of each seam crossed (the one taking the shared edge's
// coordinates in one triangle onto those in the other; u + 1 across a
// cylinder's seam). So the corners of a face whose image straddles a seam
// get coordinates continuing across it instead of spanning the texture.
// Points whose triangles are more than 64 triangles apart keep their values.
std::vector<std::array<double, 2>> continue_across_seams(const std::vector<Triangle>& triangles,
                                                         const std::vector<std::array<int, 3>>& triangle_uvs,
                                                         const std::vector<std::array<double, 2>>& uvs,
                                                         const std::vector<int>& point_triangle,
                                                         std::vector<std::array<double, 2>> values,
                                                         const std::vector<int>& reference);

// The colours and texture coordinates of `source` carried over to `target`
// through `map`, an inter-surface map of target (as A) onto source (as B):
// colours per target vertex at its image; texture coordinates per target
// corner from map.a_corners_to_b (computed with options.corner_images), each
// target triangle's in one chart (continue_across_seams), the coordinates of
// one target vertex shared between its corners where they agree. Throws
// InvalidInput when the map or the attributes do not fit the meshes.
ObjAttributes transfer_obj_attributes(const TriangleMesh& source, const ObjAttributes& source_attributes,
                                      const TriangleMesh& target, const IntersurfaceResult& map);

}  // namespace cmaps
