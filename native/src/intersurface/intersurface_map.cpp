// Inter-surface maps (issue 5): genus 0 by the composition of two consistent
// spherical parameterizations (sphere_route.h), every genus through a
// consistent partition into patches (partition_route.h), the less distorted
// kept (map_choice.h). Here: the input checked and the route chosen. See
// intersurface_map.h.
#include "consistent_maps/intersurface_map.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include "common/side_by_side.h"
#include "common/stage_clock.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "intersurface/map_choice.h"
#include "intersurface/partition_route.h"
#include "intersurface/sphere_route.h"

namespace cmaps {
namespace {

// The topology (genus, holes) of a mesh an inter-surface map takes; the
// error naming the mesh (`name` is "A" or "B") and its first defect otherwise.
MeshReport checked_topology(const TriangleMesh& mesh, const std::string& name) {
  try {
    return require_pair_map_topology(mesh);
  } catch (const TopologyError& e) {
    throw TopologyError(name + ": " + e.what());
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
}

void check_features(const std::vector<FeaturePair>& features, const TriangleMesh& a, const TriangleMesh& b) {
  std::map<int, std::size_t> seen_a, seen_b;
  for (std::size_t k = 0; k < features.size(); ++k) {
    const std::string pair = "feature pair " + std::to_string(k);
    const auto check = [&](int v, const TriangleMesh& mesh, const char* name, std::map<int, std::size_t>& seen) {
      const int n = int(mesh.vertices.size());
      if (v < 0 || v >= n)
        throw InvalidInput(pair + ": vertex " + std::to_string(v) + " is out of range for " + name + " (" +
                           std::to_string(n) + " vertices)");
      const auto [it, inserted] = seen.emplace(v, k);
      if (!inserted)
        throw InvalidInput("feature pairs " + std::to_string(it->second) + " and " + std::to_string(k) +
                           " both use vertex " + std::to_string(v) + " of " + name);
    };
    check(features[k].a, a, "A", seen_a);
    check(features[k].b, b, "B", seen_b);
  }
}

// Vertices no triangle uses (the teapot has 4) carry no surface: the map is
// computed without them, and each takes the image of the nearest used vertex.
struct UsedVertices {
  TriangleMesh mesh;         // the used vertices only, triangles in their order
  std::vector<int> to_used;  // per input vertex: its index in `mesh`, -1 if unused
  std::vector<int> nearest;  // per input vertex: the nearest used input vertex (itself if used)
};

// Null when every vertex is used (or an index is out of range: check_mesh reports that).
std::optional<UsedVertices> drop_unused(const TriangleMesh& mesh) {
  const int n = int(mesh.vertices.size());
  std::vector<char> used(n, 0);
  for (const Triangle& t : mesh.triangles)
    for (int v : t) {
      if (v < 0 || v >= n) return std::nullopt;
      used[v] = 1;
    }
  if (std::count(used.begin(), used.end(), 1) == n) return std::nullopt;
  UsedVertices u;
  u.to_used.assign(n, -1);
  for (int v = 0; v < n; ++v)
    if (used[v]) u.to_used[v] = int(u.mesh.vertices.size()), u.mesh.vertices.push_back(mesh.vertices[v]);
  for (Triangle t : mesh.triangles) {
    for (int& v : t) v = u.to_used[v];
    u.mesh.triangles.push_back(t);
  }
  u.nearest.resize(n);
  for (int v = 0; v < n; ++v) {
    u.nearest[v] = v;
    double best = std::numeric_limits<double>::infinity();
    for (int w = 0; !used[v] && w < n; ++w)
      if (used[w] && (mesh.vertices[w] - mesh.vertices[v]).squaredNorm() < best)
        best = (mesh.vertices[w] - mesh.vertices[v]).squaredNorm(), u.nearest[v] = w;
  }
  return u;
}

}  // namespace

const char* method_name(IntersurfaceMethod method) {
  switch (method) {
    case IntersurfaceMethod::sphere: return "sphere";
    case IntersurfaceMethod::partition: return "partition";
    default: return "auto";
  }
}

std::optional<IntersurfaceMethod> parse_method(const std::string& name) {
  for (IntersurfaceMethod m :
       {IntersurfaceMethod::automatic, IntersurfaceMethod::sphere, IntersurfaceMethod::partition})
    if (name == method_name(m)) return m;
  return std::nullopt;
}

IntersurfaceResult intersurface_map(const TriangleMesh& a, const TriangleMesh& b,
                                    const std::vector<FeaturePair>& features, const IntersurfaceOptions& options,
                                    const ProgressCallback& progress) {
  const auto start = Clock::now();
  const std::optional<UsedVertices> used_a = drop_unused(a), used_b = drop_unused(b);
  if (used_a || used_b) {
    // The map of the used vertices, then every input vertex's entry from it.
    const auto index = [](const std::optional<UsedVertices>& u, int v) { return u ? u->to_used[u->nearest[v]] : v; };
    check_features(features, a, b);
    std::vector<FeaturePair> used_features;
    for (std::size_t k = 0; k < features.size(); ++k) {
      const FeaturePair& f = features[k];
      using Side = std::tuple<const std::optional<UsedVertices>&, int, const char*>;
      for (const auto& [u, v, name] : {Side{used_a, f.a, "A"}, Side{used_b, f.b, "B"}})
        if (u && u->to_used[v] < 0)
          throw InvalidInput("feature pair " + std::to_string(k) + ": vertex " + std::to_string(v) + " of " + name +
                             " is used by no triangle");
      used_features.push_back({index(used_a, f.a), index(used_b, f.b)});
    }
    IntersurfaceResult r = intersurface_map(used_a ? used_a->mesh : a, used_b ? used_b->mesh : b, used_features,
                                            options, progress);
    const auto expand = [&](const std::optional<UsedVertices>& u, int n, auto& per_vertex) {
      if (!u) return;
      auto compact = per_vertex;
      per_vertex.resize(n);
      for (int v = 0; v < n; ++v) per_vertex[v] = compact[u->to_used[u->nearest[v]]];
    };
    expand(used_a, int(a.vertices.size()), r.a_to_b);
    expand(used_a, int(a.vertices.size()), r.a_on_b);
    expand(used_b, int(b.vertices.size()), r.b_to_a);
    expand(used_b, int(b.vertices.size()), r.b_on_a);
    // Corner images need nothing: the triangles, their order and corners are kept.
    const auto original = [](const std::optional<UsedVertices>& u, int v) {
      return u ? int(std::find(u->to_used.begin(), u->to_used.end(), v) - u->to_used.begin()) : v;
    };
    for (FeaturePair& f : r.features) f = {original(used_a, f.a), original(used_b, f.b)};
    r.seconds = seconds_since(start);
    return r;
  }
  const MeshReport topology_a = checked_topology(a, "A"), topology_b = checked_topology(b, "B");
  const int genus_a = topology_a.genus, genus_b = topology_b.genus;
  if (genus_a != genus_b)
    throw TopologyError("A has genus " + std::to_string(genus_a) + ", B has genus " + std::to_string(genus_b) +
                        "; an inter-surface map needs equal genus");
  // Before either method runs: the sphere's would refuse the holed mesh
  // alone, naming neither the pair nor the counts.
  const int holes_a = topology_a.boundary_loops, holes_b = topology_b.boundary_loops;
  if (holes_a != holes_b)
    throw TopologyError("A has " + std::to_string(holes_a) + (holes_a == 1 ? " hole" : " holes") + ", B has " +
                        std::to_string(holes_b) + "; an inter-surface map needs as many holes on both");
  check_features(features, a, b);
  IntersurfaceResult result;
  result.genus = genus_a;
  result.features = features;
  if (options.restarts < 1) throw InvalidInput("restarts must be at least 1, got " + std::to_string(options.restarts));
  if (options.starts < 1) throw InvalidInput("starts must be at least 1, got " + std::to_string(options.starts));
  if (genus_a > 0 && options.method == IntersurfaceMethod::sphere)
    throw InvalidInput("the sphere method maps genus-0 pairs only; A and B have genus " + std::to_string(genus_a));
  if (genus_a > 0 || options.method == IntersurfaceMethod::partition) {
    map_directly(a, b, result, options, progress);
    result.method = IntersurfaceMethod::partition;
    if (genus_a == 0) result.partition_median_dirichlet = summed_median(result);
    if (progress && !progress(1, "done")) throw Cancelled();
    result.seconds = seconds_since(start);
    return result;
  }
  if (options.grid < 2 || options.grid % 2 != 0)
    throw InvalidInput("grid must be even and at least 2, got " + std::to_string(options.grid));

  // Automatic: the direct map too, side by side with the sphere's (a
  // partition that gets stuck leaves the sphere's map, a sphere that refuses
  // a hole ringed by too few pairs the partition's, which pairs holes itself).
  const auto through_sphere = [&](const ProgressCallback& part) {
    map_through_sphere_restarts(a, b, features, result, options, part);
    result.method = IntersurfaceMethod::sphere;
    result.sphere_median_dirichlet = summed_median(result);
  };
  if (options.method == IntersurfaceMethod::sphere) {
    through_sphere(progress);
  } else {
    IntersurfaceResult direct = result;
    // The direct map takes half the threads (its two sides split them
    // again), the sphere's all: given features, the direct map is spared
    // its screening and the sphere's map outlasts it, then alone (cow -
    // horse with 19 features: 60 -> 69 s with half).
    IntersurfaceOptions halved = options;
    halved.sphere.threads = split_threads(options.sphere.threads)[0];
    const auto [direct_error, sphere_error] = run_side_by_side(
        progress, 0.3, [&](const ProgressCallback& part) { map_directly(a, b, direct, halved, part); },
        through_sphere);
    // Either map kept reports both medians and the sphere's restarts.
    if (!direct_error) result.partition_median_dirichlet = summed_median(direct);
    result.start_median_dirichlet = direct.start_median_dirichlet;
    direct.method = IntersurfaceMethod::partition;
    direct.sphere_median_dirichlet = result.sphere_median_dirichlet;
    direct.partition_median_dirichlet = result.partition_median_dirichlet;
    direct.restart_dirichlet = result.restart_dirichlet;
    direct.restart_median_dirichlet = result.restart_median_dirichlet;
    direct.restart_flipped = result.restart_flipped;
    // A tie goes to the direct map: its paths are shortest on both meshes
    // between corresponding features, and where that costs no more
    // distortion than the sphere's free optimization, the paths hold the
    // map to the truth (21 pairs of sets/cactus and sets/faces, 8-12
    // features, one run each: nearer the truth in 18, as near in 2, 0.03 %
    // farther in 1).
    keep_less_distorted(result, sphere_error, direct, direct_error, a.triangles.size() + b.triangles.size(),
                        /*second_wins_ties=*/true);
  }
  if (progress && !progress(1, "done")) throw Cancelled();
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace cmaps
