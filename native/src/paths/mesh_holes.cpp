#include "paths/mesh_holes.h"

#include <algorithm>
#include <map>
#include <unordered_map>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"

namespace cmaps {

ClosedMesh close_holes(const TriangleMesh& mesh, bool any_genus) {
  ClosedMesh closed;
  closed.mesh = mesh;
  closed.input_vertices = static_cast<int>(mesh.vertices.size());
  closed.input_triangles = static_cast<int>(mesh.triangles.size());
  const MeshReport report = check_mesh(mesh);
  const bool usable = report.manifold() && report.inconsistently_oriented_edges == 0 && report.components == 1 &&
                      report.out_of_range_indices == 0 && report.non_finite_vertices == 0;
  if (any_genus && !usable)
    throw TopologyError("mesh has " + summarize(report) + "; it must be one manifold, consistently oriented surface");
  if (report.boundary_loops == 0) {
    if (!any_genus) require_sphere_topology(mesh);
    return closed;
  }
  if (!usable) require_sphere_topology(mesh);  // names the defect
  // Boundary half-edges u -> v (no v -> u): the fan triangle runs v -> u.
  std::map<std::pair<int, int>, int> half_edges;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++half_edges[{t[k], t[(k + 1) % 3]}];
  std::unordered_map<int, int> next;
  for (const auto& [e, count] : half_edges)
    if (!half_edges.count({e.second, e.first})) {
      if (!next.emplace(e.second, e.first).second)
        throw TopologyError("mesh has a vertex (" + std::to_string(e.second) +
                            ") where two boundary loops touch; holes must be separate");
    }
  std::vector<int> starts;
  for (const auto& [v, w] : next) starts.push_back(v);
  std::sort(starts.begin(), starts.end());
  std::unordered_map<int, char> seen;
  for (int s : starts) {
    if (seen.count(s)) continue;
    std::vector<int> loop;
    for (int v = s; !seen.count(v); v = next.at(v)) {
      seen[v] = 1;
      loop.push_back(v);
      if (!next.count(v)) throw TopologyError("mesh has an open boundary chain at vertex " + std::to_string(v));
    }
    closed.loops.push_back(std::move(loop));
  }
  for (size_t h = 0; h < closed.loops.size(); ++h) {
    const auto& loop = closed.loops[h];
    Vec3 centroid = Vec3::Zero();
    for (int v : loop) centroid += mesh.vertices[v];
    closed.mesh.vertices.push_back(centroid / static_cast<double>(loop.size()));
    const int c = closed.centre(static_cast<int>(h));
    for (size_t j = 0; j < loop.size(); ++j) closed.mesh.triangles.push_back({c, loop[j], loop[(j + 1) % loop.size()]});
  }
  if (any_genus) return closed;
  try {
    require_sphere_topology(closed.mesh);
  } catch (const TopologyError& e) {
    throw TopologyError("mesh with its " + std::to_string(closed.loops.size()) +
                        " holes closed is not a sphere: " + e.what());
  }
  return closed;
}

std::vector<std::vector<int>> hole_features(const ClosedMesh& closed, const std::vector<int>& features,
                                            const std::string& who) {
  std::unordered_map<int, int> feature_of;
  for (int i = 0; i < static_cast<int>(features.size()); ++i)
    if (features[i] >= 0) feature_of[features[i]] = i;
  std::vector<std::vector<int>> result;
  for (size_t h = 0; h < closed.loops.size(); ++h) {
    std::vector<int> on;
    for (int v : closed.loops[h]) {
      const auto it = feature_of.find(v);
      if (it != feature_of.end()) on.push_back(it->second);
    }
    if (on.size() < 3)
      throw InvalidInput(who + "hole " + std::to_string(h) + " (boundary loop of " +
                         std::to_string(closed.loops[h].size()) + " vertices through vertex " +
                         std::to_string(closed.loops[h].front()) + ") is ringed by " + std::to_string(on.size()) +
                         " features; every hole needs at least 3 features on its boundary");
    result.push_back(std::move(on));
  }
  return result;
}

}  // namespace cmaps
