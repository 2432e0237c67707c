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

void require_n_by_3(const py::array& array, const char* name) {
  if (array.ndim() == 2 && array.shape(1) == 3) return;
  std::string shape;
  for (py::ssize_t d = 0; d < array.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(array.shape(d));
  if (array.ndim() == 1) shape += ",";
  raise(PyExc_ValueError, std::string(name) + " must have shape (n, 3), got (" + shape + ")");
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
  py::array array = as_array(triangles, "triangles");
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    raise(PyExc_TypeError, "triangles must hold integers, got dtype " + std::string(py::str(array.dtype())));
  require_n_by_3(array, "triangles");
  const auto indices = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
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
  py::array_t<std::int32_t> triangles({py::ssize_t(mesh.triangles.size()), py::ssize_t(3)});
  auto t = triangles.mutable_unchecked<2>();
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) t(f, k) = mesh.triangles[f][k];
  return py::make_tuple(to_numpy(mesh.vertices), triangles);
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

py::tuple spherical_parameterization(const py::handle& vertices, const py::handle& triangles, std::uint64_t seed,
                                     int effort, int threads, const py::object& progress) {
  if (effort < 0 || effort > 2) raise(PyExc_ValueError, "effort must be 0, 1 or 2, got " + std::to_string(effort));
  if (threads < 1) raise(PyExc_ValueError, "threads must be at least 1, got " + std::to_string(threads));
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    raise(PyExc_TypeError, "progress must be a callable (fraction, stage) -> bool, or None");
  const cmaps::TriangleMesh mesh = to_mesh(vertices, triangles);
  cmaps::SphereOptions options;
  options.seed = seed;
  options.effort = effort;
  options.threads = threads;
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
  m.def("measure_spherical_map", &measure_spherical_map, py::arg("vertices"), py::arg("triangles"),
        py::arg("sphere"), "Stretch and bijectivity measures of a map of the mesh onto the unit sphere.");
}
