// An optional second energy for a spherical parameterization: consistency
// with another surface's map. Through the common sphere every vertex has an
// image on the reference surface; each triangle pays the symmetric Dirichlet
// energy (|J|^2 + |J^-1|^2, 4 for an isometry) of the linear map onto the
// triangle its corners' images form. Added to the stretch energy, the map
// stays stretch-minimizing (and the stretch barrier keeps it an embedding)
// while the correspondence it induces with the reference is pulled towards
// an isometry, coarse to fine as the refinement grows the mesh, which lets
// large regions move together (Schreiner et al. 2004 optimize their
// inter-surface maps during refinement for the same reason).
#pragma once
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/progressive_mesh.h"
#include "consistent_maps/sphere_locator.h"

namespace cmaps {

// The reference: a surface triangulated like its spherical map (Steiner
// vertices included) and that map; `weight` scales the term against the
// stretch energy (both are area integrals, the term at least 4 per unit area).
struct ReferenceMap {
  const TriangleMesh* surface = nullptr;
  const std::vector<Vec3>* sphere = nullptr;
  double weight = 0.25;
};

class CorrespondenceTerm {
 public:
  // `positions`: the parameterized mesh's vertices (any scale: the reference
  // is scaled to the same total area, given as `area`).
  CorrespondenceTerm(const std::vector<Vec3>& positions, double area, const ReferenceMap& reference);

  // Weighted energy of v's current triangles with v at sphere point p (the
  // other corners where `sphere` has them).
  double star_energy(const MeshRefinement& mesh, int v, const Vec3& p, const std::vector<Vec3>& sphere) const;

  // Records v's image at sphere point s (after v moved; never concurrently for one v).
  void moved(int v, const Vec3& s);
  // Images of every vertex with a non-zero sphere point.
  void refresh_all(const std::vector<Vec3>& sphere, int threads);

 private:
  Vec3 image(const Vec3& s) const;
  const Vec3& image_of(int u, const std::vector<Vec3>& sphere, Vec3& scratch) const;

  const std::vector<Vec3>& positions_;
  const TriangleMesh& reference_;
  SphereLocator locator_;
  double scale_ = 1, weight_ = 1;
  std::vector<Vec3> images_, imaged_at_;  // per vertex: its image and the sphere point it was taken at
};

}  // namespace cmaps
