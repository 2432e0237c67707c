#include "consistent_maps/consistent_parameterization.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <set>
#include <string>

#include "common/stage_clock.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/octahedral_grid.h"
#include "consistent_maps/remesh.h"
#include "consistent_maps/sphere_locator.h"
#include "consistent_maps/spherical_parameterization.h"
#include "consistent/member_alignment.h"
#include "consistent/parameterize_with_reference.h"
#include "paths/mesh_holes.h"
#include "sphere/consistent_constrained_parameterization.h"

namespace cmaps {
namespace {

// The features a member has, with their indices into the feature list.
struct PresentFeatures {
  std::vector<int> vertices;
  std::vector<int> names;
};

PresentFeatures present(const ConsistentMember& member) {
  PresentFeatures p;
  for (int k = 0; k < static_cast<int>(member.features.size()); ++k)
    if (member.features[k] >= 0) {
      p.vertices.push_back(member.features[k]);
      p.names.push_back(k);
    }
  return p;
}

void validate(const std::vector<ConsistentMember>& members, const ConsistentOptions& options) {
  if (members.size() < 2) throw InvalidInput("a consistent set needs at least 2 meshes");
  const size_t k = members.front().features.size();
  for (size_t i = 0; i < members.size(); ++i) {
    const auto& m = members[i];
    if (m.features.size() != k)
      throw InvalidInput("mesh " + std::to_string(i) + " lists " + std::to_string(m.features.size()) +
                         " features, mesh 0 lists " + std::to_string(k));
    for (int v : m.features)
      if (v < -1 || v >= static_cast<int>(m.mesh.vertices.size()))
        throw InvalidInput("mesh " + std::to_string(i) + ": feature vertex " + std::to_string(v) +
                           " is out of range (mesh has " + std::to_string(m.mesh.vertices.size()) + " vertices)");
    if (present(m).vertices.size() < 3)
      throw InvalidInput("mesh " + std::to_string(i) + " has fewer than 3 of the features");
  }
  // Holes (thesis 3.5): the same features must ring corresponding holes on
  // every member.
  std::vector<std::set<std::vector<int>>> rings(members.size());
  for (size_t i = 0; i < members.size(); ++i) {
    const ClosedMesh closed = close_holes(members[i].mesh);
    for (std::vector<int> ring : hole_features(closed, members[i].features, "mesh " + std::to_string(i) + ": ")) {
      std::sort(ring.begin(), ring.end());
      rings[i].insert(ring);
    }
  }
  auto names = [](const std::vector<int>& ring) {
    std::string s;
    for (int f : ring) s += (s.empty() ? "" : ", ") + std::to_string(f);
    return s;
  };
  for (size_t i = 0; i < members.size(); ++i)
    for (size_t j = 0; j < members.size(); ++j)
      for (const auto& ring : rings[i])
        if (!rings[j].count(ring))
          throw InvalidInput("features " + names(ring) + " ring a hole on mesh " + std::to_string(i) +
                             " but not on mesh " + std::to_string(j) +
                             "; the same features must ring corresponding holes on every mesh");
  if (options.first >= static_cast<int>(members.size())) throw InvalidInput("first member out of range");
}

int choose_first(const std::vector<ConsistentMember>& members, int requested) {
  auto complete = [](const ConsistentMember& m) { return present(m).vertices.size() == m.features.size(); };
  if (requested >= 0) {
    if (!complete(members[requested]))
      throw InvalidInput("mesh " + std::to_string(requested) + " lacks some features; it cannot seed the set");
    return requested;
  }
  for (size_t i = 0; i < members.size(); ++i)
    if (complete(members[i])) return static_cast<int>(i);
  throw InvalidInput("no mesh has every feature; one must, to seed the feature locations");
}

// The same mesh facing outwards (judged with its holes closed), so that maps
// of all members turn alike.
TriangleMesh outward(const TriangleMesh& mesh) {
  TriangleMesh m = mesh;
  if (signed_volume(close_holes(mesh).mesh) < 0)
    for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

}  // namespace

ParameterizedSurface parameterized_surface(const TriangleMesh& mesh, const ConstrainedResult& map,
                                          bool close_holes) {
  ParameterizedSurface p;
  p.surface.vertices = mesh.vertices;
  p.surface.triangles = map.triangles;
  p.sphere = map.sphere;
  for (const SteinerVertex& s : map.steiner) {
    Vec3 x = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (s.vertices[k] >= 0) x += s.weights[k] * mesh.vertices[s.vertices[k]];
    p.surface.vertices.push_back(x);
    p.sphere.push_back(s.sphere);
  }
  if (close_holes) {
    for (int h = 0; h < map.holes; ++h) {
      p.surface.vertices.push_back(map.hole_centres_position[h]);
      p.sphere.push_back(map.hole_centres_sphere[h]);
    }
    p.surface.triangles.insert(p.surface.triangles.end(), map.hole_triangles.begin(), map.hole_triangles.end());
  }
  return p;
}

ConstrainedResult parameterize_to_locations(const ConsistentMember& member, const std::vector<Vec3>& locations,
                                            const SphereOptions& options, const ProgressCallback& progress) {
  return parameterize_to_locations(member, locations, options, progress, ReferenceMap{});
}

ConstrainedResult parameterize_to_locations(const ConsistentMember& member, const std::vector<Vec3>& locations,
                                            const SphereOptions& options, const ProgressCallback& progress,
                                            const ReferenceMap& reference, const std::vector<Vec3>* guide) {
  if (locations.size() != member.features.size())
    throw InvalidInput("got " + std::to_string(locations.size()) + " locations for " +
                       std::to_string(member.features.size()) + " features");
  const PresentFeatures p = present(member);
  std::vector<Vec3> targets;
  for (int k : p.names) targets.push_back(locations[k]);
  // Every member of a set faces outwards, so that their maps turn alike.
  return constrained_spherical_parameterization(outward(member.mesh), p.vertices, targets, options, progress, reference,
                                               guide);
}

namespace {

// Each member's own quick unconstrained map: what a constrained map lays its
// paths out in by default (constrained_parameterization.cpp), computed once
// for all of a run's constrained maps.
struct OwnMap {
  std::vector<Vec3> sphere;
  double efficiency = 0;
};

// Steps 1-6 once, with options.sphere's seed.
ConsistentResult consistent_run(const std::vector<ConsistentMember>& members, const ConsistentOptions& options,
                                const std::vector<OwnMap>& own, const ProgressCallback& progress) {
  const int n = static_cast<int>(members.size());
  ConsistentResult result;
  result.first = choose_first(members, options.first);
  const bool carry = options.carry_guides;
  const int rounds = carry ? 2 : 1;  // of steps 3-6
  // Progress: one share per map computed (the seed, n maps of step 2, per
  // round the common map and one map per member, and the last round's
  // second map per member).
  const double share = 1.0 / (1 + n + rounds * (1 + n) + (carry ? n : 0));
  int maps_done = 0;
  auto next_share = [&]() {
    ++maps_done;
    return slice(progress, (maps_done - 1) * share, maps_done * share);
  };

  // 1. Initial locations from the first member alone.
  const ConsistentMember& first = members[result.first];
  const SphereResult seed =
      spherical_parameterization(close_holes(outward(first.mesh)).mesh, options.sphere, next_share());
  for (int v : first.features) result.initial_locations.push_back(seed.sphere[v]);

  SphereOptions quick = options.sphere;
  quick.effort = 0;
  const auto own_guide = [&](int i) { return carry ? &own[i].sphere : nullptr; };  // null: computed inside

  // 2. Every member mapped to them (quickly: the maps before the last round
  // only carry the correspondence to the next).
  std::vector<ConstrainedResult> maps;
  for (int i = 0; i < n; ++i)
    maps.push_back(parameterize_to_locations(members[i], result.initial_locations, carry ? quick : options.sphere,
                                             next_share(), ReferenceMap{}, own_guide(i)));

  // Steps 3-6, twice: the second round remeshes along the maps of the first,
  // which already fit common locations and wind alike (below).
  const OctahedralGrid grid = octahedral_grid(options.grid);
  std::vector<Vec3> locations = result.initial_locations;
  for (int round = 0; round < rounds; ++round) {
    // 3. Every member sampled on one grid, the features snapped to samples.
    std::vector<Vec3> samples = grid.sphere;
    const std::vector<int> feature_samples = snap_features(samples, locations);
    std::vector<std::vector<Vec3>> shapes;
    for (int i = 0; i < n; ++i) {
      // Holes are sampled on their temporary fans, so every grid sample has a position.
      const ParameterizedSurface p = parameterized_surface(members[i].mesh, maps[i], true);
      shapes.push_back(resample(p.surface, p.sphere, samples, options.sphere.threads));
    }

    // 4-5. The grid carrying every shape: its map places the features.
    const SphereResult common = spherical_parameterization(grid.triangles, shapes, options.sphere, next_share());
    locations.clear();
    for (int s : feature_samples) locations.push_back(common.sphere[s]);

    // 6. Maps to those locations. A constrained map keeps the way its guide
    // winds around the features. Each member's guide is its current map
    // carried through the common map (each current sphere point to where the
    // grid's map puts it), which winds like the common map that suits every
    // member; a member's own unconstrained map, the default guide, often
    // winds otherwise when its feature layout is far from the common one
    // (cactus, cat-lion). A carried guide inherits the current map's flaws,
    // so the own guide is tried too, the more efficient map kept: in the
    // last round always, before only when the carried one is less efficient
    // than the member's current map.
    if (!carry) {
      for (int i = 0; i < n; ++i)
        maps[i] = parameterize_to_locations(members[i], locations, options.sphere, next_share());
      break;
    }
    const SphereLocator grid_locator(samples, grid.triangles);
    for (int i = 0; i < n; ++i) {
      std::vector<Vec3> directions = maps[i].sphere;
      directions.insert(directions.end(), maps[i].hole_centres_sphere.begin(), maps[i].hole_centres_sphere.end());
      std::vector<Vec3> carried = grid_locator.interpolate(
          common.sphere, grid_locator.locate_all(directions, options.sphere.threads), options.sphere.threads);
      for (Vec3& g : carried) g.normalize();
      const bool last = round + 1 == rounds;
      const SphereOptions& round_options = last ? options.sphere : quick;
      ConstrainedResult map = parameterize_to_locations(members[i], locations, round_options, next_share(),
                                                        ReferenceMap{}, &carried);
      if (last || map.report.efficiency < maps[i].report.efficiency) {
        ConstrainedResult along_own = parameterize_to_locations(members[i], locations, round_options,
                                                                last ? next_share() : ProgressCallback{},
                                                                ReferenceMap{}, &own[i].sphere);
        if (along_own.report.efficiency > map.report.efficiency) map = std::move(along_own);
      }
      maps[i] = std::move(map);
    }
  }
  result.feature_locations = std::move(locations);
  result.members = std::move(maps);
  return result;
}

// How well a run suits every member: the mean of its maps' efficiencies over
// the members' own. A set whose maps wind wrongly around the features for
// some member (a twisted arm) loses efficiency there, so this ranks runs
// nearly like their correspondence error does.
double suitability(const ConsistentResult& run, const std::vector<double>& own_efficiency) {
  double sum = 0;
  for (size_t i = 0; i < own_efficiency.size(); ++i)
    sum += run.members[i].report.efficiency / std::max(own_efficiency[i], 1e-12);
  return sum / double(own_efficiency.size());
}

}  // namespace

ConsistentResult consistent_spherical_parameterization(const std::vector<ConsistentMember>& members,
                                                       const ConsistentOptions& options,
                                                       const ProgressCallback& progress) {
  validate(members, options);
  const auto start = std::chrono::steady_clock::now();
  const int n = static_cast<int>(members.size()), restarts = std::max(1, options.restarts);
  const bool have_own = options.carry_guides || restarts > 1;
  std::vector<double> own_efficiency;  // of the first run's own maps: one yardstick for every run
  std::vector<double> scores;
  ConsistentResult best;
  const double span = options.align ? 0.8 : 1;  // of the progress, before step 7
  for (int k = 0; k < restarts; ++k) {
    ConsistentOptions run_options = options;
    run_options.sphere.seed = options.sphere.seed + std::uint64_t(k);
    // The own maps differ by seed, and so do the paths laid out along them.
    std::vector<OwnMap> own(n);
    for (int i = 0; i < n && have_own; ++i) {
      SphereOptions quick = run_options.sphere;
      quick.effort = 0;
      SphereResult r = spherical_parameterization(close_holes(outward(members[i].mesh)).mesh, quick);
      own[i] = {std::move(r.sphere), r.report.efficiency};
      if (k == 0) own_efficiency.push_back(r.report.efficiency);
    }
    ConsistentResult run = consistent_run(members, run_options, own, slice(progress, span * k / restarts,
                                                                           span * (k + 1) / restarts));
    run.suitability = have_own ? suitability(run, own_efficiency) : 0;
    scores.push_back(run.suitability);
    if (k == 0 || run.suitability > best.suitability) best = std::move(run), best.restart = k;
  }
  best.restart_suitability = std::move(scores);
  if (options.align) align_members(members, best, options, slice(progress, 0.8, 1));
  best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return best;
}


namespace {

// A hole of every member is the spherical polygon of its features' common
// locations, bounded by great-circle arcs that map onto the hole's boundary
// on every member. Samples just outside a hole move to the nearest point of
// these arcs, so the remeshes end on the boundary itself rather than on a
// staircase of grid edges (features stay put).
void snap_to_hole_boundaries(ConsistentRemesh& remesh, const std::vector<std::array<Vec3, 2>>& arcs) {
  if (arcs.empty()) return;
  std::vector<char> rim(remesh.sphere.size(), 0), feature(remesh.sphere.size(), 0);
  for (int v : remesh.feature_vertices) feature[v] = 1;
  for (const Triangle& t : remesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (remesh.in_hole[t[k]])
        for (int j : {1, 2})
          if (!remesh.in_hole[t[(k + j) % 3]]) rim[t[(k + j) % 3]] = 1;
  for (size_t s = 0; s < rim.size(); ++s) {
    if (!rim[s] || feature[s]) continue;
    const Vec3 x = remesh.sphere[s];
    Vec3 nearest = x;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : arcs) {
      const Vec3 normal = a.cross(b).normalized();
      Vec3 p = (x - x.dot(normal) * normal).normalized();
      if (a.cross(p).dot(normal) < 0 || p.cross(b).dot(normal) < 0) p = (x - a).norm() < (x - b).norm() ? a : b;
      if ((p - x).norm() < best) best = (p - x).norm(), nearest = p;
    }
    remesh.sphere[s] = nearest;
  }
}

}  // namespace

ConsistentRemesh consistent_remesh(const std::vector<ConsistentMember>& members, const ConsistentResult& result,
                                   int n, int threads) {
  if (members.size() != result.members.size()) throw InvalidInput("members do not match the computed set");
  const OctahedralGrid grid = octahedral_grid(n);
  ConsistentRemesh remesh;
  remesh.sphere = grid.sphere;
  remesh.triangles = grid.triangles;
  remesh.feature_vertices = snap_features(remesh.sphere, result.feature_locations);
  remesh.in_hole.assign(remesh.sphere.size(), 0);
  std::vector<ParameterizedSurface> surfaces;
  std::vector<std::array<Vec3, 2>> arcs;  // hole boundaries on the sphere
  for (size_t i = 0; i < members.size(); ++i) {
    const ConstrainedResult& map = result.members[i];
    surfaces.push_back(parameterized_surface(members[i].mesh, map, true));
    if (map.holes == 0) continue;
    // Samples on the temporary fans lie in a hole of this member.
    const ParameterizedSurface& p = surfaces.back();
    const SphereLocator locator(p.sphere, p.surface.triangles);
    const auto at = locator.locate_all(remesh.sphere, threads);
    const int real = static_cast<int>(map.triangles.size());
    for (size_t s = 0; s < at.size(); ++s)
      if (at[s].triangle >= real) remesh.in_hole[s] = 1;
    const std::vector<int> names = present(members[i]).names;  // hole_features index the member's own features
    for (const std::vector<int>& ring : map.hole_features)
      for (size_t k = 0; k < ring.size(); ++k)
        arcs.push_back({result.feature_locations[names[ring[k]]],
                        result.feature_locations[names[ring[(k + 1) % ring.size()]]]});
  }
  // Features on a hole boundary are where they belong, not in the hole.
  for (int v : remesh.feature_vertices) remesh.in_hole[v] = 0;
  snap_to_hole_boundaries(remesh, arcs);
  for (const ParameterizedSurface& p : surfaces)
    remesh.positions.push_back(resample(p.surface, p.sphere, remesh.sphere, threads));
  std::vector<Triangle> kept;
  for (const Triangle& t : remesh.triangles)
    if (!remesh.in_hole[t[0]] && !remesh.in_hole[t[1]] && !remesh.in_hole[t[2]]) kept.push_back(t);
  remesh.triangles = std::move(kept);
  return remesh;
}

}  // namespace cmaps
