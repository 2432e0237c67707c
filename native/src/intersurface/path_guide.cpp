#include "intersurface/path_guide.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/nearest_point.h"
#include "consistent_maps/mesh_check.h"

namespace cmaps {
namespace {

constexpr double kPull = 4;           // factor growth per sqrt(area) of distance from A's path
constexpr int kAffinePairs = 4;       // fewer pairs: a similarity (3) or centroids and areas
constexpr double kMaxAnisotropy = 4;  // an affine fit stretching more than this is not trusted
constexpr int kGuidePoints = 64;      // segments of the coarse polyline searched first
constexpr int kClosestSamples = 1500;  // vertices of each mesh matched per round of closest points
constexpr int kClosestRounds = 20;
// A start turned onto the principal axes must end this much closer than the
// unturned one (its summed squared distances times this, compared).
constexpr double kTurnMargin = 2;

// Every k-th vertex, at most about kClosestSamples of them.
std::vector<Vec3> samples(const TriangleMesh& mesh) {
  const std::size_t step = std::max<std::size_t>(1, mesh.vertices.size() / kClosestSamples);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < mesh.vertices.size(); i += step) out.push_back(mesh.vertices[i]);
  return out;
}

// The affine map [x 1] M = y of least weighted squares; false when it
// mirrors or stretches more than kMaxAnisotropy.
bool fit_affine(const std::vector<Vec3>& x, const std::vector<Vec3>& y, const std::vector<double>& weight,
                Eigen::Affine3d& result) {
  const int n = int(x.size());
  Eigen::MatrixXd lhs(n, 4), rhs(n, 3);
  for (int i = 0; i < n; ++i) {
    lhs.row(i) << weight[i] * x[i].transpose(), weight[i];
    rhs.row(i) = weight[i] * y[i].transpose();
  }
  const Eigen::MatrixXd m = lhs.colPivHouseholderQr().solve(rhs);
  const Eigen::Matrix3d linear = m.topRows(3).transpose();
  const Eigen::Vector3d sv = linear.jacobiSvd().singularValues();
  if (!m.allFinite() || linear.determinant() <= 0 || !(sv.minCoeff() > 0) ||
      sv.maxCoeff() >= kMaxAnisotropy * sv.minCoeff())
    return false;
  result.linear() = linear;
  result.translation() = m.row(3).transpose();
  return true;
}

Vec3 centroid(const std::vector<Vec3>& points) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : points) c += p;
  return c / double(std::max<size_t>(1, points.size()));
}

// The principal axes of a mesh's surface about `center` (columns, longest
// first), from the area-weighted spread of its triangles' centroids (vertex
// density does not pull the axes).
Eigen::Matrix3d principal_axes(const TriangleMesh& mesh, const Vec3& center) {
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &p = mesh.vertices[t[0]], &q = mesh.vertices[t[1]], &r = mesh.vertices[t[2]];
    const Vec3 d = (p + q + r) / 3 - center;
    spread += 0.5 * (q - p).cross(r - p).norm() * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(spread);
  if (solver.info() != Eigen::Success) return Eigen::Matrix3d::Identity();
  return solver.eigenvectors().rowwise().reverse();
}

// A segment of a polyline that every step of a search measures against:
// its direction and squared length computed once. Distances are squared, so
// the searches compare without a square root per segment.
struct Segment {
  Vec3 a, d;
  double length;
  Vec3 centre;  // of the smallest ball holding the segment
  double radius;
  Segment(const Vec3& from, const Vec3& to)
      : a(from), d(to - from), length(d.squaredNorm()), centre(a + 0.5 * d), radius(0.5 * d.norm()) {}
  double squared_distance(const Vec3& p) const {
    const double t = length > 0 ? std::clamp((p - a).dot(d) / length, 0.0, 1.0) : 0.0;
    return (p - (a + t * d)).squaredNorm();
  }
  // Whether the segment surely lies farther from p than `reach` (no
  // division; the margin is far above rounding).
  bool beyond(const Vec3& p, double reach) const {
    const double r = (1 + 1e-6) * (radius + reach);
    return (p - centre).squaredNorm() > r * r;
  }
};

}  // namespace

PathGuide::PathGuide(const std::vector<Vec3>& on_a, const std::vector<Vec3>& on_b, const TriangleMesh& a,
                     const TriangleMesh& b) {
  const double area_a = surface_area(a), area_b = surface_area(b);
  scale_a_ = std::sqrt(std::max(area_a, 1e-300));
  const int n = int(std::min(on_a.size(), on_b.size()));
  Eigen::Matrix3Xd from(3, n), to(3, n);
  for (int i = 0; i < n; ++i) from.col(i) = on_b[i], to.col(i) = on_a[i];
  bool fitted = false;
  if (n >= kAffinePairs)
    fitted = fit_affine(std::vector<Vec3>(on_b.begin(), on_b.begin() + n),
                        std::vector<Vec3>(on_a.begin(), on_a.begin() + n), std::vector<double>(n, 1.0), transform_);
  if (!fitted && n >= 3) {
    const Eigen::Matrix4d similarity = Eigen::umeyama(from, to, true);
    if (similarity.allFinite() && similarity.topLeftCorner<3, 3>().determinant() > 0) {
      transform_.matrix() = similarity;
      fitted = true;
    }
  }
  if (fitted) {
    align_surfaces(on_a, on_b, a, b);
    return;
  }
  // Too few pairs to fix a rotation: the centroids and areas matched, B
  // unturned or turned so that its principal axes lie along A's (the four
  // turns that do not mirror), each start refined by closest points. A turn
  // is kept only when it ends clearly closer than the unturned start, so
  // meshes posed alike stay as they were while the cow (along x) and the
  // horse (along y), or a mesh and its copy stood up from y-up to z-up, are
  // turned onto each other.
  const double s = std::sqrt(area_a / std::max(area_b, 1e-300));
  const Vec3 centroid_a = centroid(a.vertices), centroid_b = centroid(b.vertices);
  const Eigen::Matrix3d axes_a = principal_axes(a, centroid_a), axes_b = principal_axes(b, centroid_b);
  Eigen::Affine3d best = Eigen::Affine3d::Identity();
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = -1; k < 4; ++k) {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    if (k >= 0) {
      Eigen::Vector3d sign(k & 1 ? -1 : 1, k & 2 ? -1 : 1, 1);
      if ((axes_a * sign.asDiagonal() * axes_b.transpose()).determinant() < 0) sign.z() = -1;
      rotation = axes_a * sign.asDiagonal() * axes_b.transpose();
    }
    transform_.linear() = s * rotation;
    transform_.translation() = centroid_a - s * rotation * centroid_b;
    const double distance = align_surfaces(on_a, on_b, a, b) * (k >= 0 ? kTurnMargin : 1);
    if (distance < best_distance) best_distance = distance, best = transform_;
  }
  transform_ = best;
}

double PathGuide::align_surfaces(const std::vector<Vec3>& on_a, const std::vector<Vec3>& on_b,
                                 const TriangleMesh& a, const TriangleMesh& b) {
  const std::vector<Vec3> from_a = samples(a), from_b = samples(b);
  const int n = int(std::min(on_a.size(), on_b.size()));
  // The pairs weigh as much as all the samples together.
  const double pair_weight = n > 0 ? std::sqrt(double(from_a.size() + from_b.size()) / n) : 0;
  double last = std::numeric_limits<double>::infinity();
  Eigen::Affine3d kept = transform_;
  const NearestPoint nearest_on_a(from_a);
  for (int round = 0; round < kClosestRounds; ++round) {
    std::vector<Vec3> mapped(from_b.size());
    for (std::size_t i = 0; i < from_b.size(); ++i) mapped[i] = to_a(from_b[i]);
    const NearestPoint nearest_mapped(mapped);
    std::vector<Vec3> x, y;
    std::vector<double> weight;
    double distance = 0;
    for (std::size_t i = 0; i < from_b.size(); ++i) {
      const Vec3& nearest_a = from_a[nearest_on_a(mapped[i])];
      x.push_back(from_b[i]), y.push_back(nearest_a), weight.push_back(1);
      distance += (nearest_a - mapped[i]).squaredNorm();
    }
    for (const Vec3& p : from_a) {
      const int j = nearest_mapped(p);
      x.push_back(from_b[j]), y.push_back(p), weight.push_back(1);
      distance += (mapped[j] - p).squaredNorm();
    }
    if (!(distance < last * (1 - 1e-6))) {  // the last fit did not help: back to the one before
      transform_ = kept;
      break;
    }
    last = distance, kept = transform_;
    for (int i = 0; i < n; ++i) x.push_back(on_b[i]), y.push_back(on_a[i]), weight.push_back(pair_weight);
    Eigen::Affine3d next;
    if (!fit_affine(x, y, weight, next)) break;
    transform_ = next;
  }
  return last;
}

std::function<double(const Vec3&)> PathGuide::near(const std::vector<Vec3>& a_path) const {
  // The nearest segment of a coarse polyline (every step-th point), then the
  // exact distance to A's segments around it: 0 on A's path itself, so a
  // copy of A finds A's own paths.
  const int n = int(a_path.size());
  const int step = std::max(1, (n + kGuidePoints - 1) / kGuidePoints);
  std::vector<Segment> fine, coarse;
  for (int i = 0; i + 1 < n; ++i) fine.emplace_back(a_path[i], a_path[i + 1]);
  for (int i = 0; i + 1 < n; i += step) coarse.emplace_back(a_path[i], a_path[std::min(i + step, n - 1)]);
  const Vec3 first = n > 0 ? a_path.front() : Vec3::Zero();
  // A search asks about neighbours one after the other: the scan starts at
  // the coarse segment nearest the last point asked about and skips those
  // whose ball lies beyond the nearest so far, and ties go to the first
  // segment, as a plain scan in order finds it (the same paths, faster).
  return [fine = std::move(fine), coarse = std::move(coarse), first, step, hint = 0,
          this](const Vec3& on_b) mutable {
    const Vec3 p = to_a(on_b);
    if (fine.empty()) return 1 + kPull * (p - first).norm() / scale_a_;
    int best = hint;  // the first nearest coarse segment
    double nearest = coarse[best].squared_distance(p), reach = std::sqrt(nearest);
    for (int k = 0; k < int(coarse.size()); ++k) {
      if (k == hint || coarse[k].beyond(p, reach)) continue;
      const double d = coarse[k].squared_distance(p);
      if (d < nearest || (d == nearest && k < best)) nearest = d, best = k, reach = std::sqrt(d);
    }
    hint = best;
    const int near = best * step;  // the first fine segment of the nearest coarse one
    for (int i = std::max(0, near - step); i < int(fine.size()) && i < near + 2 * step; ++i)
      nearest = std::min(nearest, fine[i].squared_distance(p));
    return 1 + kPull * std::sqrt(nearest) / scale_a_;
  };
}

int PathGuide::nearest(const Vec3& a_point, const std::vector<Vec3>& b_points) const {
  int best = 0;
  for (int i = 1; i < int(b_points.size()); ++i)
    if ((to_a(b_points[i]) - a_point).squaredNorm() < (to_a(b_points[best]) - a_point).squaredNorm()) best = i;
  return best;
}

}  // namespace cmaps
