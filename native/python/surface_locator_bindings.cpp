// Closest points on a triangle mesh: the SurfaceLocator class.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bindings.h"
#include "consistent_maps/surface_locator.h"
#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

std::unique_ptr<cmaps::SurfaceLocator> new_locator(const py::handle& vertices_data, const py::handle& triangles_data) {
  std::vector<cmaps::Vec3> vertices = to_points(vertices_data, "vertices");
  std::vector<cmaps::Triangle> triangles = to_triangles(triangles_data, vertices.size());
  py::gil_scoped_release release;
  return std::make_unique<cmaps::SurfaceLocator>(std::move(vertices), std::move(triangles));
}

py::tuple locate(const cmaps::SurfaceLocator& locator, const py::handle& points_data, int threads) {
  if (threads < 1) raise(PyExc_ValueError, "threads must be at least 1, got " + std::to_string(threads));
  const std::vector<cmaps::Vec3> points = to_points(points_data, "points");
  std::vector<cmaps::SurfaceLocation> at;
  {
    py::gil_scoped_release release;
    at = locator.locate_all(points, threads);
  }
  const py::ssize_t m = py::ssize_t(at.size());
  py::array_t<std::int32_t> triangles(m);
  py::array_t<double> barycentric({m, py::ssize_t(3)});
  py::array_t<double> distances(m);
  std::int32_t* t = triangles.mutable_data();
  double* b = barycentric.mutable_data();
  double* d = distances.mutable_data();
  for (const cmaps::SurfaceLocation& l : at) {
    *t++ = l.triangle;
    *d++ = l.distance;
    for (double x : l.barycentric) *b++ = x;
  }
  return py::make_tuple(triangles, barycentric, distances);
}

}  // namespace

void bind_surface_locator(py::module_& m) {
  py::class_<cmaps::SurfaceLocator>(m, "SurfaceLocator",
                                    "Closest points on a triangle mesh (a bounding-volume hierarchy): the nearest\n"
                                    "point of the surface to any point of space, as a triangle and barycentric\n"
                                    "coordinates that interpolate per-vertex or per-corner values there.")
      .def(py::init(&new_locator), py::arg("vertices"), py::arg("triangles"),
           "vertices: (n, 3) finite, triangles: (m, 3), m >= 1 (any soup; zero-area triangles are searched\n"
           "along their edges). Raises InvalidMeshError.")
      .def("locate", &locate, py::arg("points"), py::kw_only(), py::arg("threads") = 2,
           "points: (q, 3) finite. Returns (triangles (q,) int32, barycentric (q, 3) float64, each row >= 0\n"
           "summing to 1 in the triangle's corner order, distances (q,) float64). Releases the GIL.")
      .def_property_readonly("vertices", [](const cmaps::SurfaceLocator& l) { return to_numpy(l.vertices()); })
      .def_property_readonly("triangles", [](const cmaps::SurfaceLocator& l) { return to_numpy(l.triangles()); });
}

}  // namespace cmaps::python
