#include "intersurface/cross_patch_optimization.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "common/corner_slots.h"
#include "common/parallel_for.h"
#include "consistent_maps/errors.h"
#include "intersurface/descent_step.h"
#include "intersurface/map_gradient.h"

namespace cmaps {
namespace {

constexpr double kInside = 1e-9;  // a base vertex this far inside a ring triangle (weights) is inside
constexpr double kOnEdge = 1e-9;  // a point this near a triangle (canonical side 1) lies on it, for stray_hosts

// How far p lies outside triangle c (0 inside): the largest of its
// distances beyond each side's line.
double distance_outside(const Vec2& p, const std::array<Vec2, 3>& c) {
  const auto weights = barycentric(p, c[0], c[1], c[2]);
  const double twice_area = std::abs(twice_signed_area(c[0], c[1], c[2]));
  double outside = 0;
  for (int k = 0; k < 3; ++k)  // weight k times the height over the side opposite corner k
    outside = std::max(outside, -weights[k] * twice_area / (c[(k + 1) % 3] - c[(k + 2) % 3]).norm());
  return outside;
}

// The vertex of a refined point's triangle with the largest weight.
int nearest_corner(const PartitionSide& side, const RefinedPoint& p) {
  const auto& w = p.weights;
  return side.mesh.triangles()[p.face][int(std::max_element(w.begin(), w.end()) - w.begin())];
}

}  // namespace

struct CrossPatchMap::Move {
  struct Rehost {
    RefinedPoint at;  // the vertex of B's new triangle of A
    Image back;       // its new image on A
    Jacobian jacobian = Jacobian::Zero();  // the image's derivative by v's point (when a gradient is asked for)
  };
  int home = -1;
  Vec2 point = Vec2::Zero();
  Image image;
  int image_face = -1;  // B's triangle holding the image
  std::vector<std::pair<int, Rehost>> rehosted;  // per vertex of B, in Ring::hosted's order
  double energy = kChordInf;
  double folded = 0;  // the folded chords' area, projected on the surface there
};

namespace {

std::vector<char> fan_patches(const ConsistentPartition& partition) {
  std::vector<char> fan(partition.triangles.size(), 0);
  const PartitionSide& a = partition.sides[0];
  for (int f = 0; f < int(a.patch.size()); ++f)
    if (a.in_fan(f)) fan[a.patch[f]] = 1;
  return fan;
}

}  // namespace

CrossPatchMap::CrossPatchMap(const ConsistentPartition& partition, const PatchParameterization& uv_a,
                             const PatchParameterization& uv_b)
    : CrossPatchMap(partition, 0, glue_patches(partition.sides[0], uv_a), glue_patches(partition.sides[1], uv_b)) {}

CrossPatchMap::CrossPatchMap(const ConsistentPartition& partition, int moving, GluedEmbedding a, GluedEmbedding b)
    : a_(partition.sides[moving]),
      b_(partition.sides[1 - moving]),
      fan_(fan_patches(partition)),
      base_(partition, fan_),
      a_glued_(a_, base_, std::move(a)),
      b_glued_(b_, base_, std::move(b)),
      scale_(std::sqrt(side_area(a_) / side_area(b_))) {
  const int na = a_.mesh.vertex_count(), nb = b_.mesh.vertex_count();
  shape_a_.resize(a_.mesh.triangles().size());
  for (int f = 0; f < int(shape_a_.size()); ++f) shape_a_[f] = a_.in_fan(f) ? SourceTriangle() : shape_of(a_, f);
  shape_b_.resize(b_.mesh.triangles().size());
  for (int g = 0; g < int(shape_b_.size()); ++g) shape_b_[g] = b_.in_fan(g) ? SourceTriangle() : shape_of(b_, g);
  split_a_ = split_triangles(a_);
  split_b_ = split_triangles(b_);

  // Base vertices and the vertices of holes' fans (rims included) stay.
  fixed_.assign(na, 0);
  for (int v = 0; v < na; ++v) {
    const std::vector<int>& faces = a_.mesh.faces_of(v);
    fixed_[v] = std::any_of(faces.begin(), faces.end(), [&](int f) { return a_.in_fan(f); });
  }
  for (int v : a_.feature_vertex) fixed_[v] = 1;
  double turning = 0;
  for (int f = 0; f < int(a_.mesh.triangles().size()); ++f) {
    std::array<Vec2, 3> c;
    if (!a_.in_fan(f) && a_glued_.develop_triangle(f, {1, 1, 1}, c) >= 0)
      turning += twice_signed_area(c[0], c[1], c[2]);
  }
  orientation_ = turning >= 0 ? 1 : -1;

  locate_b_ = b_glued_.locators();
  image_.resize(na);
  image_face_.assign(na, -1);
  for (int v = 0; v < na; ++v) image_[v] = image_on_b(a_glued_.home(v), a_glued_.point(v), -1, &image_face_[v]);

  // B's vertices, each in A's triangle holding it.
  host_.resize(nb);
  back_image_.resize(nb);
  hosted_.assign(a_.mesh.triangles().size(), {});
  const std::vector<PatchLocator> locate_a = a_glued_.locators();
  for (int w = 0; w < nb; ++w) {
    const auto [f, weights] = locate_a[b_glued_.home(w)].locate(b_glued_.point(w));
    host_[w] = {f, weights};
    hosted_[f].push_back(w);
    back_image_[w] = image_in(a_, f, weights, 1 / scale_);
  }
}

Image CrossPatchMap::image_on_b(int home, const Vec2& point, int hint, int* face) const {
  const auto [f, w] = locate_b_[home].locate(point, hint);
  if (face) *face = f;
  return image_in(b_, f, w, scale_);
}

double CrossPatchMap::total_energy() const {
  double e = 0, area = 0;
  for (int f = 0; f < int(shape_a_.size()); ++f) {
    const Triangle& t = a_.mesh.triangles()[f];
    const Image* image[3] = {&image_[t[0]], &image_[t[1]], &image_[t[2]]};
    const double fe = triangle_energy(shape_a_[f], image);
    if (std::isfinite(fe)) e += fe, area += shape_a_[f].area;
  }
  for (int g = 0; g < int(shape_b_.size()); ++g) {
    const Triangle& t = b_.mesh.triangles()[g];
    const Image* image[3] = {&back_image_[t[0]], &back_image_[t[1]], &back_image_[t[2]]};
    const double ge = triangle_energy(shape_b_[g], image);
    if (std::isfinite(ge)) e += scale_ * scale_ * ge;
  }
  for (int s = 0; s < int(split_a_.corners.size()); ++s) {
    const double se = split_energy(split_a_, s, image_, -1, nullptr);
    if (std::isfinite(se)) e += se;
  }
  for (int s = 0; s < int(split_b_.corners.size()); ++s) {
    const double se = split_energy(split_b_, s, back_image_, -1, nullptr);
    if (std::isfinite(se)) e += scale_ * scale_ * se;
  }
  return area > 0 ? e / area : 0;
}

// What a vertex's trials share, gathered once per move: v's ring (v and its
// neighbours) developed into the plane of v's base triangle, the base
// vertices near (corners of that triangle and of its neighbours) and B's
// vertices inside the ring, developed into that plane too, with the
// triangles of B and split chords whose images move when they are re-hosted.
struct CrossPatchMap::Ring {
  std::unordered_map<int, Vec2> at;
  std::vector<std::array<Vec2, 3>> corners;  // per triangle around v (faces_of order), v at its own point
  std::vector<int> slot;                     // per triangle around v: v's corner
  std::vector<int> index;                    // 0, 1, ...: the triangles around v, for find_holder
  std::vector<Vec2> base_points;
  std::vector<std::pair<int, Vec2>> hosted;  // vertex of B (sorted), its point
  std::vector<int> touched, touched_split;   // B's triangles and split chords at hosted vertices (sorted)
  // Per corner of each of those: its index in `hosted` (a move re-hosts them in that order), -1 if not there.
  std::vector<std::array<int, 3>> touched_hosted, touched_split_hosted;
  Vec2 low, high;                            // the box around v's neighbours
  double length = 0;                         // the mean distance from v to its neighbours
};

namespace {

void sort_unique(std::vector<int>& values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

}  // namespace

bool CrossPatchMap::gather_ring(int v, Ring& ring) const {
  const int t = a_glued_.home(v);
  const Vec2& point = a_glued_.point(v);
  const std::vector<int>& faces = a_.mesh.faces_of(v);
  ring.at[v] = point;
  for (int f : faces)
    for (int u : a_.mesh.triangles()[f])
      if (!ring.at.count(u) && !a_glued_.develop(u, t, point, ring.at[u])) return false;
  for (int f : faces) {
    const Triangle& tri = a_.mesh.triangles()[f];
    ring.corners.push_back({ring.at.at(tri[0]), ring.at.at(tri[1]), ring.at.at(tri[2])});
    ring.slot.push_back(int(std::find(tri.begin(), tri.end(), v) - tri.begin()));
    ring.index.push_back(int(ring.index.size()));
  }
  ring.low = ring.high = point;
  for (const auto& [u, p] : ring.at)
    if (u != v) {
      ring.low = ring.low.cwiseMin(p), ring.high = ring.high.cwiseMax(p);
      ring.length += (p - point).norm();
    }
  ring.length /= std::max<std::size_t>(1, ring.at.size() - 1);
  ring.base_points.assign(kCanonicalCorner, kCanonicalCorner + 3);
  for (int k = 0; k < 3; ++k)
    if (base_.neighbour(t, k) >= 0)
      for (const Vec2& c : kCanonicalCorner) ring.base_points.push_back(base_.from_neighbour(t, k, c));
  for (int f : faces)
    for (int w : hosted_[f]) {
      Vec2 at;
      if (!b_glued_.develop(w, t, point, at)) return false;
      ring.hosted.push_back({w, at});
      ring.touched.insert(ring.touched.end(), b_.mesh.faces_of(w).begin(), b_.mesh.faces_of(w).end());
      ring.touched_split.insert(ring.touched_split.end(), split_b_.of_vertex[w].begin(),
                                split_b_.of_vertex[w].end());
    }
  std::sort(ring.hosted.begin(), ring.hosted.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  sort_unique(ring.touched);
  sort_unique(ring.touched_split);
  const auto hosted_slots = [&](const Triangle& tri) {
    return corner_slots(tri, ring.hosted, [](const std::pair<int, Vec2>& h) { return h.first; });
  };
  for (int g : ring.touched) ring.touched_hosted.push_back(hosted_slots(b_.mesh.triangles()[g]));
  for (int s : ring.touched_split) ring.touched_split_hosted.push_back(hosted_slots(split_b_.corners[s]));
  return true;
}

CrossPatchMap::Move CrossPatchMap::trial(int v, const Vec2& q, const Ring& ring, PointGradient* gradient) const {
  Move m;
  const std::vector<int>& faces = a_.mesh.faces_of(v);
  std::vector<std::array<Vec2, 3>> laid = ring.corners;  // per ring triangle, v at q
  for (int i = 0; i < int(laid.size()); ++i) laid[i][ring.slot[i]] = q;
  // Every ring triangle turns the right way and holds no base vertex (only
  // those in the box around the ring and q can be inside one).
  const Vec2 low = ring.low.cwiseMin(q), high = ring.high.cwiseMax(q);
  std::vector<Vec2> near;
  for (const Vec2& p : ring.base_points)
    if ((p.array() >= low.array()).all() && (p.array() <= high.array()).all()) near.push_back(p);
  for (const auto& c : laid) {
    if (orientation_ * twice_signed_area(c[0], c[1], c[2]) <= 0) return m;
    for (const Vec2& p : near) {
      const auto w = barycentric(p, c[0], c[1], c[2]);
      if (w[0] > kInside && w[1] > kInside && w[2] > kInside) return m;
    }
  }
  if (!base_.home_of(a_glued_.home(v), q, m.home, m.point)) return m;
  m.image = image_on_b(m.home, m.point, image_face_[v], &m.image_face);

  // B's vertices inside the ring: the ring triangle holding each with v at q.
  const auto corners = [&](int i, std::array<Vec2, 3>& c) { c = laid[i]; };
  m.rehosted.reserve(ring.hosted.size());
  for (const auto& [w, at] : ring.hosted) {
    Holder holder;
    find_holder(at, ring.index.begin(), ring.index.end(), corners, holder);
    if (holder.score < -kInside) return m;  // outside the ring: a development gone wrong
    const RefinedPoint best{faces[holder.face], clamped(holder.weights)};
    Move::Rehost rehost{best, image_in(a_, best.face, best.weights, 1 / scale_)};
    if (gradient)
      rehost.jacobian = held_point_jacobian(laid[holder.face], ring.slot[holder.face], holder.weights,
                                            corner_positions(a_, best.face), 1 / scale_);
    m.rehosted.push_back({w, rehost});
  }

  Jacobian moved = Jacobian::Zero();  // m.image's derivative by q
  if (gradient)
    moved = image_jacobian(q, m.image.position, 1e-4 * ring.length, [&](const Vec2& x) -> std::optional<Vec3> {
      int home;
      Vec2 at;
      if (!base_.home_of(a_glued_.home(v), x, home, at)) return std::nullopt;
      return image_on_b(home, at, m.image_face).position;
    });
  double e = 0;
  // One chord triangle's energy, weighted, and its derivative through the corners moving with q.
  const auto charge = [&](const SourceTriangle& shape, const Image* image[3], const Jacobian* jacobian[3],
                          double weight) {
    ChordTriangle chord;
    e += weight * triangle_energy(shape, image, &m.folded, gradient ? &chord : nullptr);
    if (gradient) add_chord_gradient(shape, chord, jacobian, weight, *gradient);
  };
  // A triangle of A with v's image after the move.
  const auto forward = [&](const Triangle& tri, const SourceTriangle& shape) {
    const Image* image[3];
    const Jacobian* jacobian[3];
    for (int k = 0; k < 3; ++k) {
      image[k] = tri[k] == v ? &m.image : &image_[tri[k]];
      jacobian[k] = tri[k] == v ? &moved : nullptr;
    }
    charge(shape, image, jacobian, 1);
  };
  // A triangle of B with its corners' images after the move (`hosted`: see Ring).
  const auto back = [&](const Triangle& tri, const std::array<int, 3>& hosted, const SourceTriangle& shape) {
    const Image* image[3];
    const Jacobian* jacobian[3];
    for (int k = 0; k < 3; ++k) {
      const Move::Rehost* rehost = hosted[k] >= 0 ? &m.rehosted[hosted[k]].second : nullptr;
      image[k] = rehost ? &rehost->back : &back_image_[tri[k]];
      jacobian[k] = rehost ? &rehost->jacobian : nullptr;
    }
    charge(shape, image, jacobian, scale_ * scale_);
  };
  for (int f : faces) forward(a_.mesh.triangles()[f], shape_a_[f]);
  for (std::size_t i = 0; i < ring.touched.size(); ++i) {
    const int g = ring.touched[i];
    back(b_.mesh.triangles()[g], ring.touched_hosted[i], shape_b_[g]);
  }
  for (int s : split_a_.of_vertex[v]) forward(split_a_.corners[s], split_a_.shape[s]);
  for (std::size_t i = 0; i < ring.touched_split.size(); ++i) {
    const int s = ring.touched_split[i];
    back(split_b_.corners[s], ring.touched_split_hosted[i], split_b_.shape[s]);
  }
  m.energy = e;
  return m;
}

std::optional<CrossPatchMap::RingTrial> CrossPatchMap::ring_trial(int v, const Vec2& offset, bool gradient) const {
  Ring ring;
  if (fixed_[v] || !gather_ring(v, ring)) return std::nullopt;
  RingTrial result;
  const Move m = trial(v, a_glued_.point(v) + offset, ring, gradient ? &result.gradient : nullptr);
  if (!std::isfinite(m.energy)) return std::nullopt;
  result.energy = m.energy, result.folded = m.folded, result.length = ring.length;
  return result;
}

bool CrossPatchMap::improve(int v) {
  if (fixed_[v]) return false;
  std::size_t inside = 0;
  for (int f : a_.mesh.faces_of(v)) inside += hosted_[f].size();
  if (inside > std::size_t(kMaxRemapped)) return false;
  Ring ring;
  if (!gather_ring(v, ring)) return false;
  const Vec2 x0 = a_glued_.point(v);
  PointGradient gradient;
  const Move current = trial(v, x0, ring, &gradient);
  if (!std::isfinite(current.energy)) return false;
  const auto at = [&](const Vec2& q) { return trial(v, q, ring); };
  // A fold's flat charge has no gradient: a ring holding one first steps to
  // unfold (kept, as any step, only if the energy drops).
  std::optional<Move> move;
  if (current.folded > 0) move = descent_step(x0, gradient.folded, ring.length, kScaledHalvings, current, at);
  if (!move)
    move = newton_step(x0, gradient.energy, ring.length, current, at, [&](const Vec2& q) -> std::optional<Vec2> {
      PointGradient there;
      if (!std::isfinite(trial(v, q, ring, &there).energy)) return std::nullopt;
      return there.energy;
    });
  if (!move || breaks_invariants(v, *move)) return false;
  apply(v, *move);
  return true;
}

void CrossPatchMap::apply(int v, const Move& move) {
  a_glued_.move(v, move.home, move.point);
  image_[v] = move.image;
  image_face_[v] = move.image_face;
  for (int f : a_.mesh.faces_of(v)) hosted_[f].clear();
  for (const auto& [w, rehost] : move.rehosted) {
    host_[w] = rehost.at;
    back_image_[w] = rehost.back;
    hosted_[rehost.at.face].push_back(w);
  }
}

namespace {

// Per vertex of the side: 0 below the median along the longest axis of its
// bounding box, 1 above.
std::vector<char> halves(const PartitionSide& side) {
  const int n = side.mesh.vertex_count();
  std::vector<char> half(n, 0);
  if (n == 0) return half;
  Vec3 low = side.mesh.position(0), high = low;
  for (int v = 0; v < n; ++v) low = low.cwiseMin(side.mesh.position(v)), high = high.cwiseMax(side.mesh.position(v));
  int axis;
  (high - low).maxCoeff(&axis);
  std::vector<std::pair<double, int>> along(n);
  for (int v = 0; v < n; ++v) along[v] = {side.mesh.position(v)[axis], v};
  std::nth_element(along.begin(), along.begin() + n / 2, along.end());
  for (auto k = along.begin() + n / 2; k != along.end(); ++k) half[k->second] = 1;
  return half;
}

}  // namespace

bool CrossPatchMap::moves_alone(int v, const std::vector<char>& half) const {
  const char h = half[v];
  const auto in_half = [&](const Triangle& t) { return half[t[0]] == h && half[t[1]] == h && half[t[2]] == h; };
  const auto hosted_in_half = [&](const Triangle& t) {
    return std::all_of(t.begin(), t.end(), [&](int w) { return in_half(a_.mesh.triangles()[host_[w].face]); });
  };
  const std::vector<int>& faces = a_.mesh.faces_of(v);
  if (!std::all_of(faces.begin(), faces.end(), [&](int f) { return in_half(a_.mesh.triangles()[f]); })) return false;
  for (int s : split_a_.of_vertex[v])
    if (!in_half(split_a_.corners[s])) return false;
  for (int f : faces)
    for (int w : hosted_[f]) {
      for (int g : b_.mesh.faces_of(w))
        if (!hosted_in_half(b_.mesh.triangles()[g])) return false;
      for (int s : split_b_.of_vertex[w])
        if (!hosted_in_half(split_b_.corners[s])) return false;
    }
  return true;
}

CrossPatchOptimization CrossPatchMap::optimize(int sweeps, const std::function<bool(double)>& keep_going,
                                               int threads) {
  CrossPatchOptimization result;
  result.energy_before = total_energy();
  // Each sweep visits the vertices whose ring changed in the sweep before (all, at first).
  const int n = a_.mesh.vertex_count();
  const std::vector<char> half = halves(a_);
  std::vector<char> active(n, 1), next(n, 0), alone(n, 0);
  struct Count {
    int moved = 0, crossings = 0;
  };
  // A vertex's move, its ring marked for the next sweep.
  const auto visit = [&](int v, Count& count) {
    const int home = a_glued_.home(v);
    if (!improve(v)) return;
    ++count.moved;
    count.crossings += a_glued_.home(v) != home;
    for (int f : a_.mesh.faces_of(v))
      for (int u : a_.mesh.triangles()[f]) next[u] = 1;
  };
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    parallel_for(n, threads, [&](std::size_t v) { alone[v] = active[v] && moves_alone(int(v), half); }, 1024);
    std::array<Count, 3> count;  // half 0's, half 1's, the rest's
    parallel_for(
        2, threads,
        [&](std::size_t h) {
          for (int v = 0; v < n; ++v)
            if (alone[v] && half[v] == char(h)) visit(v, count[h]);
        },
        1);
    for (int v = 0; v < n; ++v)
      if (active[v] && !alone[v]) visit(v, count[2]);
    int moved = 0;
    for (const Count& c : count) moved += c.moved, result.crossings += c.crossings;
    result.moves += moved;
    if (moved == 0) break;
    if (keep_going && !keep_going(double(sweep + 1) / sweeps)) throw Cancelled();
    active.swap(next);
    std::fill(next.begin(), next.end(), 0);
  }
  result.energy_after = total_energy();
  return result;
}

bool CrossPatchMap::turned(const GluedSide& side, int f) const {
  std::array<Vec2, 3> c;
  return side.develop_triangle(f, {1, 1, 1}, c) < 0 || orientation_ * twice_signed_area(c[0], c[1], c[2]) <= 0;
}

int CrossPatchMap::turned_triangles() const {
  int count = 0;
  for (const GluedSide* side : {&a_glued_, &b_glued_})
    for (int f = 0; f < int(side->side().mesh.triangles().size()); ++f)
      count += !side->side().in_fan(f) && turned(*side, f);
  return count;
}

bool CrossPatchMap::breaks_invariants(int v, const Move& move) {
  const int home = a_glued_.home(v);
  const Vec2 point = a_glued_.point(v);
  a_glued_.move(v, move.home, move.point);
  const std::vector<int>& faces = a_.mesh.faces_of(v);
  const bool broken =
      std::any_of(faces.begin(), faces.end(), [&](int f) { return !a_.in_fan(f) && turned(a_glued_, f); }) ||
      std::any_of(move.rehosted.begin(), move.rehosted.end(),
                  [&](const auto& rehost) { return strays(rehost.first, rehost.second.at.face); });
  a_glued_.move(v, home, point);
  return broken;
}

bool CrossPatchMap::strays(int w, int face) const {
  std::array<Vec2, 3> c;
  const int plane = a_glued_.develop_triangle(face, {1, 1, 1}, c);
  Vec2 at;
  return plane < 0 || !b_glued_.develop(w, plane, (c[0] + c[1] + c[2]) / 3, at) || distance_outside(at, c) > kOnEdge;
}

int CrossPatchMap::stray_hosts() const {
  int stray = 0;
  for (int w = 0; w < b_.mesh.vertex_count(); ++w) {
    const std::vector<int>& faces = b_.mesh.faces_of(w);
    if (std::all_of(faces.begin(), faces.end(), [&](int g) { return b_.in_fan(g); })) continue;
    stray += strays(w, host_[w].face);
  }
  return stray;
}

RefinedPoint CrossPatchMap::locate_on_a(int patch, const Vec2& point, int near_face) const {
  RefinedPoint best{near_face, {1.0 / 3, 1.0 / 3, 1.0 / 3}};
  double score = -kChordInf;
  for (int c : a_.mesh.triangles()[near_face])
    for (int f : a_.mesh.faces_of(c)) {
      // The triangle in its own plane (its corners lie close together, so
      // their nearest copies are the right ones), the point carried there.
      std::array<Vec2, 3> corner;
      const int plane = a_glued_.develop_triangle(f, {1, 1, 1}, corner);
      Vec2 at;
      if (plane < 0 || !base_.develop(patch, point, plane, (corner[0] + corner[1] + corner[2]) / 3, at)) continue;
      const auto weights = barycentric(at, corner[0], corner[1], corner[2]);
      const double low = std::min({weights[0], weights[1], weights[2]});
      if (low > score) score = low, best = {f, weights};
    }
  best.weights = clamped(best.weights);
  return best;
}

std::vector<InputLocation> CrossPatchMap::located_on_b(const std::vector<std::pair<int, Vec2>>& points,
                                                       const TriangleMesh& b_input, int threads) const {
  std::vector<InputLocation> image(points.size());
  parallel_for(points.size(), threads, [&](std::size_t i) {
    const auto [face, w] = locate_b_[points[i].first].locate(points[i].second);
    image[i] = to_input(b_, b_input, face, w);
  });
  return image;
}

std::vector<InputLocation> CrossPatchMap::map_a(const TriangleMesh& b_input, int threads) const {
  std::vector<std::pair<int, Vec2>> points(a_.mesh.input_vertex_count());
  for (int v = 0; v < int(points.size()); ++v) points[v] = {a_glued_.home(v), a_glued_.point(v)};
  std::vector<InputLocation> image = located_on_b(points, b_input, threads);
  snap_features(a_, b_, b_input, image);
  return image;
}

std::vector<InputLocation> CrossPatchMap::map_b(const TriangleMesh& a_input) const {
  std::vector<InputLocation> image(b_.mesh.input_vertex_count());
  for (int w = 0; w < int(image.size()); ++w) image[w] = to_input(a_, a_input, host_[w].face, host_[w].weights);
  snap_features(b_, a_, a_input, image);
  return image;
}

std::pair<int, Vec2> CrossPatchMap::canonical_point(const GluedSide& side, const RefinedPoint& p) {
  std::pair<int, Vec2> at;
  if (side.canonical_point(p.face, p.weights, at.first, at.second)) return at;
  // Never, short of a broken embedding: the nearest corner's own point.
  const int nearest = nearest_corner(side.side(), p);
  return {side.home(nearest), side.point(nearest)};
}

std::vector<InputLocation> CrossPatchMap::map_a_corners(const TriangleMesh& a_input, const TriangleMesh& b_input,
                                                        int threads) const {
  const std::vector<RefinedPoint> corners = corner_points(a_, a_input, threads);
  std::vector<std::pair<int, Vec2>> points(corners.size());
  parallel_for(corners.size(), threads, [&](std::size_t i) { points[i] = canonical_point(a_glued_, corners[i]); });
  return located_on_b(points, b_input, threads);
}

std::vector<InputLocation> CrossPatchMap::map_b_corners(const TriangleMesh& a_input, const TriangleMesh& b_input,
                                                        int threads) const {
  const std::vector<RefinedPoint> corners = corner_points(b_, b_input, threads);
  std::vector<InputLocation> image(corners.size());
  parallel_for(corners.size(), threads, [&](std::size_t i) {
    const auto [patch, p] = canonical_point(b_glued_, corners[i]);
    const RefinedPoint on_a = locate_on_a(patch, p, host_[nearest_corner(b_, corners[i])].face);
    image[i] = to_input(a_, a_input, on_a.face, on_a.weights);
  });
  return image;
}

}  // namespace cmaps
