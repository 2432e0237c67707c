// Consistent sets: their spherical parameterization, later members, consistent remeshes.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bindings.h"
#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/octahedral_grid.h"
#include "consistent_maps/remesh.h"
#include "conversions.h"
#include "python_progress.h"
#include "sphere_outputs.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

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

}  // namespace

void bind_consistent(py::module_& m) {
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
        "efficiency over the members' own), 'restart_suitability' (per run), 'seconds', and "
        "'members': per member (sphere, stats, extras) as returned by\n"
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
  m.def("consistent_remesh", &consistent_remesh, py::arg("surfaces"), py::arg("feature_locations"), py::arg("n"),
        py::kw_only(), py::arg("threads") = 2,
        "Consistent remeshes: every parameterized surface sampled at the vertices of the octahedral grid of\n"
        "resolution n (even), the grid vertex nearest each feature location moved onto it. surfaces: per member\n"
        "(vertices, triangles, sphere), e.g. (extras['refined_vertices'], extras['triangles'],\n"
        "extras['refined_sphere']) of a consistent set's member. Returns a dict: 'sphere' (V, 3) the sample\n"
        "points, 'triangles' (2 n^2, 3) int32 their shared connectivity, 'positions' (members, V, 3) and\n"
        "'feature_vertices' (k,) int32: feature i is vertex feature_vertices[i] of every remesh.");
}

}  // namespace cmaps::python
