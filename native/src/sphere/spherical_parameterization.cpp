#include "consistent_maps/spherical_parameterization.h"

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"

namespace cmaps {

SphereResult spherical_parameterization(const TriangleMesh& mesh, const SphereOptions&,
                                        const ProgressCallback&) {
  require_sphere_topology(mesh);
  throw Error("spherical parameterization: not implemented yet");
}

}  // namespace cmaps
