// Attribute transfer: texture coordinates continued across UV seams.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bindings.h"
#include "consistent_maps/attribute_transfer.h"
#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

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

}  // namespace

void bind_transfer(py::module_& m) {
  m.def("continue_across_seams", &continue_across_seams, py::arg("triangles"), py::arg("triangle_uvs"), py::arg("uvs"),
        py::arg("point_triangles"), py::arg("values"), py::arg("reference"),
        "Texture coordinates of points on a mesh, each re-expressed in the chart of another point's triangle.\n"
        "triangles (m, 3) vertex indices and triangle_uvs (m, 3) rows of uvs (c, 2): corner k of triangle t has\n"
        "uvs[triangle_uvs[t, k]]. values (q, 2): point i's coordinates in the chart of its triangle\n"
        "point_triangles[i]; returned (q, 2) in the chart of point reference[i]'s triangle, continued across\n"
        "the seams between them (the similarity of each seam crossed along the fewest triangles; at most 64\n"
        "apart, else unchanged): the corners of a face whose image straddles a seam then span no texture.");
}

}  // namespace cmaps::python
