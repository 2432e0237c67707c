#include "intersurface/patch_map_optimization.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/parallel_for.h"
#include "intersurface/patch_embedding.h"
#include "intersurface/patch_energy.h"

namespace cmaps {
namespace {

constexpr int kHalvings = 10;  // path slides' line search: step, step / 2, ...

// A vertex inside a path, between the two patches beside it: it slides
// along the path (both patches' canonical edge, the same fraction of it in
// each), between its path neighbours, so the map along paths is optimized
// too and not left at arc length.
struct PathSlide {
  int vertex, previous, next;
  int patches[2];
};

std::vector<PathSlide> path_slides(const PartitionSide& side) {
  std::vector<PathSlide> slides;
  for (const auto& path : side.paths)
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      PathSlide slide{path[i], path[i - 1], path[i + 1], {-1, -1}};
      for (int f : side.mesh.faces_of(slide.vertex)) {
        const int t = side.patch[f];
        if (slide.patches[0] < 0) slide.patches[0] = t;
        else if (t != slide.patches[0]) slide.patches[1] = t;
      }
      // A path with one patch on both sides has no second chart to slide in.
      if (slide.patches[1] >= 0) slides.push_back(slide);
    }
  return slides;
}

// One descent step of a path vertex in its fraction along the path: central
// differences, halving line search, both patches' energies summed.
bool slide(const PathSlide& s, PatchEnergy& first, PatchEnergy& second) {
  PatchEnergy* energy[2] = {&first, &second};
  if (!first.movable(s.vertex) || !second.movable(s.vertex)) return false;
  const Vec2 &a = first.uv().at(s.previous), &b = first.uv().at(s.next);
  const double at = (first.uv().at(s.vertex) - a).dot(b - a) / (b - a).squaredNorm();
  const PatchEnergy::Hosted inside[2] = {first.hosted(s.vertex), second.hosted(s.vertex)};
  const auto trials = [&](double fraction) {
    std::array<PatchEnergy::Move, 2> moves;
    for (int k = 0; k < 2; ++k) {
      const Vec2 &p = energy[k]->uv().at(s.previous), &q = energy[k]->uv().at(s.next);
      moves[k] = energy[k]->trial(s.vertex, p + fraction * (q - p), inside[k]);
    }
    return moves;
  };
  const auto total = [](const std::array<PatchEnergy::Move, 2>& moves) { return moves[0].energy + moves[1].energy; };
  const double current = total(trials(at));
  if (!std::isfinite(current)) return false;
  constexpr double h = 1e-4;
  const double plus = total(trials(at + h)), minus = total(trials(at - h));
  if (!std::isfinite(plus) || !std::isfinite(minus) || plus == minus) return false;
  const double direction = plus < minus ? 1 : -1;
  double step = 0.25;
  for (int k = 0; k < kHalvings; ++k, step *= 0.5) {
    const auto moves = trials(at + direction * step);
    if (total(moves) < current) {
      for (int j = 0; j < 2; ++j) energy[j]->apply(s.vertex, moves[j]);
      return true;
    }
  }
  return false;
}

// The global step before the local sweeps, which move one vertex at a time
// and so barely spread a region the map squeezes as a whole (a protrusion of
// the source onto a small part of the target). The patch's interior is
// embedded again and again, each weight scaled by the root of the map's area
// ratio at the neighbour it points to (stretch reweighting, Yoshizawa et al.
// 2004, with the target's area pulled back instead of the source's own):
// where the target gets too little area, the neighbours pull less and the
// region opens up. Weights stay positive, so each embedding is bijective;
// each round is kept only if it lowers both directions' energy.
void match_target_areas(const PartitionSide& source, const std::vector<int>& faces, const std::vector<char>& on_path,
                        std::unordered_map<int, Vec2>& uv, const std::unordered_map<int, double>& pull,
                        int rounds, PatchEnergy& energy) {
  if (rounds <= 0) return;
  std::unordered_map<int, Vec2> points;
  for (const auto& [v, p] : uv)
    if (on_path[v]) points.emplace(v, p);
  PatchEmbedding embedding(source, faces, points);
  if (embedding.empty()) return;
  PatchEmbedding::Weights weight = embedding.mean_value_weights();
  for (auto& row : weight)
    for (auto& [u, w] : row) w *= pull.at(u);
  double ignored = 0, best = energy.total(ignored);
  for (int round = 0; round < rounds; ++round) {
    const std::unordered_map<int, double> ratio = energy.area_ratios();
    bool lowered = false;
    // The ratio's root first, then its fourth and eighth: a full step can overshoot.
    for (double power = 0.5; power > 0.1 && !lowered; power *= 0.5) {
      PatchEmbedding::Weights next_weight = weight;
      for (auto& row : next_weight)
        for (auto& [u, w] : row) w *= std::pow(ratio.at(u), power);
      embedding.solve(next_weight);
      std::unordered_map<int, Vec2> kept = uv;
      uv = points;
      energy.reembed();
      const double e = energy.total(ignored);
      if (e < best)
        best = e, weight = std::move(next_weight), lowered = true;
      else
        uv = std::move(kept);  // the energy follows once no smaller step is left to try
    }
    if (!lowered) {
      energy.reembed();
      return;
    }
  }
}

}  // namespace

MapOptimization optimize_patch_map(const PartitionSide& source, PatchParameterization& source_uv,
                                   const PartitionSide& target, const PatchParameterization& target_uv,
                                   int sweeps, int threads, int area_rounds) {
  const int patches = int(source_uv.uv.size());
  std::vector<std::vector<int>> faces(patches), target_faces(patches);
  for (int f = 0; f < int(source.patch.size()); ++f) faces[source.patch[f]].push_back(f);
  for (int f = 0; f < int(target.patch.size()); ++f) target_faces[target.patch[f]].push_back(f);
  std::vector<char> on_path(source.mesh.vertex_count(), 0);
  for (const auto& path : source.paths)
    for (int v : path) on_path[v] = 1;
  const double scale = std::sqrt(side_area(source) / side_area(target));

  std::vector<std::unique_ptr<PatchEnergy>> energy(patches);
  std::vector<std::vector<int>> free(patches);
  std::vector<double> before(patches, 0), after(patches, 0), area(patches, 0);
  parallel_for(
      patches, threads,
      [&](int t) {
        energy[t] = std::make_unique<PatchEnergy>(source, source_uv.uv[t], faces[t], target, target_uv.uv[t],
                                                  target_faces[t], scale);
        before[t] = energy[t]->total(area[t]);
        match_target_areas(source, faces[t], on_path, source_uv.uv[t], source_uv.pull[t], area_rounds, *energy[t]);
        for (const auto& [v, p] : source_uv.uv[t])
          if (!on_path[v]) free[t].push_back(v);
        std::sort(free[t].begin(), free[t].end());
      },
      1);
  const std::vector<PathSlide> slides = path_slides(source);

  // Rounds of one sweep over every unsettled patch's interior (in parallel),
  // then one over the path vertices; a patch settles when a sweep moves
  // nothing in it and no path vertex beside it slid.
  MapOptimization result;
  std::vector<char> settled(patches, 0);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    std::vector<int> moved(patches, 0);
    parallel_for(
        patches, threads,
        [&](int t) {
          if (settled[t]) return;
          energy[t]->begin_sweep();
          for (int v : free[t]) moved[t] += energy[t]->improve(v);
        },
        1);
    for (int t = 0; t < patches; ++t) settled[t] = moved[t] == 0, result.moves += moved[t];
    int slid = 0;
    for (const PathSlide& s : slides)
      if (slide(s, *energy[s.patches[0]], *energy[s.patches[1]])) {
        ++slid;
        for (int t : s.patches) settled[t] = 0;
      }
    result.moves += slid;
    if (slid == 0 && std::all_of(settled.begin(), settled.end(), [](char c) { return c; })) break;
  }
  for (int t = 0; t < patches; ++t) {
    double ignored = 0;
    after[t] = energy[t]->total(ignored);
  }
  double total_area = 0;
  for (int t = 0; t < patches; ++t) {
    result.energy_before += before[t];
    result.energy_after += after[t];
    total_area += area[t];
  }
  if (total_area > 0) result.energy_before /= total_area, result.energy_after /= total_area;
  return result;
}

}  // namespace cmaps
