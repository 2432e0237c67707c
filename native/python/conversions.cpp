#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

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

IntegerArray to_integers(const py::handle& data, const char* name) {
  py::array array = as_array(data, name);
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    raise(PyExc_TypeError, std::string(name) + " must hold integers, got dtype " + std::string(py::str(array.dtype())));
  return IntegerArray::ensure(array);
}

std::vector<int> to_index_vector(const py::handle& data, const char* name, std::int64_t limit) {
  const auto indices = to_integers(data, name);
  if (indices.ndim() != 1)
    raise(PyExc_ValueError, std::string(name) + " must have shape (n,), got " + shape_of(indices));
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

cmaps::TriangleMesh to_mesh_pair(const py::handle& item, const std::string& name) {
  if (!py::isinstance<py::sequence>(item) || py::isinstance<py::str>(item) || py::len(item) != 2)
    raise(PyExc_TypeError, name + " must be a (vertices, triangles) pair");
  return to_mesh(item[py::int_(0)], item[py::int_(1)]);
}

void require_grid_resolution(int n, const char* name) {
  if (n < 2 || n % 2 != 0)
    raise(PyExc_ValueError, std::string(name) + " must be even and at least 2, got " + std::to_string(n));
}

py::array_t<double> to_numpy(const std::vector<double>& values) {
  return py::array_t<double>(py::ssize_t(values.size()), values.data());
}

py::array_t<std::int32_t> to_numpy(const std::vector<int>& values) {
  return py::array_t<std::int32_t>(py::ssize_t(values.size()), values.data());
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

}  // namespace cmaps::python
