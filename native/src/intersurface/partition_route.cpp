#include "intersurface/partition_route.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <numeric>

#include "common/side_by_side.h"
#include "common/stage_clock.h"
#include "consistent_maps/errors.h"
#include "intersurface/consistent_partition.h"
#include "intersurface/cross_patch_optimization.h"
#include "intersurface/farthest_points.h"
#include "intersurface/hole_rims.h"
#include "intersurface/map_choice.h"
#include "intersurface/map_distortion.h"
#include "intersurface/patch_balance.h"
#include "intersurface/patch_map_optimization.h"
#include "intersurface/patch_parameterization.h"
#include "intersurface/path_guide.h"
#include "intersurface/split_triangles.h"
#include "paths/mesh_holes.h"

namespace cmaps {
namespace {

constexpr std::size_t kSphereBasePairs = 4;
constexpr std::size_t kBaseCandidates = 8;  // extremities of B a new pair may take

// A sphere's base needs at least kSphereBasePairs vertices (the issue's
// minimum for genus 0): pairs added to `pairs`, the first (when there is
// none) at A's spread vertex of restart `start`, the others farthest from
// those on A. B's partner is one of B's extremities as farthest-point
// sampling from B's paired vertices finds them (kBaseCandidates of them),
// the one nearest in A's frame as fitted to the pairs so far (PathGuide,
// which turns B onto A's principal axes while the pairs are too few to fix
// a rotation): the plain nearest vertex put a cow's hoof on the horse's
// belly, the legs' lengths differing more than an affine frame follows.
void add_sphere_base_pairs(const TriangleMesh& a, const TriangleMesh& b, int start,
                           std::vector<std::array<int, 2>>& pairs) {
  std::vector<int> seeds_a;
  for (const auto& p : pairs) seeds_a.push_back(p[0]);
  Spread spread_a(a, /*along_edges=*/true);
  while (pairs.size() < kSphereBasePairs) {
    const int next_a = pairs.empty() ? spread_vertex(a, start) : spread_a.next(seeds_a);
    std::vector<Vec3> on_a, on_b;
    std::vector<int> seeds_b;
    for (const auto& p : pairs)
      on_a.push_back(a.vertices[p[0]]), on_b.push_back(b.vertices[p[1]]), seeds_b.push_back(p[1]);
    const std::size_t paired = seeds_b.size();
    if (seeds_b.empty()) seeds_b.push_back(farthest_from_centroid(b));
    Spread spread_b(b, /*along_edges=*/true);
    for (int v = 0; seeds_b.size() < paired + kBaseCandidates && (v = spread_b.next(seeds_b)) >= 0;)
      seeds_b.push_back(v);
    std::vector<Vec3> candidates;
    for (std::size_t k = paired; k < seeds_b.size(); ++k) candidates.push_back(b.vertices[seeds_b[k]]);
    if (next_a < 0 || candidates.empty()) break;
    const PathGuide guide(on_a, on_b, a, b);
    pairs.push_back({next_a, seeds_b[paired + guide.nearest(a.vertices[next_a], candidates)]});
    seeds_a.push_back(next_a);
  }
}

// Genus >= 1: the map through one consistent partition of the closed
// meshes (patch embeddings, their optimization, point location), measured.
void map_partition(ConsistentPartition& partition, const ClosedMesh& closed_a, const ClosedMesh& closed_b,
                   const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                   const IntersurfaceOptions& options, const ProgressCallback& progress) {
  auto stage = Clock::now();
  if (progress && !progress(0, "parameterizing patches")) throw Cancelled();
  PatchParameterization uv_a = parameterize_patches(partition.sides[0], partition);
  const PatchParameterization uv_b = parameterize_patches(partition.sides[1], partition);
  result.seconds_parameterize = seconds_since(stage);

  stage = Clock::now();
  if (progress && !progress(0.3, "optimizing the map")) throw Cancelled();
  const bool optimize = options.optimize_rounds > 0;
  optimize_patch_map(partition.sides[0], uv_a, partition.sides[1], uv_b, optimize ? options.optimize_sweeps : 0,
                     options.sphere.threads, optimize ? kPatchAreaRounds : 0);
  // Then across the paths (cross_patch_optimization.h): A's vertices, then
  // B's against A's embedding as it is then, and so on.
  const bool across_paths = optimize && options.cross_sweeps > 0;
  const int turns = across_paths ? options.cross_turns : 1;
  std::array<GluedEmbedding, 2> glued{glue_patches(partition.sides[0], uv_a), glue_patches(partition.sides[1], uv_b)};
  std::unique_ptr<CrossPatchMap> across;
  for (int turn = 0; turn < turns; ++turn) {
    const int moving = turn % 2;
    across = std::make_unique<CrossPatchMap>(partition, moving, glued[moving], glued[1 - moving]);
    if (across_paths)
      across->optimize(
          options.cross_sweeps,
          [&](double done) {
            return !progress || progress(0.3 + 0.4 * (turn + done) / turns, "optimizing the map across the paths");
          },
          options.sphere.threads);
    glued[moving] = across->moved();
  }
  result.seconds_optimize = seconds_since(stage);

  stage = Clock::now();
  if (progress && !progress(0.7, "locating vertices on the other mesh")) throw Cancelled();
  const int threads = options.sphere.threads;
  const auto convert = [](const std::vector<InputLocation>& located) {
    std::vector<SurfacePoint> points(located.size());
    for (std::size_t i = 0; i < located.size(); ++i) points[i] = {located[i].triangle, located[i].barycentric};
    return points;
  };
  const TriangleMesh &ca = closed_a.mesh, &cb = closed_b.mesh;
  // The surfaces' own points only (no hole centre, no fan corner); none lands in a fan.
  const auto surface_only = [&](std::vector<SurfacePoint> points, std::size_t count, const TriangleMesh& target) {
    points.resize(count);
    for (const SurfacePoint& p : points)
      if (p.triangle >= int(target.triangles.size())) throw Error("internal error: a surface point maps into a hole");
    return points;
  };
  // The last turn's map reads both directions: its moving side's points
  // located on the fixed side, the fixed side's through their hosts.
  const bool b_moved_last = (turns - 1) % 2 == 1;
  const TriangleMesh &moving_input = b_moved_last ? cb : ca, &fixed_input = b_moved_last ? ca : cb;
  std::vector<InputLocation> moving_to_fixed = across->map_a(fixed_input, threads);
  std::vector<InputLocation> fixed_to_moving = across->map_b(moving_input);
  if (b_moved_last) std::swap(moving_to_fixed, fixed_to_moving);
  result.a_to_b = surface_only(convert(moving_to_fixed), a.vertices.size(), b);
  result.b_to_a = surface_only(convert(fixed_to_moving), b.vertices.size(), a);
  if (options.corner_images) {
    std::vector<InputLocation> moving_corners = across->map_a_corners(moving_input, fixed_input, threads);
    std::vector<InputLocation> fixed_corners = across->map_b_corners(moving_input, fixed_input, threads);
    if (b_moved_last) std::swap(moving_corners, fixed_corners);
    result.a_corners_to_b = surface_only(convert(moving_corners), 3 * a.triangles.size(), b);
    result.b_corners_to_a = surface_only(convert(fixed_corners), 3 * b.triangles.size(), a);
  }
  result.a_along_paths = along_paths(partition.sides[0]);
  result.b_along_paths = along_paths(partition.sides[1]);
  result.moved_b = false;  // A's vertices moved first (exchange_sides turns this for a map from B's side)
  result.a_on_b = surface_positions(b, result.a_to_b);
  result.b_on_a = surface_positions(a, result.b_to_a);
  result.seconds_locate = seconds_since(stage);

  stage = Clock::now();
  result.map_flipped = across->turned_triangles() + across->stray_hosts();
  const double facing_ab = facing(ca, cb);
  result.distortion_a_to_b = result.composition_a_to_b = measure_intersurface_map(a, b, result.a_to_b, facing_ab);
  result.distortion_b_to_a = result.composition_b_to_a = measure_intersurface_map(b, a, result.b_to_a, facing_ab);
  result.seconds_measure = seconds_since(stage);
}

// What every start's partitions of a pair share, for both orders of the
// pair: each mesh with its holes closed (checked and fanned once, not per
// start and side: 32 times over feline - teapot's screening), and, for a
// pair given no features and without holes, each mesh's pairless alignment
// onto the other (PathGuide), which picks the partner of a start's vertex.
class PairMeshes {
 public:
  // The pair in one order (first 0: A's paths traced first; 1: B's).
  struct Ordered {
    const TriangleMesh &a, &b;
    const ClosedMesh &closed_a, &closed_b;
    const PathGuide* unpaired;  // null: the starts bring their own pairs (features, holes or genus 0)
  };

  PairMeshes(const TriangleMesh& a, const TriangleMesh& b, const IntersurfaceResult& result)
      : meshes_{&a, &b}, closed_{close_holes(a, /*any_genus=*/true), close_holes(b, /*any_genus=*/true)} {
    if (result.genus > 0 && result.features.empty() && closed_[0].loops.empty())
      unpaired_ = {PathGuide({}, {}, a, b), PathGuide({}, {}, b, a)};
  }

  Ordered order(int first) const {
    return {*meshes_[first], *meshes_[1 - first], closed_[first], closed_[1 - first],
            unpaired_.empty() ? nullptr : &unpaired_[first]};
  }

 private:
  std::array<const TriangleMesh*, 2> meshes_;
  std::array<ClosedMesh, 2> closed_;
  std::vector<PathGuide> unpaired_;  // per order, when used
};

// A pair's consistent partition for the direct map, as traced and with its
// paths moved to balance the patches' areas (`retraced` paths moved).
struct PatchPartitions {
  ConsistentPartition traced, balanced;
  int retraced = 0;
  double seconds_features = 0, seconds_partition = 0;
};

// The partitions of the pair (A's paths traced first). A pair given no
// features and without holes starts from the pair of restart `start`.
PatchPartitions partition_pair(const PairMeshes::Ordered& pair, const IntersurfaceResult& result,
                               const IntersurfaceOptions& options, int start, const ProgressCallback& progress) {
  auto stage = Clock::now();
  const TriangleMesh &a = pair.a, &b = pair.b;
  std::vector<std::array<int, 2>> pairs;
  for (const FeaturePair& f : result.features) pairs.push_back({f.a, f.b});
  // Holes are closed by fans; paths keep cyclic orders by each mesh's own
  // orientation: B is turned like A (its input triangle indices stay, only
  // corner order flips).
  PatchPartitions made;
  const ClosedMesh &closed_a = pair.closed_a, &closed_b = pair.closed_b;
  if (result.genus == 0 && closed_a.loops.empty()) {
    add_sphere_base_pairs(a, b, start, pairs);
  } else if (pairs.empty() && closed_a.loops.empty()) {
    // A's vertex farthest from its centroid (or, restarting, another spread
    // vertex), and B's nearest to it with the centroids and areas matched
    // (meshes posed alike get a matching pair). Holes bring their own pairs
    // on their rims.
    const int far_a = spread_vertex(a, start);
    pairs.push_back({far_a, pair.unpaired->nearest(a.vertices[far_a], b.vertices)});
  }
  TriangleMesh b_like_a = closed_b.mesh;
  const bool turned = facing(closed_a.mesh, closed_b.mesh) < 0;
  if (turned)
    for (Triangle& t : b_like_a.triangles) std::swap(t[1], t[2]);
  PartitionHoles holes;
  if (!closed_a.loops.empty() || !closed_b.loops.empty()) {
    std::vector<Vec3> on_a, on_b;
    for (const auto& p : pairs) on_a.push_back(a.vertices[p[0]]), on_b.push_back(b.vertices[p[1]]);
    holes.rims = pair_hole_rims(closed_a, closed_b, pairs, turned, PathGuide(on_a, on_b, a, b));
    holes.first_fan = {closed_a.input_triangles, closed_b.input_triangles};
    for (const HoleRim& rim : holes.rims) {
      for (const auto& f : rim.features)
        if (std::find(pairs.begin(), pairs.end(), f) == pairs.end()) pairs.push_back(f);
      pairs.push_back(rim.centre);
    }
  }
  made.seconds_features = seconds_since(stage);

  stage = Clock::now();
  if (progress && !progress(0.05, "partitioning")) throw Cancelled();
  made.traced = consistent_partition(closed_a.mesh, b_like_a, pairs, result.genus, holes);
  // Balancing is an improvement the traced partition can do without: if it fails, that serves.
  made.balanced = made.traced;
  try {
    made.retraced = balance_patch_areas(made.balanced, options.balance_rounds).retraced;
  } catch (const Error&) {
    // retraced stays 0: the partition as traced serves
  }
  made.seconds_partition = seconds_since(stage);
  return made;
}

// A side's partitions for the direct map (see partition_pair), and which of
// them a map kept: -1 before any, 0 the traced, 1 the balanced (the other
// one is then let go).
struct SidePartitions {
  std::shared_ptr<PatchPartitions> made;
  int kept = -1;
};

// The direct map through a consistent partition (every pair of genus >= 1;
// genus 0 on request or to compare with the sphere): through the partition
// as traced and through the balanced one (when any path moved), the lower
// summed median distortion kept, as for genus 0's restarts; through the
// balanced one alone when the traced one is too unbalanced
// (IntersurfaceOptions::max_traced_ratio). With `side`,
// the pair's partitions from `start` are taken from there, or traced and
// left there when it holds none; the maps refine copies of them while the
// screening will map them again, else the partitions themselves. Once a map
// through both kept one (side->kept), only that one is mapped: the
// screening's maps, without sweeps, pick the one the optimized maps would
// (on all 43 sides of 22 unfeatured pairs measured; on fertility's stretched
// copy it picks the other, whose optimized median lies within
// less_distorted's 5 % of the one kept before, BENCHMARKS.md), and each
// optimized map costs as much as the screening of a start (feline - teapot:
// 14-22 s without the balancing, 30-33 s with it).
void map_through_patches(const PairMeshes::Ordered& pair, IntersurfaceResult& result,
                         const IntersurfaceOptions& options, int start, const ProgressCallback& progress,
                         SidePartitions* side = nullptr) {
  const TriangleMesh &a = pair.a, &b = pair.b;
  SidePartitions own;  // without `side`: nothing reuses the partitions, so the maps take them
  const bool reused = side != nullptr;
  if (!side) side = &own;
  if (!side->made)
    side->made = std::make_shared<PatchPartitions>(partition_pair(pair, result, options, start, progress));
  PatchPartitions& made = *side->made;
  const ClosedMesh &closed_a = pair.closed_a, &closed_b = pair.closed_b;
  const int given = int(result.features.size()), retraced = made.retraced;
  result.seconds_features = made.seconds_features;
  result.seconds_partition = made.seconds_partition;
  ConsistentPartition partition;  // the one the map kept, as the map refined it
  // The map through the balanced partition, into `moved`: false when it fails.
  const auto map_balanced = [&](ConsistentPartition& balanced, IntersurfaceResult& moved, double from) {
    try {
      map_partition(balanced, closed_a, closed_b, a, b, moved, options, slice(progress, from, 1));
      return true;
    } catch (const Cancelled&) {
      throw;
    } catch (const Error&) {
      return false;
    }
  };
  // The screening maps them again for the start it keeps; every other map can take them.
  const bool mapped_again = reused && side->kept < 0;
  const auto take = [&](ConsistentPartition& p) { return mapped_again ? p : std::move(p); };
  // The balanced partition alone once a map kept it, or when the traced one
  // is too unbalanced to compete.
  const bool balanced_only = retraced > 0 && (side->kept == 1 || (side->kept < 0 && patch_area_ratio(made.traced) >
                                                                                          options.max_traced_ratio));
  bool kept_balanced = false;
  if (balanced_only) {
    IntersurfaceResult moved = result;
    ConsistentPartition balanced = take(made.balanced);
    if (map_balanced(balanced, moved, 0.6)) {
      result = std::move(moved);
      partition = std::move(balanced);
      kept_balanced = true;
    } else if (made.traced.sides.empty()) {
      made = partition_pair(pair, result, options, start, progress);  // the traced partition, let go before, serves
    }
  }
  if (!kept_balanced) {
    const bool both = retraced > 0 && side->kept < 0 && !balanced_only;
    partition = take(made.traced);
    result.patch_area_ratio = patch_area_ratio(partition);
    map_partition(partition, closed_a, closed_b, a, b, result, options, slice(progress, 0.6, both ? 0.8 : 1));
    if (both) {
      IntersurfaceResult moved = result;
      ConsistentPartition balanced = take(made.balanced);
      const bool mapped = map_balanced(balanced, moved, 0.8);
      kept_balanced = mapped && less_distorted(moved, result, a.triangles.size() + b.triangles.size());
      // Both maps share the partition and features: their times count once.
      IntersurfaceResult& kept = kept_balanced ? moved : result;
      const double partition_seconds = kept.seconds_partition, feature_seconds = kept.seconds_features;
      add_stage_seconds(kept, kept_balanced ? result : moved);
      kept.seconds_partition = partition_seconds, kept.seconds_features = feature_seconds;
      if (kept_balanced) result = std::move(moved), partition = std::move(balanced);
    }
  }
  if (kept_balanced) {
    result.balanced_patches = true;
    result.patch_area_ratio = patch_area_ratio(partition);
  }
  side->kept = kept_balanced;
  (kept_balanced ? made.traced : made.balanced) = ConsistentPartition();

  const std::vector<int>&fa = partition.sides[0].feature_vertex, &fb = partition.sides[1].feature_vertex;
  result.features.clear();
  for (std::size_t k = 0; k < fa.size(); ++k)
    if (int(k) < given || (fa[k] < int(a.vertices.size()) && fb[k] < int(b.vertices.size())))
      result.features.push_back({fa[k], fb[k]});
  result.added_features = int(result.features.size()) - given;
  result.base_vertices = int(fa.size());
  result.base_triangles = int(partition.triangles.size());
  result.steiner_a = partition.sides[0].mesh.vertex_count() - int(closed_a.mesh.vertices.size());
  result.steiner_b = partition.sides[1].mesh.vertex_count() - int(closed_b.mesh.vertices.size());
}

// The partitions of one start from both sides (see map_through_patches).
struct StartPartitions {
  int start = -1;
  std::array<SidePartitions, 2> sides;  // from A's side, from B's side
};

// Per start tried: the start, both directions' summed mean and median,
// folds, and the side its map kept (0: traced and optimized from A's side,
// 1: from B's).
struct StartTrials {
  std::vector<int> starts;
  std::vector<double> energies, medians;
  std::vector<int> folds, sides;
};

// Direct maps from each of `starts` (see map_through_patches), each traced
// and optimized from A's side and from B's side, the less distorted kept:
// the partition is traced on A first and A's embedding moves against B's,
// so the two differ (sets/cactus 2 -> 0, 10 features: 1.1 % off the truth
// one way, 0.6 % the other), and the map kept does not depend on which mesh
// is called A. The least distorted start is kept in `result` and each one's
// summed mean, median and folds appended to `tried` (in order, with its
// start). `sides`, when given, names per start the one side to map
// (-1: both). A start whose sides all fail is skipped; when all fail, the
// first error is thrown. `partitions` holds the partitions of its start when that
// is among `starts` (they are not traced again), and is left holding those
// of the start kept (null: no partitions are kept).
//
// The sides of all starts queue for the threads (each side's own loops get
// an equal share of them), so a side that ends early does not leave its
// core idle until its partner ends (feline - teapot's sides took 7.4-12.4 s,
// and a core idled about 7 s over the 8 starts).
// Each start is judged, in order, as soon as both its sides are done; only
// the best so far is kept, so memory holds a few maps and not one per start.
void map_directly_best_of(const PairMeshes& pair, IntersurfaceResult& result, const IntersurfaceOptions& options,
                          const std::vector<int>& starts, StartTrials& tried, StartPartitions* partitions,
                          const ProgressCallback& progress, const std::vector<int>& sides = {}) {
  const PairMeshes::Ordered forward = pair.order(0), backward = pair.order(1);
  const std::size_t samples = forward.a.triangles.size() + forward.b.triangles.size();
  struct Start {
    std::array<IntersurfaceResult, 2> sides;  // traced on A first, on B first
    std::array<std::exception_ptr, 2> thrown;
    StartPartitions made;
    int only = -1;  // the one side mapped, -1: both
    int ended = 0;
  };
  std::vector<Start> trial(starts.size());
  std::vector<std::array<int, 2>> tasks;  // start, side
  for (std::size_t k = 0; k < starts.size(); ++k) {
    trial[k].sides = {result, result};
    exchange_sides(trial[k].sides[1]);
    trial[k].made = partitions && partitions->start == starts[k] ? *partitions : StartPartitions{starts[k], {}};
    trial[k].only = sides.empty() ? -1 : sides[k];
    for (int s = 0; s < 2; ++s)
      if (trial[k].only < 0 || trial[k].only == s) tasks.push_back({int(k), s});
  }
  const int count = int(tasks.size());
  // At least two when there are two: the sides of one start always ran side by side.
  const int workers = std::max(std::min(2, count), std::min(options.sphere.threads, count));
  IntersurfaceOptions own = options;
  own.sphere.threads = std::max(1, options.sphere.threads / workers);

  IntersurfaceResult best;
  std::exception_ptr error;
  bool found = false;
  StartPartitions kept;
  std::size_t judged = 0;
  const auto judge = [&](Start& start) {
    IntersurfaceResult &map = start.sides[0], &backward = start.sides[1];
    if (start.only != 0 && !start.thrown[1]) exchange_sides(backward);  // side 1 mapped: back to A -> B
    try {
      if (start.only < 0) {
        keep_less_distorted(map, start.thrown[0], backward, start.thrown[1], samples);
      } else {
        if (start.thrown[start.only]) std::rethrow_exception(start.thrown[start.only]);
        if (start.only == 1) map = std::move(backward);
      }
    } catch (const Cancelled&) {
      throw;
    } catch (const Error&) {
      if (!error) error = std::current_exception();
      return;
    }
    tried.starts.push_back(start.made.start);
    tried.energies.push_back(map.distortion_a_to_b.symmetric_dirichlet + map.distortion_b_to_a.symmetric_dirichlet);
    tried.medians.push_back(summed_median(map));
    tried.folds.push_back(summed_folds(map));
    tried.sides.push_back(map.moved_b);
    if (!found || less_distorted(map, best, samples)) best = std::move(map), kept = std::move(start.made);
    found = true;
  };
  const auto side = [&](Start& start, int k) { return partitions ? &start.made.sides[k] : nullptr; };
  const auto thrown = run_tasks(
      progress, std::vector<double>(count, 1.0 / count), workers,
      [&](int task, const ProgressCallback& part) {
        const auto [k, s] = tasks[task];
        Start& start = trial[k];
        map_through_patches(s == 0 ? forward : backward, start.sides[s], own, start.made.start, part, side(start, s));
      },
      [&](int task, const std::exception_ptr& thrown) {
        const auto [k, s] = tasks[task];
        trial[k].thrown[s] = thrown;
        ++trial[k].ended;
        const auto done = [](const Start& start) { return start.ended == (start.only < 0 ? 2 : 1); };
        for (; judged < trial.size() && done(trial[judged]); ++judged) {
          judge(trial[judged]);
          trial[judged] = Start();  // its maps and partitions are no longer needed
        }
      });
  for (const std::exception_ptr& e : thrown) failed_with_error(e);  // rethrows a cancellation or failure
  if (!found) std::rethrow_exception(error);
  result = std::move(best);
  if (partitions) *partitions = std::move(kept);
}

}  // namespace

void map_directly(const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                  const IntersurfaceOptions& options, const ProgressCallback& progress) {
  const PairMeshes pair(a, b, result);
  // Both have as many holes (intersurface_map checked).
  const bool automatic = result.features.empty() && pair.order(0).closed_a.loops.empty();
  if (!automatic) {
    StartTrials ignored;
    map_directly_best_of(pair, result, options, {0}, ignored, nullptr, progress);
    return;
  }
  const std::size_t samples = a.triangles.size() + b.triangles.size();
  std::vector<int> starts(std::max(options.starts, options.restarts));
  std::iota(starts.begin(), starts.end(), 0);
  StartTrials screened;
  StartPartitions partitions;  // the screened start kept: its optimization does not trace them again
  std::vector<int> sides;      // per start optimized: the side its screened map kept
  double screening = 0;
  if (options.optimize_rounds > 0 && int(starts.size()) > options.restarts) {
    // Screened with the patches' areas matched to the other mesh's (the
    // global step of optimize_patch_map) but without the local sweeps: the
    // plain embeddings rank by how the patches' areas happen to match, which
    // the optimization then evens out (cow - horse: the start least
    // distorted unoptimized ends at summed median 12.90, the one least
    // distorted once the areas are matched at 10.92, the best of the eight).
    IntersurfaceOptions quick = options;
    quick.optimize_sweeps = 0;
    quick.cross_sweeps = 0;
    IntersurfaceResult ignored = result;
    screening = 0.4;
    map_directly_best_of(pair, ignored, quick, starts, screened, &partitions, slice(progress, 0, screening));
    // The least distorted of those left, options.restarts times (the tie
    // rule is no ordering to sort by), each optimized from the side its
    // screened map kept: the optimized maps rank the sides alike (21 of the
    // 22 unfeatured pairs of BENCHMARKS.md, session 52; torus - elk's other
    // side ends 5 % less distorted), and one side takes both threads instead
    // of each side one.
    std::vector<int> left(screened.starts.size());
    std::iota(left.begin(), left.end(), 0);
    starts.clear();
    while (int(starts.size()) < options.restarts && !left.empty()) {
      auto best = left.begin();
      for (auto k = left.begin(); k != left.end(); ++k)
        if (less_distorted(screened.medians[*k], screened.folds[*k], screened.medians[*best], screened.folds[*best],
                           samples))
          best = k;
      starts.push_back(screened.starts[*best]);
      sides.push_back(screened.sides[*best]);
      left.erase(best);
    }
    if (!sides.empty() && partitions.start == starts[0]) partitions.sides[1 - sides[0]] = SidePartitions();
  }
  StartTrials optimized;
  map_directly_best_of(pair, result, options, starts, optimized, &partitions, slice(progress, screening, 1), sides);
  result.start_median_dirichlet = screened.medians;
  if (optimized.starts.size() > 1) {
    result.restart_dirichlet = std::move(optimized.energies);
    result.restart_median_dirichlet = std::move(optimized.medians);
    result.restart_flipped = std::move(optimized.folds);
  }
}

}  // namespace cmaps
