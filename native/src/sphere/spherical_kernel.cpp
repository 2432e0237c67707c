#include "sphere/spherical_kernel.h"

#include <Eigen/Geometry>
#include <cmath>

namespace cmaps {
namespace {

using Point = Eigen::Vector2d;

// Sutherland-Hodgman step: keep the part of a convex polygon where
// c + n.x >= 0.
std::vector<Point> clip(const std::vector<Point>& polygon, const Point& n, double c) {
  std::vector<Point> out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Point &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
    const double sp = c + n.dot(p), sq = c + n.dot(q);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
  }
  return out;
}

}  // namespace

std::optional<Vec3> kernel_point(const std::vector<Vec3>& ring, const Vec3& center) {
  const Vec3 e1 = center.unitOrthogonal(), e2 = center.cross(e1);
  // Points up to about 76 degrees from the centre.
  const double r = 4.0;
  std::vector<Point> polygon{{-r, -r}, {r, -r}, {r, r}, {-r, r}};
  for (size_t i = 0; i < ring.size() && polygon.size() >= 3; ++i) {
    // det(x, a, b) = x . (a x b) > 0 with x = center + s e1 + t e2.
    const Vec3 normal = ring[i].cross(ring[(i + 1) % ring.size()]);
    polygon = clip(polygon, Point(normal.dot(e1), normal.dot(e2)), normal.dot(center));
  }
  if (polygon.size() < 3) return std::nullopt;
  double area = 0;
  Point centroid(0, 0);
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Point &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
    const double cross = p.x() * q.y() - p.y() * q.x();
    area += cross;
    centroid += (p + q) * cross;
  }
  if (!(area > 0)) return std::nullopt;
  centroid /= 3 * area;
  return (center + centroid.x() * e1 + centroid.y() * e2).normalized();
}

}  // namespace cmaps
