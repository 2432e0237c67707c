#include "sphere_outputs.h"

#include <pybind11/numpy.h>

#include "consistent_maps/consistent_parameterization.h"
#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

void add_map_report(py::dict& d, const cmaps::SphericalMapReport& r) {
  d["efficiency"] = r.efficiency;
  d["l2_stretch"] = r.l2_stretch;
  d["linf_stretch"] = r.linf_stretch;
  d["flipped"] = r.flipped;
  d["degenerate"] = r.degenerate;
  d["spherical_area_sum"] = r.spherical_area_sum;
  d["surface_area"] = r.surface_area;
  d["bijective"] = r.bijective();
}

py::tuple constrained_outputs(const cmaps::TriangleMesh& mesh, const cmaps::ConstrainedResult& result,
                              double seconds) {
  py::dict stats;
  add_map_report(stats, result.report);
  stats["seconds"] = seconds;
  stats["seconds_paths"] = result.seconds_paths;
  stats["seconds_simplify"] = result.seconds_simplify;
  stats["seconds_optimize"] = result.seconds_optimize;
  stats["faces"] = mesh.triangles.size();
  stats["vertices"] = mesh.vertices.size();
  stats["refined_faces"] = result.triangles.size();
  stats["steiner_vertices"] = result.steiner.size();
  stats["steiner_fraction"] = double(result.steiner.size()) / double(mesh.vertices.size());
  stats["auxiliary_vertices"] = result.auxiliary_vertices;
  stats["retraced_paths"] = result.retraced_paths;
  stats["layout_flips"] = result.layout_flips;
  stats["max_constraint_error"] = result.max_constraint_error;

  const py::ssize_t s = py::ssize_t(result.steiner.size());
  py::array_t<std::int32_t> steiner_vertices({s, py::ssize_t(3)});
  py::array_t<double> steiner_weights({s, py::ssize_t(3)});
  std::vector<cmaps::Vec3> steiner_sphere(result.steiner.size());
  auto sv = steiner_vertices.mutable_unchecked<2>();
  auto sw = steiner_weights.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < s; ++i) {
    for (int k = 0; k < 3; ++k) sv(i, k) = result.steiner[i].vertices[k], sw(i, k) = result.steiner[i].weights[k];
    steiner_sphere[i] = result.steiner[i].sphere;
  }
  const cmaps::ParameterizedSurface surface = cmaps::parameterized_surface(mesh, result);
  py::dict extras;
  extras["steiner_vertices"] = steiner_vertices;
  extras["steiner_weights"] = steiner_weights;
  extras["steiner_sphere"] = to_numpy(steiner_sphere);
  extras["triangles"] = to_numpy(result.triangles);
  extras["input_triangle"] = py::array_t<std::int32_t>(py::ssize_t(result.input_triangle.size()),
                                                       result.input_triangle.data());
  extras["targets"] = to_numpy(result.targets);
  extras["refined_vertices"] = to_numpy(surface.surface.vertices);
  extras["refined_sphere"] = to_numpy(surface.sphere);
  return py::make_tuple(to_numpy(result.sphere), stats, extras);
}

}  // namespace cmaps::python
