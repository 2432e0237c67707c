// Spherical parameterizations: unconstrained, constrained, and measuring a given map.
#include <cstdint>
#include <string>
#include <vector>

#include "bindings.h"
#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/spherical_parameterization.h"
#include "consistent_maps/stretch_metric.h"
#include "conversions.h"
#include "python_progress.h"
#include "sphere_outputs.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

py::tuple spherical_parameterization(const py::handle& vertices, const py::handle& triangles, std::uint64_t seed,
                                     int effort, int threads, const py::object& progress) {
  const cmaps::SphereOptions options = sphere_options(seed, effort, threads, progress);
  const cmaps::TriangleMesh mesh = to_mesh(vertices, triangles);
  const auto [result, seconds] = run_released(progress, [&](const cmaps::ProgressCallback& callback) {
    return cmaps::spherical_parameterization(mesh, options, callback);
  });

  py::dict stats;
  add_map_report(stats, result.report);
  stats["seconds"] = seconds;
  stats["seconds_simplify"] = result.seconds_simplify;
  stats["seconds_optimize"] = result.seconds_optimize;
  stats["faces"] = mesh.triangles.size();
  stats["vertices"] = mesh.vertices.size();
  return py::make_tuple(to_numpy(result.sphere), stats);
}

// Feature vertex indices: a (k,) integer array-like, each a vertex of the mesh.
std::vector<int> to_features(const py::handle& data, std::size_t vertex_count) {
  const py::array array = as_array(data, "features");
  if (array.ndim() == 1 && array.size() == 0) return {};  // [] is float64 to numpy; the library names the problem
  const auto indices = to_integers(array, "features");
  if (indices.ndim() != 1) raise(PyExc_ValueError, "features must have shape (k,), got " + shape_of(indices));
  const auto f = indices.unchecked<1>();
  std::vector<int> features(f.shape(0));
  for (py::ssize_t i = 0; i < f.shape(0); ++i) {
    if (f(i) < 0 || f(i) >= std::int64_t(vertex_count))
      raise(invalid_mesh_error, "feature " + std::to_string(i) + " is vertex " + std::to_string(f(i)) +
                                    " but the mesh has " + std::to_string(vertex_count) + " vertices");
    features[i] = int(f(i));
  }
  return features;
}

py::tuple constrained_spherical_parameterization(const py::handle& vertices, const py::handle& triangles,
                                                 const py::handle& features_data, const py::object& targets_data,
                                                 std::uint64_t seed, int effort, int threads,
                                                 const py::object& progress) {
  const cmaps::SphereOptions options = sphere_options(seed, effort, threads, progress);
  const cmaps::TriangleMesh mesh = to_mesh(vertices, triangles);
  const std::vector<int> features = to_features(features_data, mesh.vertices.size());
  std::vector<cmaps::Vec3> targets;
  if (!targets_data.is_none()) {
    targets = to_points(targets_data, "targets");
    if (targets.size() != features.size())
      raise(PyExc_ValueError, "targets has " + std::to_string(targets.size()) + " rows for " +
                                  std::to_string(features.size()) + " features");
  }
  const auto [result, seconds] = run_released(progress, [&](const cmaps::ProgressCallback& callback) {
    return cmaps::constrained_spherical_parameterization(mesh, features, targets, options, callback);
  });
  return constrained_outputs(mesh, result, seconds);
}

py::dict measure_spherical_map(const py::handle& vertices, const py::handle& triangles, const py::handle& sphere) {
  const cmaps::TriangleMesh mesh = to_mesh(vertices, triangles);
  const std::vector<cmaps::Vec3> points = to_points(sphere, "sphere");
  if (points.size() != mesh.vertices.size())
    raise(PyExc_ValueError, "sphere has " + std::to_string(points.size()) + " rows but the mesh has " +
                                std::to_string(mesh.vertices.size()) + " vertices");
  cmaps::SphericalMapReport report;
  {
    py::gil_scoped_release release;
    report = cmaps::measure_spherical_map(mesh, points);
  }
  py::dict d;
  add_map_report(d, report);
  return d;
}

}  // namespace

void bind_sphere(py::module_& m) {
  m.def("spherical_parameterization", &spherical_parameterization, py::arg("vertices"), py::arg("triangles"),
        py::kw_only(), py::arg("seed") = 1, py::arg("effort") = 1, py::arg("threads") = 2,
        py::arg("progress") = py::none(),
        "Stretch-minimizing bijective map of a closed genus-0 mesh onto the unit sphere.\n"
        "Returns (sphere (n, 3) float64, stats dict). progress(fraction, stage) is called from the\n"
        "computation; returning False stops it with Cancelled. Raises InvalidMeshError for unsupported input.");
  m.def("constrained_spherical_parameterization", &constrained_spherical_parameterization, py::arg("vertices"),
        py::arg("triangles"), py::arg("features"), py::arg("targets") = py::none(), py::kw_only(),
        py::arg("seed") = 1, py::arg("effort") = 1, py::arg("threads") = 2, py::arg("progress") = py::none(),
        "Like spherical_parameterization, with every feature vertex exactly at its target.\n"
        "features: (k,) distinct vertex indices, k >= 3. targets: (k, 3) distinct directions (normalized),\n"
        "or None to take them from the unconstrained map. Returns (sphere (n, 3) float64, stats dict,\n"
        "extras dict). The map is piecewise linear on a refinement of the input: extras['triangles']\n"
        "(m', 3) int32 indexes the n input vertices followed by s Steiner vertices, vertex n + i lying on\n"
        "the input surface at sum_j extras['steiner_weights'][i, j] * vertices[extras['steiner_vertices'][i, j]]\n"
        "(unused slots are -1 with weight 0) and mapped to extras['steiner_sphere'][i];\n"
        "extras['input_triangle'][t] is the input triangle refined triangle t lies in; extras['targets'] is\n"
        "(k, 3), the targets used. Raises InvalidMeshError for unsupported input or bad features/targets,\n"
        "Cancelled when progress returns False.");
  m.def("measure_spherical_map", &measure_spherical_map, py::arg("vertices"), py::arg("triangles"),
        py::arg("sphere"), "Stretch and bijectivity measures of a map of the mesh onto the unit sphere.");
}

}  // namespace cmaps::python
