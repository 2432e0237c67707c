// Point location on a spherical parameterization: the SphereLocator class.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bindings.h"
#include "consistent_maps/sphere_locator.h"
#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

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

}  // namespace

void bind_sphere_locator(py::module_& m) {
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
}

}  // namespace cmaps::python
