// Python data in and out: any numpy-compatible array is checked here (shape,
// dtype, index ranges) and converted, so the library only sees well-formed
// input; every problem is raised as a Python exception naming the argument.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps::python {

namespace py = pybind11;

// Python exception types, created once at import (module.cpp) and kept alive for the process.
extern PyObject* invalid_mesh_error;
extern PyObject* mesh_io_error;
extern PyObject* cancelled_error;

// Raises `type` with `message` in Python.
[[noreturn]] void raise(PyObject* type, const std::string& message);

using IntegerArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

// Any array-like as a numpy array, or TypeError naming it.
py::array as_array(const py::handle& data, const char* name);
// "(3, 2)", "(5,)": an array's shape as messages print it.
std::string shape_of(const py::array& array);
void require_n_by_3(const py::array& array, const char* name);
// Any integer array-like as C-contiguous int64 (bools and floats are refused).
IntegerArray to_integers(const py::handle& data, const char* name);
// (n,) integers, each in [0, limit) when limit >= 0, or IndexError naming the entry.
std::vector<int> to_index_vector(const py::handle& data, const char* name, std::int64_t limit);
// (n, 3) real numbers.
std::vector<cmaps::Vec3> to_points(const py::handle& data, const char* name);
// (m, 3) vertex indices, each in [0, vertex_count).
std::vector<cmaps::Triangle> to_triangles(const py::handle& triangles, std::size_t vertex_count);
cmaps::TriangleMesh to_mesh(const py::handle& vertices, const py::handle& triangles);
// A (vertices, triangles) pair; `name` labels it in messages.
cmaps::TriangleMesh to_mesh_pair(const py::handle& item, const std::string& name);
// An even grid resolution of at least 2, or ValueError naming it.
void require_grid_resolution(int n, const char* name);

py::array_t<double> to_numpy(const std::vector<double>& values);
py::array_t<std::int32_t> to_numpy(const std::vector<int>& values);
py::array_t<double> to_numpy(const std::vector<cmaps::Vec3>& points);
py::array_t<std::int32_t> to_numpy(const std::vector<cmaps::Triangle>& triangles);

}  // namespace cmaps::python
