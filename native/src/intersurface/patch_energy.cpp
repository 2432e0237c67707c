#include "intersurface/patch_energy.h"

#include <algorithm>
#include <cmath>

#include "common/corner_slots.h"
#include "intersurface/descent_step.h"

namespace cmaps {
namespace {

constexpr double kRatioClamp = 1e-8;  // area ratios beyond it (degenerate images) count as it

// The vertices of a side's triangles, each once, in index order.
std::vector<int> sorted_corners(const PartitionSide& side, const std::vector<int>& faces) {
  std::vector<int> corners;
  for (int f : faces) corners.insert(corners.end(), side.mesh.triangles()[f].begin(), side.mesh.triangles()[f].end());
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return corners;
}

// p's image on the target, trying the target's triangle `hint` first; `face` gets the triangle holding it.
Image locate(const PatchLocator& locator, const PartitionSide& side, const Vec2& p, double scale, int hint,
             int* face = nullptr) {
  const auto [f, w] = locator.locate(p, hint);
  if (face) *face = f;
  return image_in(side, f, w, scale);
}

}  // namespace

PatchEnergy::PatchEnergy(const PartitionSide& source, std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces,
                         const PartitionSide& target, const std::unordered_map<int, Vec2>& target_uv,
                         const std::vector<int>& target_faces, double scale)
    : source_(source), uv_(uv), target_(target), scale_(scale) {
  target_locator_ = std::make_unique<PatchLocator>(target, target_uv, target_faces);
  vertex_ = sorted_corners(source, faces);
  for (int i = 0; i < int(vertex_.size()); ++i) local_[vertex_[i]] = i;
  // A hole's temporary fan keeps its embedding valid but weighs nothing.
  ring_.resize(vertex_.size());
  for (int f : faces) {
    const Triangle& t = source.mesh.triangles()[f];
    face_.push_back(f);
    triangle_.push_back({local_.at(t[0]), local_.at(t[1]), local_.at(t[2])});
    shape_.push_back(source.in_fan(f) ? SourceTriangle() : shape_of(source, f));
    for (int k = 0; k < 3; ++k) ring_[triangle_.back()[k]].push_back(int(triangle_.size()) - 1);
  }
  for (int i = 0; i < int(face_.size()); ++i) local_face_[face_[i]] = i;
  const std::vector<int> target_vertex = sorted_corners(target, target_faces);
  std::unordered_map<int, int> target_local;
  for (int i = 0; i < int(target_vertex.size()); ++i) target_local[target_vertex[i]] = i;
  target_point_.resize(target_vertex.size());
  target_ring_.resize(target_vertex.size());
  for (int g : target_faces) {
    const Triangle& t = target.mesh.triangles()[g];
    back_triangle_.push_back({target_local.at(t[0]), target_local.at(t[1]), target_local.at(t[2])});
    back_shape_.push_back(target.in_fan(g) ? SourceTriangle() : shape_of(target, g));
    for (int w : back_triangle_.back()) target_ring_[w].push_back(int(back_triangle_.size()) - 1);
  }
  for (int w = 0; w < int(target_vertex.size()); ++w) target_point_[w] = target_uv.at(target_vertex[w]);
  reembed();
}

void PatchEnergy::reembed() {
  const PatchLocator onto_source(source_, uv_, face_);
  point_.resize(vertex_.size());
  image_.resize(vertex_.size());
  image_face_.assign(vertex_.size(), -1);
  active_.assign(vertex_.size(), 0);
  changed_.assign(vertex_.size(), 1);
  for (int i = 0; i < int(vertex_.size()); ++i) {
    point_[i] = uv_.at(vertex_[i]);
    image_[i] = locate(*target_locator_, target_, point_[i], scale_, -1, &image_face_[i]);
  }
  host_.assign(face_.size(), {});
  back_image_.resize(target_point_.size());
  // Each target vertex once, in the order its first triangle lists it.
  std::vector<char> seen(target_point_.size(), 0);
  for (const auto& corners : back_triangle_)
    for (int w : corners) {
      if (seen[w]) continue;
      seen[w] = 1;
      const auto [f, weights] = onto_source.locate(target_point_[w]);
      back_image_[w] = image_in(source_, f, weights, 1 / scale_);
      host_[local_face_.at(f)].push_back(w);
    }
  // All triangles of the embedding turn the same way (it is bijective); keep it so.
  double total = 0;
  for (int f = 0; f < int(triangle_.size()); ++f) total += signed_area(f, -1, Vec2());
  orientation_ = total >= 0 ? 1 : -1;
}

double PatchEnergy::total(double& area) const {
  double e = 0;
  area = 0;
  for (int f = 0; f < int(triangle_.size()); ++f) {
    const double fe = source_energy(f, -1, nullptr);
    if (std::isfinite(fe)) e += fe, area += shape_[f].area;
  }
  for (int g = 0; g < int(back_triangle_.size()); ++g) {
    const double ge = target_energy(g, {-1, -1, -1}, {});
    if (std::isfinite(ge)) e += scale_ * scale_ * ge;
  }
  return e;
}

bool PatchEnergy::movable(int v) const {
  std::size_t inside = 0;
  for (int f : ring_[local_.at(v)]) inside += host_[f].size();
  return inside <= kMaxRemapped;
}

PatchEnergy::Hosted PatchEnergy::hosted(int v) const {
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
  for (int g : h.triangles) h.slots.push_back(corner_slots(back_triangle_[g], h.vertices));
  return h;
}

PatchEnergy::Move PatchEnergy::trial(int v, const Vec2& p, const Hosted& inside, PointGradient* gradient) const {
  Move m;
  m.point = p;
  const int i = local_.at(v);
  const std::vector<int>& faces = ring_[i];
  for (int f : faces)
    if (orientation_ * signed_area(f, i, p) <= 0) return m;
  const auto corners = [&](int f, std::array<Vec2, 3>& c) {
    for (int k = 0; k < 3; ++k) c[k] = triangle_[f][k] == i ? p : point_[triangle_[f][k]];
  };
  m.image = locate(*target_locator_, target_, p, scale_, image_face_[i], &m.image_face);
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
      return std::optional<Vec3>(locate(*target_locator_, target_, x, scale_, m.image_face).position);
    });
  double e = 0;
  for (int f : faces) e += source_energy(f, i, &m.image, &moved, gradient);
  for (std::size_t k = 0; k < inside.triangles.size(); ++k)
    e += scale_ * scale_ * target_energy(inside.triangles[k], inside.slots[k], m.remapped, gradient);
  m.energy = e;
  return m;
}

bool PatchEnergy::improve(int v) {
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

void PatchEnergy::begin_sweep() {
  active_.swap(changed_);
  std::fill(changed_.begin(), changed_.end(), 0);
}

void PatchEnergy::apply(int v, const Move& m) {
  const int i = local_.at(v);
  for (int f : ring_[i])
    for (int j : triangle_[f]) changed_[j] = 1;
  uv_[v] = point_[i] = m.point;
  image_[i] = m.image;
  image_face_[i] = m.image_face;
  for (int f : ring_[i]) host_[f].clear();
  for (const auto& [w, remap] : m.remapped) {
    back_image_[w] = remap.image;
    host_[remap.host].push_back(w);
  }
}

std::unordered_map<int, double> PatchEnergy::area_ratios() const {
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

double PatchEnergy::source_energy(int f, int i, const Image* q, const Jacobian* moved,
                                  PointGradient* gradient) const {
  const Image* image[3];
  const Jacobian* jacobian[3];
  for (int k = 0; k < 3; ++k) {
    image[k] = triangle_[f][k] == i ? q : &image_[triangle_[f][k]];
    jacobian[k] = triangle_[f][k] == i ? moved : nullptr;
  }
  ChordTriangle chord;
  const double e = triangle_energy(shape_[f], image, nullptr, gradient ? &chord : nullptr);
  if (gradient) add_chord_gradient(shape_[f], chord, jacobian, 1, *gradient);
  return e;
}

double PatchEnergy::target_energy(int g, const std::array<int, 3>& slots,
                                  const std::vector<std::pair<int, Remap>>& remapped, PointGradient* gradient) const {
  const Image* image[3];
  const Jacobian* jacobian[3];
  for (int k = 0; k < 3; ++k) {
    const Remap* remap = slots[k] >= 0 ? &remapped[slots[k]].second : nullptr;
    image[k] = remap ? &remap->image : &back_image_[back_triangle_[g][k]];
    jacobian[k] = remap ? &remap->jacobian : nullptr;
  }
  ChordTriangle chord;
  const double e = triangle_energy(back_shape_[g], image, nullptr, gradient ? &chord : nullptr);
  if (gradient) add_chord_gradient(back_shape_[g], chord, jacobian, scale_ * scale_, *gradient);
  return e;
}

double PatchEnergy::signed_area(int f, int i, const Vec2& p) const {
  Vec2 c[3];
  for (int k = 0; k < 3; ++k) c[k] = triangle_[f][k] == i ? p : point_[triangle_[f][k]];
  const Vec2 a = c[1] - c[0], b = c[2] - c[0];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

}  // namespace cmaps
