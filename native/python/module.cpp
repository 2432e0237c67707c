// consistent_maps._native: the library for Python (and so for Blender).
// Arrays come in as any real/integer numpy-compatible data and are validated
// here, so the library only ever sees well-formed index arrays; long
// computations release the GIL and report progress through a Python callable.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "consistent_maps/attribute_transfer.h"
#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/octahedral_grid.h"
#include "consistent_maps/remesh.h"
#include "consistent_maps/sphere_locator.h"
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

// (m, 3) vertex indices, each in [0, vertex_count).
std::vector<cmaps::Triangle> to_triangles(const py::handle& triangles, std::size_t vertex_count) {
  const auto indices = to_integers(triangles, "triangles");
  require_n_by_3(indices, "triangles");
  const auto t = indices.unchecked<2>();
  const std::int64_t n = std::int64_t(vertex_count);
  std::vector<cmaps::Triangle> result(t.shape(0));
  for (py::ssize_t f = 0; f < t.shape(0); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = t(f, k);
      if (v < 0 || v >= n)
        raise(invalid_mesh_error, "triangle " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                      " but the mesh has " + std::to_string(n) + " vertices");
      result[f][k] = int(v);
    }
  }
  return result;
}

cmaps::TriangleMesh to_mesh(const py::handle& vertices, const py::handle& triangles) {
  cmaps::TriangleMesh mesh;
  mesh.vertices = to_points(vertices, "vertices");
  mesh.triangles = to_triangles(triangles, mesh.vertices.size());
  return mesh;
}

py::array_t<double> to_numpy(const std::vector<double>& values) {
  return py::array_t<double>(py::ssize_t(values.size()), values.data());
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

// Runs `compute(callback)` without the GIL, forwarding its progress to the
// Python callable; returns {its result, wall seconds}. A Python error raised
// by the callable is re-raised here in place of the cancellation it caused.
template <class Compute>
auto run_released(const py::object& progress, Compute&& compute) {
  PythonProgress forward(progress);
  const cmaps::ProgressCallback callback = [&forward](double fraction, const std::string& stage) {
    return forward(fraction, stage);
  };
  try {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    auto result = compute(callback);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::make_pair(std::move(result), seconds);
  } catch (const cmaps::Cancelled&) {
    forward.rethrow_python_error();
    throw;
  }
}

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

// A constrained map as Python sees it: (sphere, stats, extras). `seconds` is the
// wall time of the computation it came from.
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

// ------------------------------------------------------------------ consistent sets

// One member's features: per feature a vertex index in [0, vertex_count) or
// -1 (the member lacks it), no vertex twice. `label` names the row in messages.
std::vector<int> feature_row(const std::int64_t* data, py::ssize_t count, std::size_t vertex_count,
                             const std::string& label) {
  std::vector<int> row(count);
  std::map<std::int64_t, py::ssize_t> seen;
  for (py::ssize_t k = 0; k < count; ++k) {
    const std::int64_t v = data[k];
    if (v < -1 || v >= std::int64_t(vertex_count))
      raise(invalid_mesh_error, label + "[" + std::to_string(k) + "] is vertex " + std::to_string(v) +
                                    " but the mesh has " + std::to_string(vertex_count) +
                                    " vertices (-1 marks a missing feature)");
    if (v >= 0) {
      const auto [it, inserted] = seen.emplace(v, k);
      if (!inserted)
        raise(invalid_mesh_error, label + "[" + std::to_string(it->second) + "] and " + label + "[" +
                                      std::to_string(k) + "] are both vertex " + std::to_string(v));
    }
    row[k] = int(v);
  }
  return row;
}

using IntegerArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

// Features with -1 for missing: an integer array-like of shape (k,) when
// `rows` is 0, else (rows, k). Empty lists (float64 to numpy) are allowed.
IntegerArray to_feature_array(const py::handle& data, py::ssize_t rows) {
  const py::array array = as_array(data, "features");
  const std::string expected = rows ? "(" + std::to_string(rows) + ", k), one row per mesh" : std::string("(k,)");
  const bool shaped = rows ? array.ndim() == 2 && array.shape(0) == rows : array.ndim() == 1;
  if (!shaped) raise(PyExc_ValueError, "features must have shape " + expected + ", got " + shape_of(array));
  if (array.size() == 0)
    return rows ? IntegerArray(std::vector<py::ssize_t>{rows, 0}) : IntegerArray(std::vector<py::ssize_t>{0});
  return to_integers(array, "features");
}

// A (vertices, triangles) pair; `name` labels it in messages.
cmaps::TriangleMesh to_mesh_pair(const py::handle& item, const std::string& name) {
  if (!py::isinstance<py::sequence>(item) || py::isinstance<py::str>(item) || py::len(item) != 2)
    raise(PyExc_TypeError, name + " must be a (vertices, triangles) pair");
  return to_mesh(item[py::int_(0)], item[py::int_(1)]);
}

// A sequence of (vertices, triangles) pairs, each a genus-0 mesh, closed or with holes.
std::vector<cmaps::TriangleMesh> to_meshes(const py::handle& meshes) {
  if (!py::isinstance<py::sequence>(meshes) || py::isinstance<py::str>(meshes))
    raise(PyExc_TypeError, "meshes must be a sequence of (vertices, triangles) pairs");
  const auto items = py::reinterpret_borrow<py::sequence>(meshes);
  std::vector<cmaps::TriangleMesh> result;
  for (std::size_t i = 0; i < items.size(); ++i) {
    result.push_back(to_mesh_pair(items[i], "meshes[" + std::to_string(i) + "]"));
    try {
      cmaps::require_sphere_topology(result.back(), true);
    } catch (const cmaps::InvalidInput& e) {
      raise(invalid_mesh_error, "meshes[" + std::to_string(i) + "]: " + e.what());
    }
  }
  return result;
}

void require_grid_resolution(int n, const char* name) {
  if (n < 2 || n % 2 != 0)
    raise(PyExc_ValueError, std::string(name) + " must be even and at least 2, got " + std::to_string(n));
}

py::dict consistent_spherical_parameterization(const py::handle& meshes_data, const py::handle& features_data,
                                               int first, int grid, int restarts, bool align, std::uint64_t seed,
                                               int effort, int threads, const py::object& progress) {
  cmaps::ConsistentOptions options;
  options.sphere = sphere_options(seed, effort, threads, progress);
  options.grid = grid;
  options.first = first;
  if (restarts < 1) raise(PyExc_ValueError, "restarts must be at least 1, got " + std::to_string(restarts));
  options.restarts = restarts;
  options.align = align;
  require_grid_resolution(grid, "grid");
  std::vector<cmaps::TriangleMesh> meshes = to_meshes(meshes_data);
  if (meshes.size() < 2)
    raise(PyExc_ValueError, "a consistent set needs at least 2 meshes, got " + std::to_string(meshes.size()));
  if (first < -1 || first >= int(meshes.size()))
    raise(PyExc_ValueError, "first must be -1 (automatic) or a mesh index below " + std::to_string(meshes.size()) +
                                ", got " + std::to_string(first));
  const IntegerArray table = to_feature_array(features_data, py::ssize_t(meshes.size()));
  std::vector<cmaps::ConsistentMember> members;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    std::vector<int> row = feature_row(table.data() + i * table.shape(1), table.shape(1), meshes[i].vertices.size(),
                                       "features[" + std::to_string(i) + "]");
    members.push_back({std::move(meshes[i]), std::move(row)});
  }

  const auto [result, seconds] = run_released(progress, [&](const cmaps::ProgressCallback& callback) {
    return cmaps::consistent_spherical_parameterization(members, options, callback);
  });
  py::list maps;
  for (std::size_t i = 0; i < members.size(); ++i) {
    const cmaps::ConstrainedResult& map = result.members[i];
    maps.append(constrained_outputs(members[i].mesh, map,
                                    map.seconds_paths + map.seconds_simplify + map.seconds_optimize));
  }
  py::dict d;
  d["feature_locations"] = to_numpy(result.feature_locations);
  d["initial_locations"] = to_numpy(result.initial_locations);
  d["first"] = result.first;
  d["restart"] = result.restart;
  d["suitability"] = result.suitability;
  d["restart_suitability"] = to_numpy(result.restart_suitability);
  d["seconds"] = seconds;
  d["members"] = maps;
  return d;
}

py::tuple parameterize_to_locations(const py::handle& vertices, const py::handle& triangles,
                                    const py::handle& features_data, const py::handle& locations_data,
                                    std::uint64_t seed, int effort, int threads, const py::object& progress) {
  const cmaps::SphereOptions options = sphere_options(seed, effort, threads, progress);
  cmaps::ConsistentMember member{to_mesh(vertices, triangles), {}};
  const IntegerArray features = to_feature_array(features_data, 0);
  member.features = feature_row(features.data(), features.shape(0), member.mesh.vertices.size(), "features");
  const std::vector<cmaps::Vec3> locations = to_points(locations_data, "locations");
  if (locations.size() != member.features.size())
    raise(PyExc_ValueError, "locations has " + std::to_string(locations.size()) + " rows for " +
                                std::to_string(member.features.size()) + " features");
  const auto [result, seconds] = run_released(progress, [&](const cmaps::ProgressCallback& callback) {
    return cmaps::parameterize_to_locations(member, locations, options, callback);
  });
  return constrained_outputs(member.mesh, result, seconds);
}

// ------------------------------------------------------------------ inter-surface maps

// (k, 2) integer pairs [index_in_A, index_in_B]; empty lists are allowed. The
// library checks the ranges and repeats.
std::vector<cmaps::FeaturePair> to_feature_pairs(const py::handle& data) {
  const py::array array = as_array(data, "feature_pairs");
  if (array.size() == 0 && (array.ndim() == 1 || (array.ndim() == 2 && array.shape(1) == 2))) return {};
  const auto pairs = to_integers(array, "feature_pairs");
  if (pairs.ndim() != 2 || pairs.shape(1) != 2)
    raise(PyExc_ValueError, "feature_pairs must have shape (k, 2), got " + shape_of(pairs));
  const auto p = pairs.unchecked<2>();
  std::vector<cmaps::FeaturePair> result(p.shape(0));
  const auto index = [](std::int64_t v) { return int(std::clamp<std::int64_t>(v, -1, 1LL << 30)); };
  for (py::ssize_t k = 0; k < p.shape(0); ++k) result[k] = {index(p(k, 0)), index(p(k, 1))};
  return result;
}

py::array_t<std::int32_t> to_numpy(const std::vector<int>& values) {
  return py::array_t<std::int32_t>(py::ssize_t(values.size()), values.data());
}

// Per source vertex: (triangles (n,) int32, barycentric (n, 3) float64).
std::pair<py::array_t<std::int32_t>, py::array_t<double>> to_numpy(const std::vector<cmaps::SurfacePoint>& points) {
  std::vector<int> triangles(points.size());
  py::array_t<double> barycentric({py::ssize_t(points.size()), py::ssize_t(3)});
  auto b = barycentric.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    triangles[i] = points[i].triangle;
    for (int k = 0; k < 3; ++k) b(i, k) = points[i].barycentric[k];
  }
  return {to_numpy(triangles), barycentric};
}

py::dict intersurface_map(const py::handle& mesh_a, const py::handle& mesh_b, const py::handle& pairs_data, int grid,
                          int optimize, int restarts, bool corner_images, int balance_rounds, int cross_sweeps,
                          int starts, const std::string& method,
                          std::uint64_t seed, int effort, int threads, const py::object& progress) {
  cmaps::IntersurfaceOptions options;
  const std::optional<cmaps::IntersurfaceMethod> chosen = cmaps::parse_method(method);
  if (!chosen) raise(PyExc_ValueError, "method must be 'auto', 'sphere' or 'partition', got '" + method + "'");
  options.method = *chosen;
  options.corner_images = corner_images;
  if (balance_rounds < 0)
    raise(PyExc_ValueError, "balance_rounds must be at least 0, got " + std::to_string(balance_rounds));
  options.balance_rounds = balance_rounds;
  if (cross_sweeps < 0) raise(PyExc_ValueError, "cross_sweeps must be at least 0, got " + std::to_string(cross_sweeps));
  options.cross_sweeps = cross_sweeps;
  if (optimize < 0) raise(PyExc_ValueError, "optimize must be at least 0, got " + std::to_string(optimize));
  if (restarts < 1) raise(PyExc_ValueError, "restarts must be at least 1, got " + std::to_string(restarts));
  options.restarts = restarts;
  if (starts < 1) raise(PyExc_ValueError, "starts must be at least 1, got " + std::to_string(starts));
  options.starts = starts;
  options.optimize_rounds = optimize;
  if (optimize == 0) options.correspondence_weight = 0;  // the plain composition
  options.sphere = sphere_options(seed, effort, threads, progress);
  require_grid_resolution(grid, "grid");
  options.grid = grid;
  const cmaps::TriangleMesh a = to_mesh_pair(mesh_a, "mesh_a"), b = to_mesh_pair(mesh_b, "mesh_b");
  const std::vector<cmaps::FeaturePair> pairs = to_feature_pairs(pairs_data);
  const auto [result, seconds] = run_released(progress, [&](const cmaps::ProgressCallback& callback) {
    return cmaps::intersurface_map(a, b, pairs, options, callback);
  });

  py::dict d;
  // Points on a mesh as '<name>_triangle' (n,) and '<name>_barycentric' (n, 3).
  const auto put = [&d](const std::string& name, const std::vector<cmaps::SurfacePoint>& points) {
    const auto [triangles, barycentric] = to_numpy(points);
    d[(name + "_triangle").c_str()] = triangles;
    d[(name + "_barycentric").c_str()] = barycentric;
  };
  put("a_to_b", result.a_to_b);
  put("b_to_a", result.b_to_a);
  if (corner_images) {
    put("a_corners_to_b", result.a_corners_to_b);
    put("b_corners_to_a", result.b_corners_to_a);
  }
  d["a_on_b"] = to_numpy(result.a_on_b);
  d["b_on_a"] = to_numpy(result.b_on_a);
  py::array_t<std::int32_t> features({py::ssize_t(result.features.size()), py::ssize_t(2)});
  auto f = features.mutable_unchecked<2>();
  for (std::size_t k = 0; k < result.features.size(); ++k) f(k, 0) = result.features[k].a, f(k, 1) = result.features[k].b;
  d["features"] = features;
  d["added_features"] = result.added_features;
  d["genus"] = result.genus;
  d["method"] = cmaps::method_name(result.method);
  const auto computed = [](double median) { return median < 0 ? py::object(py::none()) : py::object(py::float_(median)); };
  d["sphere_median_dirichlet"] = computed(result.sphere_median_dirichlet);
  d["partition_median_dirichlet"] = computed(result.partition_median_dirichlet);
  const cmaps::MapDistortion &ab = result.distortion_a_to_b, &ba = result.distortion_b_to_a;
  d["symmetric_dirichlet"] = py::make_tuple(ab.symmetric_dirichlet, ba.symmetric_dirichlet);
  d["flipped"] = py::make_tuple(ab.flipped, ba.flipped);
  d["degenerate"] = py::make_tuple(ab.degenerate, ba.degenerate);
  d["sphere_flipped"] = result.sphere_flipped;
  d["refitted"] = py::make_tuple(result.refitted_a, result.refitted_b);
  d["balanced_patches"] = result.balanced_patches;
  d["patch_area_ratio"] = result.patch_area_ratio;
  d["stretch_efficiency"] = py::make_tuple(result.efficiency_a, result.efficiency_b);
  d["steiner"] = py::make_tuple(result.steiner_a, result.steiner_b);
  d["restart_dirichlet"] = to_numpy(result.restart_dirichlet);
  d["restart_median_dirichlet"] = to_numpy(result.restart_median_dirichlet);
  d["restart_flipped"] = py::array_t<int>(result.restart_flipped.size(), result.restart_flipped.data());
  d["start_median_dirichlet"] = to_numpy(result.start_median_dirichlet);
  d["median_symmetric_dirichlet"] = py::make_tuple(ab.median_symmetric_dirichlet, ba.median_symmetric_dirichlet);
  d["seconds"] = seconds;
  d["base_vertices"] = result.base_vertices;
  d["base_triangles"] = result.base_triangles;
  d["seconds_features"] = result.seconds_features;
  d["composition_dirichlet"] = py::make_tuple(result.composition_a_to_b.symmetric_dirichlet,
                                              result.composition_b_to_a.symmetric_dirichlet);
  d["seconds_partition"] = result.seconds_partition;
  d["seconds_parameterize"] = result.seconds_parameterize;
  d["seconds_optimize"] = result.seconds_optimize;
  d["seconds_locate"] = result.seconds_locate;
  d["seconds_measure"] = result.seconds_measure;
  return d;
}

// Per member (vertices, triangles, sphere): a parameterized surface.
struct Surface {
  cmaps::TriangleMesh mesh;
  std::vector<cmaps::Vec3> sphere;
};

py::dict consistent_remesh(const py::handle& surfaces_data, const py::handle& locations_data, int n, int threads) {
  require_grid_resolution(n, "n");
  if (threads < 1) raise(PyExc_ValueError, "threads must be at least 1, got " + std::to_string(threads));
  if (!py::isinstance<py::sequence>(surfaces_data) || py::isinstance<py::str>(surfaces_data))
    raise(PyExc_TypeError, "surfaces must be a sequence of (vertices, triangles, sphere) triples");
  const auto items = py::reinterpret_borrow<py::sequence>(surfaces_data);
  std::vector<Surface> surfaces;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const py::object item = items[i];
    if (!py::isinstance<py::sequence>(item) || py::len(item) != 3)
      raise(PyExc_TypeError, "surfaces[" + std::to_string(i) + "] must be a (vertices, triangles, sphere) triple");
    Surface s{to_mesh(item[py::int_(0)], item[py::int_(1)]), to_points(item[py::int_(2)], "sphere")};
    if (s.sphere.size() != s.mesh.vertices.size())
      raise(PyExc_ValueError, "surfaces[" + std::to_string(i) + "]: sphere has " + std::to_string(s.sphere.size()) +
                                  " rows for " + std::to_string(s.mesh.vertices.size()) + " vertices");
    surfaces.push_back(std::move(s));
  }
  const std::vector<cmaps::Vec3> locations = to_points(locations_data, "feature_locations");

  cmaps::OctahedralGrid grid;
  std::vector<int> feature_vertices;
  std::vector<std::vector<cmaps::Vec3>> positions;
  {
    py::gil_scoped_release release;
    grid = cmaps::octahedral_grid(n);
    feature_vertices = cmaps::snap_features(grid.sphere, locations);
    for (const Surface& s : surfaces) positions.push_back(cmaps::resample(s.mesh, s.sphere, grid.sphere, threads));
  }
  const py::ssize_t v = py::ssize_t(grid.sphere.size());
  py::array_t<double> stacked({py::ssize_t(surfaces.size()), v, py::ssize_t(3)});
  double* out = stacked.mutable_data();
  for (const auto& p : positions)
    for (const cmaps::Vec3& x : p) out[0] = x.x(), out[1] = x.y(), out[2] = x.z(), out += 3;
  py::dict d;
  d["sphere"] = to_numpy(grid.sphere);
  d["triangles"] = to_numpy(grid.triangles);
  d["positions"] = stacked;
  d["feature_vertices"] = py::array_t<std::int32_t>(py::ssize_t(feature_vertices.size()), feature_vertices.data());
  return d;
}

// ------------------------------------------------------------------ grids and geometry images

py::array_t<std::int32_t> pixel_array(const cmaps::OctahedralGrid& grid) {
  const py::ssize_t side = grid.n + 1;
  py::array_t<std::int32_t> pixels({side, side});
  std::copy(grid.pixel_vertex.begin(), grid.pixel_vertex.end(), pixels.mutable_data());
  return pixels;
}

py::tuple octahedral_grid(int n) {
  require_grid_resolution(n, "n");
  cmaps::OctahedralGrid grid;
  {
    py::gil_scoped_release release;
    grid = cmaps::octahedral_grid(n);
  }
  return py::make_tuple(to_numpy(grid.sphere), to_numpy(grid.triangles), pixel_array(grid));
}

cmaps::GeometryImage to_image(const py::handle& data) {
  py::array array = as_array(data, "image");
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    raise(PyExc_TypeError, "image must hold real numbers, got dtype " + std::string(py::str(array.dtype())));
  if (array.ndim() != 3 || array.shape(0) != array.shape(1) || array.shape(2) != 3 || array.shape(0) < 3 ||
      (array.shape(0) - 1) % 2 != 0)
    raise(PyExc_ValueError, "image must have shape (n+1, n+1, 3) with n even and at least 2, got " + shape_of(array));
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  cmaps::GeometryImage image;
  image.n = int(array.shape(0) - 1);
  image.pixels.resize(std::size_t(values.size() / 3));
  const double* v = values.data();
  for (cmaps::Vec3& p : image.pixels) p = {v[0], v[1], v[2]}, v += 3;
  return image;
}

py::array_t<double> image_array(const cmaps::GeometryImage& image) {
  const py::ssize_t side = image.n + 1;
  py::array_t<double> array({side, side, py::ssize_t(3)});
  double* out = array.mutable_data();
  for (const cmaps::Vec3& p : image.pixels) out[0] = p.x(), out[1] = p.y(), out[2] = p.z(), out += 3;
  return array;
}

// ".npy" or ".png" (any case): the geometry image format of a path.
bool is_png(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".npy" && ext != ".png")
    raise(PyExc_ValueError, "geometry image path '" + path.string() + "' must end in .npy or .png");
  return ext == ".png";
}

void write_geometry_image(const std::filesystem::path& path, const py::handle& data) {
  const bool png = is_png(path);
  const cmaps::GeometryImage image = to_image(data);
  py::gil_scoped_release release;
  if (png) cmaps::write_geometry_image_png(path.string(), image);
  else cmaps::write_geometry_image_npy(path.string(), image);
}

py::array_t<double> read_geometry_image(const std::filesystem::path& path) {
  const bool png = is_png(path);
  if (!std::filesystem::exists(path))
    raise(PyExc_FileNotFoundError, "cannot read '" + path.string() + "': no such file");
  cmaps::GeometryImage image;
  {
    py::gil_scoped_release release;
    image = png ? cmaps::read_geometry_image_png(path.string()) : cmaps::read_geometry_image_npy(path.string());
  }
  return image_array(image);
}

py::tuple geometry_image_mesh(const py::handle& data) {
  const cmaps::GeometryImage image = to_image(data);
  cmaps::TriangleMesh mesh;
  {
    py::gil_scoped_release release;
    mesh = cmaps::geometry_image_mesh(image);
  }
  return py::make_tuple(to_numpy(mesh.vertices), to_numpy(mesh.triangles));
}

py::array_t<double> vertex_normals(const py::handle& vertices, const py::handle& triangles) {
  const cmaps::TriangleMesh mesh = to_mesh(vertices, triangles);
  std::vector<cmaps::Vec3> normals;
  {
    py::gil_scoped_release release;
    normals = cmaps::vertex_normals(mesh);
  }
  return to_numpy(normals);
}

// ------------------------------------------------------------------ attribute transfer

// (n,) integers, each in [0, limit) when limit >= 0.
std::vector<int> to_index_vector(const py::handle& data, const char* name, std::int64_t limit) {
  const auto indices = to_integers(data, name);
  if (indices.ndim() != 1) raise(PyExc_ValueError, std::string(name) + " must have shape (n,), got " + shape_of(indices));
  std::vector<int> result(std::size_t(indices.shape(0)));
  for (std::size_t i = 0; i < result.size(); ++i) {
    const std::int64_t v = indices.data()[i];
    if (v < 0 || (limit >= 0 && v >= limit))
      raise(PyExc_IndexError, std::string(name) + "[" + std::to_string(i) + "] is " + std::to_string(v) +
                                  ", out of range [0, " + std::to_string(limit) + ")");
    result[i] = int(v);
  }
  return result;
}

// (n, 2) real numbers.
std::vector<std::array<double, 2>> to_pairs(const py::handle& data, const char* name) {
  const py::array array = as_array(data, name);
  if (array.ndim() != 2 || array.shape(1) != 2)
    raise(PyExc_ValueError, std::string(name) + " must have shape (n, 2), got " + shape_of(array));
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  std::vector<std::array<double, 2>> result(std::size_t(values.shape(0)));
  for (std::size_t i = 0; i < result.size(); ++i) result[i] = {values.data()[2 * i], values.data()[2 * i + 1]};
  return result;
}

py::array_t<double> continue_across_seams(const py::handle& triangles_data, const py::handle& triangle_uvs_data,
                                          const py::handle& uvs_data, const py::handle& point_triangles_data,
                                          const py::handle& values_data, const py::handle& reference_data) {
  const std::vector<std::array<double, 2>> uvs = to_pairs(uvs_data, "uvs");
  const auto corner_indices = to_integers(triangle_uvs_data, "triangle_uvs");
  require_n_by_3(corner_indices, "triangle_uvs");
  std::vector<std::array<int, 3>> triangle_uvs(std::size_t(corner_indices.shape(0)));
  for (std::size_t t = 0; t < triangle_uvs.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t c = corner_indices.data()[3 * t + k];
      if (c < 0 || c >= std::int64_t(uvs.size()))
        raise(PyExc_IndexError, "triangle_uvs[" + std::to_string(t) + "] refers to row " + std::to_string(c) +
                                    " of " + std::to_string(uvs.size()) + " uvs");
      triangle_uvs[t][k] = int(c);
    }
  const auto vertex_indices = to_integers(triangles_data, "triangles");
  require_n_by_3(vertex_indices, "triangles");
  if (vertex_indices.shape(0) != corner_indices.shape(0))
    raise(PyExc_ValueError, "triangles has " + std::to_string(vertex_indices.shape(0)) + " rows, triangle_uvs " +
                                std::to_string(corner_indices.shape(0)));
  std::vector<cmaps::Triangle> triangles(triangle_uvs.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) triangles[t][k] = int(vertex_indices.data()[3 * t + k]);
  std::vector<std::array<double, 2>> values = to_pairs(values_data, "values");
  const std::vector<int> point_triangles =
      to_index_vector(point_triangles_data, "point_triangles", std::int64_t(triangles.size()));
  const std::vector<int> reference = to_index_vector(reference_data, "reference", std::int64_t(values.size()));
  if (point_triangles.size() != values.size() || reference.size() != values.size())
    raise(PyExc_ValueError, "values, point_triangles and reference need one row per point, got " +
                                std::to_string(values.size()) + ", " + std::to_string(point_triangles.size()) +
                                " and " + std::to_string(reference.size()));
  {
    py::gil_scoped_release release;
    values = cmaps::continue_across_seams(triangles, triangle_uvs, uvs, point_triangles, std::move(values), reference);
  }
  py::array_t<double> result({py::ssize_t(values.size()), py::ssize_t(2)});
  double* out = result.mutable_data();
  for (const auto& v : values) *out++ = v[0], *out++ = v[1];
  return result;
}

// ------------------------------------------------------------------ point location

std::unique_ptr<cmaps::SphereLocator> new_locator(const py::handle& sphere_data, const py::handle& triangles_data) {
  std::vector<cmaps::Vec3> sphere = to_points(sphere_data, "sphere");
  std::vector<cmaps::Triangle> triangles = to_triangles(triangles_data, sphere.size());
  py::gil_scoped_release release;
  return std::make_unique<cmaps::SphereLocator>(std::move(sphere), std::move(triangles));
}

py::tuple locate(const cmaps::SphereLocator& locator, const py::handle& directions_data, int threads) {
  if (threads < 1) raise(PyExc_ValueError, "threads must be at least 1, got " + std::to_string(threads));
  const std::vector<cmaps::Vec3> directions = to_points(directions_data, "directions");
  std::vector<cmaps::SphereLocation> at;
  {
    py::gil_scoped_release release;
    at = locator.locate_all(directions, threads);
  }
  const py::ssize_t m = py::ssize_t(at.size());
  py::array_t<std::int32_t> triangles(m);
  py::array_t<double> barycentric({m, py::ssize_t(3)});
  std::int32_t* t = triangles.mutable_data();
  double* b = barycentric.mutable_data();
  for (const cmaps::SphereLocation& l : at) {
    *t++ = l.triangle;
    for (double x : l.barycentric) *b++ = x;
  }
  return py::make_tuple(triangles, barycentric);
}

py::array_t<double> interpolate(const cmaps::SphereLocator& locator, const py::handle& values_data,
                                const py::handle& triangles_data, const py::handle& barycentric_data, int threads) {
  if (threads < 1) raise(PyExc_ValueError, "threads must be at least 1, got " + std::to_string(threads));
  const py::array values_array = as_array(values_data, "values");
  const char kind = values_array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    raise(PyExc_TypeError, "values must hold real numbers, got dtype " + std::string(py::str(values_array.dtype())));
  if (values_array.ndim() != 1 && values_array.ndim() != 2)
    raise(PyExc_ValueError, "values must have shape (n,) or (n, d), got " + shape_of(values_array));
  if (std::size_t(values_array.shape(0)) != locator.sphere().size())
    raise(PyExc_ValueError, "values has " + std::to_string(values_array.shape(0)) + " rows but the locator has " +
                                std::to_string(locator.sphere().size()) + " vertices");
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values_array);
  const int stride = values.ndim() == 2 ? int(values.shape(1)) : 1;

  const IntegerArray triangles = to_integers(triangles_data, "triangles");
  if (triangles.ndim() != 1) raise(PyExc_ValueError, "triangles must have shape (m,), got " + shape_of(triangles));
  const py::array barycentric_array = as_array(barycentric_data, "barycentric");
  if (barycentric_array.ndim() != 2 || barycentric_array.shape(1) != 3 ||
      barycentric_array.shape(0) != triangles.shape(0))
    raise(PyExc_ValueError, "barycentric must have shape (" + std::to_string(triangles.shape(0)) + ", 3), got " +
                                shape_of(barycentric_array));
  const auto barycentric = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(barycentric_array);
  const std::int64_t count = std::int64_t(locator.triangles().size());
  std::vector<cmaps::SphereLocation> at(std::size_t(triangles.shape(0)));
  const std::int64_t* t = triangles.data();
  const double* b = barycentric.data();
  for (std::size_t i = 0; i < at.size(); ++i, ++t, b += 3) {
    if (*t < 0 || *t >= count)
      raise(PyExc_IndexError, "triangles[" + std::to_string(i) + "] is " + std::to_string(*t) +
                                  " but the locator has " + std::to_string(count) + " triangles");
    at[i].triangle = int(*t);
    at[i].barycentric = {b[0], b[1], b[2]};
  }
  const std::vector<double> flat(values.data(), values.data() + values.size());
  std::vector<double> result;
  {
    py::gil_scoped_release release;
    result = locator.interpolate(flat, stride, at, threads);
  }
  py::array_t<double> out = values.ndim() == 2 ? py::array_t<double>({py::ssize_t(at.size()), py::ssize_t(stride)})
                                                : py::array_t<double>(py::ssize_t(at.size()));
  std::copy(result.begin(), result.end(), out.mutable_data());
  return out;
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
        "(unused slots are -1 with weight 0) and mapped to extras['steiner_sphere'][i];\n"
        "extras['input_triangle'][t] is the input triangle refined triangle t lies in; extras['targets'] is\n"
        "(k, 3), the targets used. Raises InvalidMeshError for unsupported input or bad features/targets,\n"
        "Cancelled when progress returns False.");
  m.def("consistent_spherical_parameterization", &consistent_spherical_parameterization, py::arg("meshes"),
        py::arg("features"), py::kw_only(), py::arg("first") = -1, py::arg("grid") = 64, py::arg("restarts") = 1,
        py::arg("align") = false, py::arg("seed") = 1, py::arg("effort") = 1, py::arg("threads") = 2,
        py::arg("progress") = py::none(),
        "Consistent spherical parameterization of a set (thesis 3.2): every feature lands on one common\n"
        "point of the sphere on every member. meshes: sequence of (vertices, triangles), closed genus 0.\n"
        "features: (members, k) integer vertex indices, -1 where a member lacks the feature; every member\n"
        "needs at least 3 and one member all of them. first: member seeding the locations (-1: the first\n"
        "with every feature); grid: even resolution of the intermediate octahedral remeshes; restarts: runs\n"
        "with seeds seed, seed + 1, ..., keeping the one whose maps keep most of each member's own\n"
        "efficiency; align: step 7, each member's map refitted towards the seeding member's where that lowers\n"
        "the distortion between them (poses of one shape: less sliding between the features, at some\n"
        "efficiency). Returns a dict: 'feature_locations' (k, 3) common unit vectors, 'initial_locations'\n"
        "(k, 3) from the first member alone, 'first', 'restart' (the run kept), 'suitability' (its mean\n"
        "efficiency over the members' own), 'restart_suitability' (per run), 'seconds', and 'members': per member (sphere, stats, extras) as returned by\n"
        "constrained_spherical_parameterization (extras['refined_vertices'], extras['triangles'] and\n"
        "extras['refined_sphere'] are the map as a parameterized surface, Steiner vertices included).\n"
        "Raises InvalidMeshError naming the member for bad meshes or features, Cancelled when progress\n"
        "returns False.");
  m.def("parameterize_to_locations", &parameterize_to_locations, py::arg("vertices"), py::arg("triangles"),
        py::arg("features"), py::arg("locations"), py::kw_only(), py::arg("seed") = 1, py::arg("effort") = 1,
        py::arg("threads") = 2, py::arg("progress") = py::none(),
        "Adds a member to an existing set (thesis 4.2): the constrained map of the mesh with feature i at\n"
        "locations[i]. features: (k,) vertex indices, -1 where the mesh lacks the feature (left free; at\n"
        "least 3 present); locations: (k, 3), e.g. a set's 'feature_locations'. Returns (sphere, stats, extras)\n"
        "like constrained_spherical_parameterization.");
  m.def("intersurface_map", &intersurface_map, py::arg("mesh_a"), py::arg("mesh_b"),
        py::arg("feature_pairs") = py::list(), py::kw_only(), py::arg("grid") = 64,
        py::arg("optimize") = cmaps::IntersurfaceOptions{}.optimize_rounds,
        py::arg("restarts") = 1, py::arg("corner_images") = false, py::arg("balance_rounds") = 4,
        py::arg("cross_sweeps") = cmaps::IntersurfaceOptions{}.cross_sweeps,
        py::arg("starts") = cmaps::IntersurfaceOptions{}.starts,
        py::arg("method") = "auto", py::arg("seed") = 1, py::arg("effort") = 1, py::arg("threads") = 2, py::arg("progress") = py::none(),
        "Inter-surface map between two meshes of equal genus, closed or with as many holes (genus >= 1:\n"
        "through a consistent partition into triangular patches, 'base_vertices' and 'base_triangles' of its\n"
        "base mesh, 'seconds_partition'; genus 0: method 'sphere' through a consistent spherical\n"
        "parameterization of both, 'partition' directly as for genus >= 1, 'auto' both, keeping the lower\n"
        "summed median distortion; 'method' says which was kept, 'sphere_median_dirichlet' and\n"
        "'partition_median_dirichlet' the summed medians of the maps computed, None for one not). mesh_a, mesh_b: (vertices, triangles); feature_pairs: (k, 2)\n"
        "[vertex of A, vertex of B], mapped exactly onto each other (fewer than 3: pairs are added\n"
        "automatically up to 4). Returns a dict: 'a_to_b_triangle' (nA,) int32 and 'a_to_b_barycentric'\n"
        "(nA, 3): each vertex of A on an input triangle of B with weights w.r.t. its corners; likewise\n"
        "'b_to_a_*'; with corner_images, also 'a_corners_to_b_triangle' (3 mA,) int32 and\n"
        "'a_corners_to_b_barycentric' (3 mA, 3): row 3 t + k, the image on B of the point of A's triangle t\n"
        "next to its corner k (1e-3 of the way towards the other two), so per-corner values (UVs) are taken\n"
        "from the corner's own side of a seam; likewise 'b_corners_to_a_*' (3 mB rows);\n"
        "'a_on_b' (nA, 3), 'b_on_a' (nB, 3) the mapped positions; 'features' (k', 2) the pairs\n"
        "used (given, then added), 'added_features'; per direction (A to B, B to A) 'symmetric_dirichlet'\n"
        "(area-normalized, optimum 4, each source triangle mapped linearly onto its corners' images),\n"
        "'flipped', 'degenerate', and 'composition_dirichlet' before the distortion optimization (optimize:\n"
        "its rounds, 0 = no optimization: for genus 0 the plain composition of the spherical maps; the\n"
        "direct map's optimization also moves A's vertices across the partition's paths, at most\n"
        "cross_sweeps sweeps, 0 = the paths stay walls);\n"
        "'median_symmetric_dirichlet' (the median triangle's; the mean is dominated by a few triangles);\n"
        "'restart_dirichlet', 'restart_median_dirichlet' and 'restart_flipped', the energies and\n"
        "folded samples (both directions summed) of each of the `restarts` maps through the sphere (restart k:\n"
        "layout k % 3 of single pass, carried guides, aligned; seed + k // 3); the least distorted is returned\n"
        "(the lowest summed median; medians within 5 % of each other: the fewer folded samples, 'flipped', if\n"
        "the counts differ by over 0.5 % of the triangles); the direct map (any genus) is computed from A's\n"
        "side and from B's side, for a pair without feature_pairs and holes from the least distorted of\n"
        "`starts` automatic first pairs each mapped without optimization ('start_median_dirichlet': their\n"
        "summed medians; with restarts > 1 that many of them optimized, also reported in 'restart_*'),\n"
        "and method 'auto' computes both maps, each time keeping the less distorted\n"
        "(method 'auto': a tie that folds do not break goes to the direct map);\n"
        "'refitted' (genus 0): whether A's map, then B's, was refitted against the other's (kept only when\n"
        "that lowers the medians);\n"
        "'balanced_patches' (genus >= 1): whether the map went through the partition with its paths moved to\n"
        "balance corresponding patches' areas (balance_rounds rounds, 0 = not tried; kept only when less\n"
        "distorted, as for method), 'patch_area_ratio': the largest ratio of a patch's shares of A's and B's area in the partition used;\n"
        "'sphere_flipped', 'stretch_efficiency' and 'steiner' of the two spherical maps (genus 0);\n"
        "'seconds' and per stage. Raises InvalidMeshError for different genus,\n"
        "non-manifold meshes or bad pairs, Cancelled when progress returns False.");
  m.def("consistent_remesh", &consistent_remesh, py::arg("surfaces"), py::arg("feature_locations"), py::arg("n"),
        py::kw_only(), py::arg("threads") = 2,
        "Consistent remeshes: every parameterized surface sampled at the vertices of the octahedral grid of\n"
        "resolution n (even), the grid vertex nearest each feature location moved onto it. surfaces: per member\n"
        "(vertices, triangles, sphere), e.g. (extras['refined_vertices'], extras['triangles'],\n"
        "extras['refined_sphere']) of a consistent set's member. Returns a dict: 'sphere' (V, 3) the sample\n"
        "points, 'triangles' (2 n^2, 3) int32 their shared connectivity, 'positions' (members, V, 3) and\n"
        "'feature_vertices' (k,) int32: feature i is vertex feature_vertices[i] of every remesh.");
  m.def("octahedral_grid", &octahedral_grid, py::arg("n"),
        "Praun & Hoppe's flat-octahedron sphere grid of even resolution n: (sphere (n^2 + 2, 3) unit vectors,\n"
        "triangles (2 n^2, 3) int32 counter-clockwise from outside, pixel_vertex (n+1, n+1) int32: the vertex\n"
        "of each geometry-image pixel). values[pixel_vertex] is the geometry image of per-vertex values.");
  m.def("write_geometry_image", &write_geometry_image, py::arg("path"), py::arg("image"),
        "Writes an (n+1, n+1, 3) geometry image as float64 .npy or as 16-bit RGB .png quantized to the\n"
        "values' bounding box (kept in the file so it reads back to geometry). Raises MeshIOError.");
  m.def("read_geometry_image", &read_geometry_image, py::arg("path"),
        "Reads a geometry image (.npy float64/float32, or .png as written above) as (n+1, n+1, 3) float64.");
  m.def("geometry_image_mesh", &geometry_image_mesh, py::arg("image"),
        "The mesh of an (n+1, n+1, 3) geometry image: (vertices (n^2 + 2, 3), triangles (2 n^2, 3) int32), the\n"
        "octahedral grid's connectivity.");
  m.def("vertex_normals", &vertex_normals, py::arg("vertices"), py::arg("triangles"),
        "Unit area-weighted vertex normals (n, 3); zero for a vertex with only zero-area triangles.");
  m.def("continue_across_seams", &continue_across_seams, py::arg("triangles"), py::arg("triangle_uvs"), py::arg("uvs"),
        py::arg("point_triangles"), py::arg("values"), py::arg("reference"),
        "Texture coordinates of points on a mesh, each re-expressed in the chart of another point's triangle.\n"
        "triangles (m, 3) vertex indices and triangle_uvs (m, 3) rows of uvs (c, 2): corner k of triangle t has\n"
        "uvs[triangle_uvs[t, k]]. values (q, 2): point i's coordinates in the chart of its triangle\n"
        "point_triangles[i]; returned (q, 2) in the chart of point reference[i]'s triangle, continued across\n"
        "the seams between them (the similarity of each seam crossed along the fewest triangles; at most 64\n"
        "apart, else unchanged): the corners of a face whose image straddles a seam then span no texture.");

  py::class_<cmaps::SphereLocator>(m, "SphereLocator",
                                   "Point location on a spherical parameterization (millions of queries per second\n"
                                   "per core): which triangle's cone holds a direction, with barycentric coordinates\n"
                                   "that interpolate per-vertex values (positions, normals, UVs, colours).")
      .def(py::init(&new_locator), py::arg("sphere"), py::arg("triangles"),
           "sphere: (n, 3) unit vectors, triangles: (m, 3) positively oriented, covering the sphere once\n"
           "(e.g. a member's extras['refined_sphere'] and extras['triangles']). Raises InvalidMeshError.")
      .def("locate", &locate, py::arg("directions"), py::kw_only(), py::arg("threads") = 2,
           "directions: (m, 3) non-zero (need not be unit). Returns (triangles (m,) int32, barycentric (m, 3)\n"
           "float64, each row >= 0 summing to 1 in the triangle's corner order). Releases the GIL.")
      .def("interpolate", &interpolate, py::arg("values"), py::arg("triangles"), py::arg("barycentric"),
           py::kw_only(), py::arg("threads") = 2,
           "values: (n,) or (n, d), one row per locator vertex; triangles, barycentric as from locate().\n"
           "Returns (m,) or (m, d) float64: row i is sum_j barycentric[i, j] * values[corner j of triangles[i]].\n"
           "Releases the GIL.")
      .def_property_readonly("sphere", [](const cmaps::SphereLocator& l) { return to_numpy(l.sphere()); })
      .def_property_readonly("triangles", [](const cmaps::SphereLocator& l) { return to_numpy(l.triangles()); });

  m.def("measure_spherical_map", &measure_spherical_map, py::arg("vertices"), py::arg("triangles"),
        py::arg("sphere"), "Stretch and bijectivity measures of a map of the mesh onto the unit sphere.");
}
