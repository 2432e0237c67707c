// consistent_maps._native: the library for Python (and so for Blender).
// Arrays come in as any real/integer numpy-compatible data and are validated
// here, so the library only ever sees well-formed index arrays; long
// computations release the GIL and report progress through a Python callable.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/spherical_parameterization.h"
#include "consistent_maps/stretch_metric.h"
#include "consistent_maps/version.h"

namespace py = pybind11;

namespace {

// Python exception types, created once at import and kept alive for the process.
PyObject* invalid_mesh_error = nullptr;
PyObject* mesh_io_error = nullptr;
PyObject* cancelled_error = nullptr;

[[noreturn]] void raise(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

py::array as_array(const py::handle& data, const char* name) {
  py::array array = py::array::ensure(data);
  if (!array) {
    PyErr_Clear();
    raise(PyExc_TypeError, std::string(name) + " must be an array-like of numbers");
  }
  return array;
}

std::string shape_of(const py::array& array) {
  std::string shape;
  for (py::ssize_t d = 0; d < array.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(array.shape(d));
  if (array.ndim() == 1) shape += ",";
  return "(" + shape + ")";
}

void require_n_by_3(const py::array& array, const char* name) {
  if (array.ndim() == 2 && array.shape(1) == 3) return;
  raise(PyExc_ValueError, std::string(name) + " must have shape (n, 3), got " + shape_of(array));
}

// Any integer array-like as C-contiguous int64 (bools and floats are refused).
py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> to_integers(const py::handle& data,
                                                                                 const char* name) {
  py::array array = as_array(data, name);
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    raise(PyExc_TypeError, std::string(name) + " must hold integers, got dtype " + std::string(py::str(array.dtype())));
  return py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
}

std::vector<cmaps::Vec3> to_points(const py::handle& data, const char* name) {
  py::array array = as_array(data, name);
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    raise(PyExc_TypeError, std::string(name) + " must hold real numbers, got dtype " +
                               std::string(py::str(array.dtype())));
  require_n_by_3(array, name);
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  const auto v = values.unchecked<2>();
  std::vector<cmaps::Vec3> points(v.shape(0));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) points[i] = {v(i, 0), v(i, 1), v(i, 2)};
  return points;
}

cmaps::TriangleMesh to_mesh(const py::handle& vertices, const py::handle& triangles) {
  cmaps::TriangleMesh mesh;
  mesh.vertices = to_points(vertices, "vertices");
  const auto indices = to_integers(triangles, "triangles");
  require_n_by_3(indices, "triangles");
  const auto t = indices.unchecked<2>();
  const std::int64_t n = std::int64_t(mesh.vertices.size());
  mesh.triangles.resize(t.shape(0));
  for (py::ssize_t f = 0; f < t.shape(0); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = t(f, k);
      if (v < 0 || v >= n)
        raise(invalid_mesh_error, "triangle " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                      " but the mesh has " + std::to_string(n) + " vertices");
      mesh.triangles[f][k] = int(v);
    }
  }
  return mesh;
}

py::array_t<double> to_numpy(const std::vector<cmaps::Vec3>& points) {
  py::array_t<double> array({py::ssize_t(points.size()), py::ssize_t(3)});
  auto a = array.mutable_unchecked<2>();
  for (size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) a(i, k) = points[i][k];
  return array;
}

py::array_t<std::int32_t> to_numpy(const std::vector<cmaps::Triangle>& triangles) {
  py::array_t<std::int32_t> array({py::ssize_t(triangles.size()), py::ssize_t(3)});
  auto t = array.mutable_unchecked<2>();
  for (size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) t(f, k) = triangles[f][k];
  return array;
}

py::dict report_dict(const cmaps::MeshReport& r) {
  py::dict d;
  d["vertices"] = r.vertices;
  d["referenced_vertices"] = r.referenced_vertices;
  d["faces"] = r.faces;
  d["components"] = r.components;
  d["boundary_loops"] = r.boundary_loops;
  d["euler_characteristic"] = r.euler_characteristic;
  d["genus"] = r.genus;
  d["manifold"] = r.manifold();
  d["closed"] = r.closed();
  d["non_manifold_edges"] = r.non_manifold_edges;
  d["non_manifold_vertices"] = r.non_manifold_vertices;
  d["degenerate_faces"] = r.degenerate_faces;
  d["duplicate_faces"] = r.duplicate_faces;
  d["inconsistently_oriented_edges"] = r.inconsistently_oriented_edges;
  d["non_finite_vertices"] = r.non_finite_vertices;
  d["out_of_range_indices"] = r.out_of_range_indices;
  d["summary"] = cmaps::summarize(r);
  return d;
}

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

py::tuple read_mesh(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) raise(PyExc_FileNotFoundError, "cannot read '" + path.string() + "': no such file");
  cmaps::TriangleMesh mesh;
  {
    py::gil_scoped_release release;
    mesh = cmaps::read_mesh(path.string());
  }
  return py::make_tuple(to_numpy(mesh.vertices), to_numpy(mesh.triangles));
}

py::dict check_mesh(const py::handle& vertices, const py::handle& triangles) {
  const cmaps::TriangleMesh mesh = to_mesh(vertices, triangles);
  cmaps::MeshReport report;
  std::optional<std::string> problem;
  {
    py::gil_scoped_release release;
    report = cmaps::check_mesh(mesh);
    try {
      cmaps::require_sphere_topology(mesh);
    } catch (const cmaps::InvalidInput& e) {
      problem = e.what();
    }
  }
  py::dict d = report_dict(report);
  d["sphere_error"] = problem ? py::object(py::str(*problem)) : py::object(py::none());
  return d;
}

// Forwards progress to Python with the GIL held. It never lets an exception
// escape into the library (which may call it from a worker thread): a Python
// error or a pending Ctrl-C is stored and turned into a cancellation, and
// re-raised once the computation has unwound.
class PythonProgress {
 public:
  explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {}

  bool operator()(double fraction, const std::string& stage) {
    py::gil_scoped_acquire gil;
    if (stop_) return false;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback_.is_none() && callback_(fraction, stage).ptr() == Py_False) stop_ = true;
    } catch (py::error_already_set& e) {
      error_ = std::move(e);
      stop_ = true;
    }
    return !stop_;
  }

  // Call with the GIL held, after the computation.
  void rethrow_python_error() {
    if (error_) throw std::move(*error_);
  }

 private:
  py::object callback_;
  bool stop_ = false;  // guarded by the GIL
  std::optional<py::error_already_set> error_;
};

// Checks the keyword arguments shared by the parameterizations.
cmaps::SphereOptions sphere_options(std::uint64_t seed, int effort, int threads, const py::object& progress) {
  if (effort < 0 || effort > 2) raise(PyExc_ValueError, "effort must be 0, 1 or 2, got " + std::to_string(effort));
  if (threads < 1) raise(PyExc_ValueError, "threads must be at least 1, got " + std::to_string(threads));
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    raise(PyExc_TypeError, "progress must be a callable (fraction, stage) -> bool, or None");
  cmaps::SphereOptions options;
  options.seed = seed;
  options.effort = effort;
  options.threads = threads;
  return options;
}

py::tuple spherical_parameterization(const py::handle& vertices, const py::handle& triangles, std::uint64_t seed,
                                     int effort, int threads, const py::object& progress) {
  const cmaps::SphereOptions options = sphere_options(seed, effort, threads, progress);
  const cmaps::TriangleMesh mesh = to_mesh(vertices, triangles);
  PythonProgress forward(progress);
  const cmaps::ProgressCallback callback = [&forward](double fraction, const std::string& stage) {
    return forward(fraction, stage);
  };

  cmaps::SphereResult result;
  double seconds = 0;
  try {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    result = cmaps::spherical_parameterization(mesh, options, callback);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } catch (const cmaps::Cancelled&) {
    forward.rethrow_python_error();
    throw;
  }

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
  PythonProgress forward(progress);
  const cmaps::ProgressCallback callback = [&forward](double fraction, const std::string& stage) {
    return forward(fraction, stage);
  };

  cmaps::ConstrainedResult result;
  double seconds = 0;
  try {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    result = cmaps::constrained_spherical_parameterization(mesh, features, targets, options, callback);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } catch (const cmaps::Cancelled&) {
    forward.rethrow_python_error();
    throw;
  }

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
  py::dict extras;
  extras["steiner_vertices"] = steiner_vertices;
  extras["steiner_weights"] = steiner_weights;
  extras["steiner_sphere"] = to_numpy(steiner_sphere);
  extras["triangles"] = to_numpy(result.triangles);
  extras["targets"] = to_numpy(result.targets);
  return py::make_tuple(to_numpy(result.sphere), stats, extras);
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

PyObject* new_exception(py::module_& m, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = "consistent_maps._native." + std::string(name);
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (!type) throw py::error_already_set();
  m.attr(name) = py::handle(type);
  return type;
}

}  // namespace

PYBIND11_MODULE(_native, m) {
  m.doc() = "Native core of Consistent Maps: mesh I/O, validation and spherical parameterization.";
  m.attr("__version__") = cmaps::kVersion;

  invalid_mesh_error = new_exception(m, "InvalidMeshError", PyExc_ValueError,
                                     "The mesh cannot be processed: bad data or unsupported topology.");
  mesh_io_error = new_exception(m, "MeshIOError", PyExc_OSError, "A mesh file could not be read or written.");
  cancelled_error = new_exception(m, "Cancelled", PyExc_Exception, "The progress callback returned False.");

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const cmaps::Cancelled& e) {
      PyErr_SetString(cancelled_error, e.what());
    } catch (const cmaps::InvalidInput& e) {
      PyErr_SetString(invalid_mesh_error, e.what());
    } catch (const cmaps::IoError& e) {
      PyErr_SetString(mesh_io_error, e.what());
    } catch (const cmaps::Error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  m.def("read_mesh", &read_mesh, py::arg("path"),
        "Reads an OBJ, OFF, PLY or STL file. Returns (vertices (n, 3) float64, triangles (m, 3) int32);\n"
        "polygons are fan-triangulated. Raises FileNotFoundError or MeshIOError.");
  m.def("check_mesh", &check_mesh, py::arg("vertices"), py::arg("triangles"),
        "Topology and defect report of a triangle mesh, as a dict. 'sphere_error' is None when the mesh\n"
        "can be mapped to the sphere, else the reason it cannot.");
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
        "(unused slots are -1 with weight 0) and mapped to extras['steiner_sphere'][i]; extras['targets'] is\n"
        "(k, 3), the targets used. Raises InvalidMeshError for unsupported input or bad features/targets,\n"
        "Cancelled when progress returns False.");
  m.def("measure_spherical_map", &measure_spherical_map, py::arg("vertices"), py::arg("triangles"),
        py::arg("sphere"), "Stretch and bijectivity measures of a map of the mesh onto the unit sphere.");
}
