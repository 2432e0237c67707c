// Meshes: reading files, checking topology and defects, vertex normals.
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "bindings.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

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

py::tuple read_mesh(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path))
    raise(PyExc_FileNotFoundError, "cannot read '" + path.string() + "': no such file");
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
  std::optional<std::string> sphere_problem, pair_problem;
  {
    py::gil_scoped_release release;
    report = cmaps::check_mesh(mesh);
    const auto reason = [&mesh](auto require) -> std::optional<std::string> {
      try {
        require(mesh);
      } catch (const cmaps::InvalidInput& e) {
        return e.what();
      }
      return std::nullopt;
    };
    sphere_problem = reason([](const cmaps::TriangleMesh& m) { cmaps::require_sphere_topology(m); });
    pair_problem = reason([](const cmaps::TriangleMesh& m) { cmaps::require_pair_map_topology(m); });
  }
  const auto text = [](const std::optional<std::string>& s) { return s ? py::object(py::str(*s)) : py::none(); };
  py::dict d = report_dict(report);
  d["sphere_error"] = text(sphere_problem);
  d["pair_map_error"] = text(pair_problem);
  return d;
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

}  // namespace

void bind_mesh(py::module_& m) {
  m.def("read_mesh", &read_mesh, py::arg("path"),
        "Reads an OBJ, OFF, PLY or STL file. Returns (vertices (n, 3) float64, triangles (m, 3) int32);\n"
        "polygons are fan-triangulated. Raises FileNotFoundError or MeshIOError.");
  m.def("check_mesh", &check_mesh, py::arg("vertices"), py::arg("triangles"),
        "Topology and defect report of a triangle mesh, as a dict. 'sphere_error' is None when the mesh\n"
        "can be mapped to the sphere, else the reason it cannot; 'pair_map_error' likewise for an\n"
        "inter-surface map onto a partner of the same genus (any genus, holes and unused vertices allowed).");
  m.def("vertex_normals", &vertex_normals, py::arg("vertices"), py::arg("triangles"),
        "Unit area-weighted vertex normals (n, 3); zero for a vertex with only zero-area triangles.");
}

}  // namespace cmaps::python
