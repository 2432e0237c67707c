#include "intersurface/patch_map_optimization.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "common/parallel_for.h"
#include "intersurface/chord_energy.h"
#include "intersurface/descent_step.h"
#include "intersurface/map_gradient.h"
#include "intersurface/patch_embedding.h"
#include "intersurface/patch_locator.h"

namespace cmaps {
namespace {

constexpr int kHalvings = 10;  // path slides' line search: step, step / 2, ...
constexpr double kRatioClamp = 1e-8;  // area ratios beyond it (degenerate images) count as it

// One patch, both directions: the source's triangles mapped onto the target
// and the target's triangles mapped back, as functions of one free source
// vertex's canonical point. Moving it re-maps the target vertices inside its
// ring (the ring's outline stays, so no others). Vertices and triangles are
// numbered locally, in the order of their indices in the meshes.
class PatchEnergy {
 public:
  PatchEnergy(const PartitionSide& source, std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces,
              const PartitionSide& target, const std::unordered_map<int, Vec2>& target_uv,
              const std::vector<int>& target_faces, double scale)
      : source_(source), uv_(uv), target_(target), scale_(scale) {
    target_locator_ = std::make_unique<PatchLocator>(target, target_uv, target_faces);
    const PatchLocator onto_source(source, uv, faces);
    vertex_ = sorted_corners(source, faces);
    for (int i = 0; i < int(vertex_.size()); ++i) local_[vertex_[i]] = i;
    point_.resize(vertex_.size());
    image_.resize(vertex_.size());
    active_.assign(vertex_.size(), 0);
    changed_.assign(vertex_.size(), 1);
    for (int i = 0; i < int(vertex_.size()); ++i) {
      point_[i] = uv.at(vertex_[i]);
      image_[i] = locate(*target_locator_, target, point_[i], scale);
    }
    // A hole's temporary fan keeps its embedding valid but weighs nothing.
    ring_.resize(vertex_.size());
    for (int f : faces) {
      const Triangle& t = source.mesh.triangles()[f];
      face_.push_back(f);
      triangle_.push_back({local_.at(t[0]), local_.at(t[1]), local_.at(t[2])});
      shape_.push_back(source.in_fan(f) ? SourceTriangle() : shape_of(source, f));
      for (int k = 0; k < 3; ++k) ring_[triangle_.back()[k]].push_back(int(triangle_.size()) - 1);
    }
    std::unordered_map<int, int> local_face;
    for (int i = 0; i < int(faces.size()); ++i) local_face[faces[i]] = i;
    const std::vector<int> target_vertex = sorted_corners(target, target_faces);
    std::unordered_map<int, int> target_local;
    for (int i = 0; i < int(target_vertex.size()); ++i) target_local[target_vertex[i]] = i;
    back_image_.resize(target_vertex.size());
    target_point_.resize(target_vertex.size());
    target_ring_.resize(target_vertex.size());
    host_.resize(faces.size());
    std::vector<char> seen(target_vertex.size(), 0);
    for (int g : target_faces) {
      const Triangle& t = target.mesh.triangles()[g];
      back_triangle_.push_back({target_local.at(t[0]), target_local.at(t[1]), target_local.at(t[2])});
      back_shape_.push_back(target.in_fan(g) ? SourceTriangle() : shape_of(target, g));
      for (int w : back_triangle_.back()) {
        target_ring_[w].push_back(int(back_triangle_.size()) - 1);
        if (seen[w]) continue;
        seen[w] = 1;
        target_point_[w] = target_uv.at(target_vertex[w]);
        const auto [f, weights] = onto_source.locate(target_point_[w]);
        back_image_[w] = image_in(source, f, weights, 1 / scale);
        host_[local_face.at(f)].push_back(w);
      }
    }
    // All triangles of the embedding turn the same way (it is bijective); keep it so.
    double total = 0;
    for (int f = 0; f < int(triangle_.size()); ++f) total += signed_area(f, -1, Vec2());
    orientation_ = total >= 0 ? 1 : -1;
  }

  // Both directions' energies, the target's weighted to the source's area.
  double total(double& area) const {
    double e = 0;
    area = 0;
    for (int f = 0; f < int(triangle_.size()); ++f) {
      const double fe = source_energy(f, -1, nullptr);
      if (std::isfinite(fe)) e += fe, area += shape_[f].area;
    }
    for (int g = 0; g < int(back_triangle_.size()); ++g) {
      const double ge = target_energy(g, {});
      if (std::isfinite(ge)) e += scale_ * scale_ * ge;
    }
    return e;
  }

  // Whether mesh vertex v may move: not when its ring here holds too many target vertices to re-map.
  bool movable(int v) const {
    std::size_t inside = 0;
    for (int f : ring_[local_.at(v)]) inside += host_[f].size();
    return inside <= kMaxRemapped;
  }

  // What the trials of one vertex share: the local target vertices inside
  // its ring (sorted) and their triangles (sorted), whose images move with
  // it, and the mean distance from it to its ring's other corners.
  struct Hosted {
    std::vector<int> vertices, triangles;
    double length = 0;
  };
  Hosted hosted(int v) const {
    Hosted h;
    const int i = local_.at(v);
    int count = 0;
    for (int f : ring_[i])
      for (int j : triangle_[f])
        if (j != i) h.length += (point_[j] - point_[i]).norm(), ++count;
    h.length /= std::max(count, 1);
    for (int f : ring_[i])
      for (int w : host_[f]) {
        h.vertices.push_back(w);
        h.triangles.insert(h.triangles.end(), target_ring_[w].begin(), target_ring_[w].end());
      }
    std::sort(h.vertices.begin(), h.vertices.end());
    std::sort(h.triangles.begin(), h.triangles.end());
    h.triangles.erase(std::unique(h.triangles.begin(), h.triangles.end()), h.triangles.end());
    return h;
  }

  // One descent step of mesh vertex v (descent_step.h).
  bool improve(int v) {
    const int i = local_.at(v);
    if (!active_[i] || !movable(v)) return false;
    const Vec2 u0 = point_[i];
    const Hosted inside = hosted(v);
    PointGradient gradient;
    const Move current = trial(v, u0, inside, &gradient);
    if (!std::isfinite(current.energy)) return false;
    const auto move = descent_step(u0, gradient.energy, inside.length, kGuessedHalvings, current,
                                   [&](const Vec2& p) { return trial(v, p, inside); });
    if (!move) return false;
    apply(v, *move);
    return true;
  }

  // Vertex v at canonical point p: its image, the re-mapped target vertices, the ring's energy.
  struct Remap {
    Image image;  // the target vertex's new image
    int host;     // its new source triangle (local)
    Jacobian jacobian = Jacobian::Zero();  // the image's derivative by v's point (when a gradient is asked for)
  };
  struct Move {
    Vec2 point;
    Image image;
    std::vector<std::pair<int, Remap>> remapped;  // per local target vertex (sorted)
    double energy = kChordInf;
  };

  // The energy of mesh vertex v's triangles in this patch and of the
  // target's triangles around the target vertices they hold (`inside`,
  // from hosted(v)), with v at p; inf when one of v's triangles would turn
  // over. With `gradient`, also its derivative by p.
  Move trial(int v, const Vec2& p, const Hosted& inside, PointGradient* gradient = nullptr) const {
    Move m;
    m.point = p;
    const int i = local_.at(v);
    const std::vector<int>& faces = ring_[i];
    for (int f : faces)
      if (orientation_ * signed_area(f, i, p) <= 0) return m;
    const auto corners = [&](int f, std::array<Vec2, 3>& c) {
      for (int k = 0; k < 3; ++k) c[k] = triangle_[f][k] == i ? p : point_[triangle_[f][k]];
    };
    m.image = locate(*target_locator_, target_, p, scale_);
    // Target vertices inside the ring: their source triangle with v at p.
    m.remapped.reserve(inside.vertices.size());
    for (int w : inside.vertices) {
      Holder best;
      find_holder(target_point_[w], faces.begin(), faces.end(), corners, best);
      // The image lies in the moved triangle: v's position enters through its weight.
      Remap remap{image_in(source_, face_[best.face], clamped(best.weights), 1 / scale_), best.face};
      if (gradient) {
        std::array<Vec2, 3> c;
        corners(best.face, c);
        const int slot = int(std::find(triangle_[best.face].begin(), triangle_[best.face].end(), i) -
                             triangle_[best.face].begin());
        remap.jacobian = held_point_jacobian(c, slot, best.weights, corner_positions(source_, face_[best.face]),
                                              1 / scale_);
      }
      m.remapped.push_back({w, remap});
    }
    Jacobian moved = Jacobian::Zero();  // m.image's derivative by p
    if (gradient)
      moved = image_jacobian(p, m.image.position, 1e-4 * inside.length, [&](const Vec2& x) {
        return std::optional<Vec3>(locate(*target_locator_, target_, x, scale_).position);
      });
    double e = 0;
    for (int f : faces) e += source_energy(f, i, &m.image, &moved, gradient);
    for (int g : inside.triangles) e += scale_ * scale_ * target_energy(g, m.remapped, gradient);
    m.energy = e;
    return m;
  }

  // Starts a sweep: the vertices to try are those whose ring changed since the last.
  void begin_sweep() {
    active_.swap(changed_);
    std::fill(changed_.begin(), changed_.end(), 0);
  }

  void apply(int v, const Move& m) {
    const int i = local_.at(v);
    for (int f : ring_[i])
      for (int j : triangle_[f]) changed_[j] = 1;
    uv_[v] = point_[i] = m.point;
    image_[i] = m.image;
    for (int f : ring_[i]) host_[f].clear();
    for (const auto& [w, remap] : m.remapped) {
      back_image_[w] = remap.image;
      host_[remap.host].push_back(w);
    }
  }

  const std::unordered_map<int, Vec2>& uv() const { return uv_; }

  // Per source vertex: how much the map scales area around it, the
  // area-weighted geometric mean over its triangles of image area (chord
  // triangle, target scaled) over source area; 1 where it has no area.
  std::unordered_map<int, double> area_ratios() const {
    std::vector<double> log_sum(vertex_.size(), 0), weight(vertex_.size(), 0);
    for (int f = 0; f < int(triangle_.size()); ++f) {
      const double area = shape_[f].area;
      if (area <= 0) continue;
      const auto& t = triangle_[f];
      const double image = 0.5 * (image_[t[1]].position - image_[t[0]].position)
                                     .cross(image_[t[2]].position - image_[t[0]].position)
                                     .norm();
      const double ratio = std::clamp(image / area, kRatioClamp, 1 / kRatioClamp);
      for (int i : t) log_sum[i] += area * std::log(ratio), weight[i] += area;
    }
    std::unordered_map<int, double> ratio;
    for (int i = 0; i < int(vertex_.size()); ++i)
      ratio[vertex_[i]] = weight[i] > 0 ? std::exp(log_sum[i] / weight[i]) : 1;
    return ratio;
  }

 private:
  // The vertices of a side's triangles, each once, in index order.
  static std::vector<int> sorted_corners(const PartitionSide& side, const std::vector<int>& faces) {
    std::vector<int> corners;
    for (int f : faces) corners.insert(corners.end(), side.mesh.triangles()[f].begin(), side.mesh.triangles()[f].end());
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    return corners;
  }

  static Image locate(const PatchLocator& locator, const PartitionSide& side, const Vec2& p, double scale) {
    const auto [face, w] = locator.locate(p);
    return image_in(side, face, w, scale);
  }

  // Local triangle f's energy, local vertex i's image replaced by q (none
  // when i < 0); with `gradient`, its derivative added, q moving by `moved`.
  double source_energy(int f, int i, const Image* q, const Jacobian* moved = nullptr,
                       PointGradient* gradient = nullptr) const {
    const Image* image[3];
    const Jacobian* jacobian[3];
    for (int k = 0; k < 3; ++k) {
      image[k] = triangle_[f][k] == i ? q : &image_[triangle_[f][k]];
      jacobian[k] = triangle_[f][k] == i ? moved : nullptr;
    }
    if (gradient) add_chord_gradient(shape_[f], image, jacobian, 1, *gradient);
    return triangle_energy(shape_[f], image);
  }

  // Local target triangle g's energy with the re-mapped images; with
  // `gradient`, its derivative (weighted as the trial weighs it) added.
  double target_energy(int g, const std::vector<std::pair<int, Remap>>& remapped,
                       PointGradient* gradient = nullptr) const {
    const Image* image[3];
    const Jacobian* jacobian[3];
    for (int k = 0; k < 3; ++k) {
      const Remap* remap = find_remapped(remapped, back_triangle_[g][k]);
      image[k] = remap ? &remap->image : &back_image_[back_triangle_[g][k]];
      jacobian[k] = remap ? &remap->jacobian : nullptr;
    }
    if (gradient) add_chord_gradient(back_shape_[g], image, jacobian, scale_ * scale_, *gradient);
    return triangle_energy(back_shape_[g], image);
  }

  double signed_area(int f, int i, const Vec2& p) const {
    Vec2 c[3];
    for (int k = 0; k < 3; ++k) c[k] = triangle_[f][k] == i ? p : point_[triangle_[f][k]];
    const Vec2 a = c[1] - c[0], b = c[2] - c[0];
    return 0.5 * (a.x() * b.y() - a.y() * b.x());
  }

  const PartitionSide& source_;
  std::unordered_map<int, Vec2>& uv_;  // kept up to date for the path slides
  const PartitionSide& target_;
  double scale_;
  double orientation_ = 1;
  // The source's side of the patch, local: vertices, their mesh index, canonical point and image.
  std::vector<int> vertex_;
  std::unordered_map<int, int> local_;
  std::vector<Vec2> point_;
  std::vector<Image> image_;
  std::vector<int> face_;                     // per local triangle: its index in the mesh
  std::vector<std::array<int, 3>> triangle_;  // and its local corners
  std::vector<SourceTriangle> shape_;
  std::vector<std::vector<int>> ring_;  // per local vertex: its local triangles
  std::vector<std::vector<int>> host_;  // per local triangle: the local target vertices inside it
  std::vector<char> active_, changed_;  // per local vertex: to try in this sweep, in the next
  // The target's side, local.
  std::vector<Vec2> target_point_;
  std::vector<Image> back_image_;
  std::vector<std::array<int, 3>> back_triangle_;
  std::vector<SourceTriangle> back_shape_;
  std::vector<std::vector<int>> target_ring_;  // per local target vertex: its local target triangles
  std::unique_ptr<PatchLocator> target_locator_;
};

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
template <class MakeEnergy>
void match_target_areas(const PartitionSide& source, const std::vector<int>& faces, const std::vector<char>& on_path,
                        std::unordered_map<int, Vec2>& uv, const std::unordered_map<int, double>& pull,
                        int rounds, std::unique_ptr<PatchEnergy>& energy, const MakeEnergy& make_energy) {
  if (rounds <= 0) return;
  std::unordered_map<int, Vec2> points;
  for (const auto& [v, p] : uv)
    if (on_path[v]) points.emplace(v, p);
  PatchEmbedding embedding(source, faces, points);
  if (embedding.empty()) return;
  PatchEmbedding::Weights weight = embedding.mean_value_weights();
  for (auto& row : weight)
    for (auto& [u, w] : row) w *= pull.at(u);
  double ignored = 0, best = energy->total(ignored);
  for (int round = 0; round < rounds; ++round) {
    const std::unordered_map<int, double> ratio = energy->area_ratios();
    bool lowered = false;
    // The ratio's root first, then its fourth and eighth: a full step can overshoot.
    for (double power = 0.5; power > 0.1 && !lowered; power *= 0.5) {
      PatchEmbedding::Weights next_weight = weight;
      for (auto& row : next_weight)
        for (auto& [u, w] : row) w *= std::pow(ratio.at(u), power);
      embedding.solve(next_weight);
      std::unordered_map<int, Vec2> kept = uv;
      uv = points;
      std::unique_ptr<PatchEnergy> next = make_energy();
      const double e = next->total(ignored);
      if (e < best) {
        best = e, energy = std::move(next), weight = std::move(next_weight), lowered = true;
      } else {
        uv = std::move(kept);
      }
    }
    if (!lowered) return;
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
        const auto make_energy = [&] {
          return std::make_unique<PatchEnergy>(source, source_uv.uv[t], faces[t], target, target_uv.uv[t],
                                               target_faces[t], scale);
        };
        energy[t] = make_energy();
        before[t] = energy[t]->total(area[t]);
        match_target_areas(source, faces[t], on_path, source_uv.uv[t], source_uv.pull[t], area_rounds, energy[t],
                           make_energy);
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
