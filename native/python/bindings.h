// The module's functions and classes, one file per pipeline stage; module.cpp
// creates the module and its exception types and calls each of these once.
#pragma once

#include <pybind11/pybind11.h>

namespace cmaps::python {

namespace py = pybind11;

void bind_mesh(py::module_& m);                 // mesh_bindings.cpp: reading, checking, normals
void bind_sphere(py::module_& m);               // sphere_bindings.cpp: (constrained) spherical maps
void bind_consistent(py::module_& m);           // consistent_bindings.cpp: consistent sets and remeshes
void bind_intersurface(py::module_& m);         // intersurface_bindings.cpp: inter-surface maps
void bind_geometry_image(py::module_& m);       // geometry_image_bindings.cpp: octahedral grids, images
void bind_transfer(py::module_& m);             // transfer_bindings.cpp: texture coordinates across seams
void bind_sphere_locator(py::module_& m);       // sphere_locator_bindings.cpp: point location
void bind_surface_locator(py::module_& m);      // surface_locator_bindings.cpp: closest points

}  // namespace cmaps::python
