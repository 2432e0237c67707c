#include "sphere/correspondence_term.h"

#include <cmath>

#include "common/parallel_for.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "intersurface/symmetric_dirichlet.h"

namespace cmaps {

CorrespondenceTerm::CorrespondenceTerm(const std::vector<Vec3>& positions, double area, const ReferenceMap& reference)
    : positions_(positions),
      reference_(*reference.surface),
      locator_(*reference.sphere, reference.surface->triangles),
      weight_(reference.weight),
      images_(positions.size(), Vec3::Zero()),
      imaged_at_(positions.size(), Vec3::Zero()) {
  const double reference_area = surface_area(reference_);
  if (!(reference_area > 0) || !(area > 0)) throw InvalidInput("correspondence term: a surface has no area");
  scale_ = std::sqrt(area / reference_area);
}

Vec3 CorrespondenceTerm::image(const Vec3& s) const {
  const SphereLocation at = locator_.locate(s);
  const Triangle& t = reference_.triangles[at.triangle];
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < 3; ++k) x += at.barycentric[k] * reference_.vertices[t[k]];
  return scale_ * x;
}

const Vec3& CorrespondenceTerm::image_of(int u, const std::vector<Vec3>& sphere, Vec3& scratch) const {
  if (imaged_at_[u] == sphere[u]) return images_[u];
  return scratch = image(sphere[u]);  // not recorded: the caller may be one of several threads
}

double CorrespondenceTerm::star_energy(const MeshRefinement& mesh, int v, const Vec3& p,
                                       const std::vector<Vec3>& sphere) const {
  const Vec3 at_p = image(p);
  double energy = 0;
  for (int f : mesh.faces_of(v)) {
    const Triangle& t = mesh.triangles()[f];
    Vec3 scratch[3];
    const Vec3 q[3] = {t[0] == v ? at_p : image_of(t[0], sphere, scratch[0]),
                       t[1] == v ? at_p : image_of(t[1], sphere, scratch[1]),
                       t[2] == v ? at_p : image_of(t[2], sphere, scratch[2])};
    const Vec3 x[3] = {positions_[t[0]], positions_[t[1]], positions_[t[2]]};
    double area;
    const double e = symmetric_dirichlet(x, q, &area);
    if (area > 0) energy += e * area;
  }
  return weight_ * energy;
}

void CorrespondenceTerm::moved(int v, const Vec3& s) {
  images_[v] = image(s);
  imaged_at_[v] = s;
}

void CorrespondenceTerm::refresh_all(const std::vector<Vec3>& sphere, int threads) {
  parallel_for(sphere.size(), threads, [&](size_t v) {
    if (sphere[v] != Vec3::Zero() && imaged_at_[v] != sphere[v]) moved(int(v), sphere[v]);
  });
}

}  // namespace cmaps
