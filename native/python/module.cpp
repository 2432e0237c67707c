// consistent_maps._native: the library for Python (and so for Blender).
// Arrays come in as any real/integer numpy-compatible data and are validated
// (conversions.cpp), so the library only ever sees well-formed index arrays;
// long computations release the GIL and report progress through a Python
// callable (python_progress.h). This file creates the module and its exception
// types; the functions come from one *_bindings.cpp per pipeline stage.
#include <pybind11/pybind11.h>

#include <exception>
#include <string>

#include "bindings.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/version.h"
#include "conversions.h"

namespace py = pybind11;
using namespace cmaps::python;

namespace {

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

  bind_mesh(m);
  bind_sphere(m);
  bind_consistent(m);
  bind_intersurface(m);
  bind_geometry_image(m);
  bind_transfer(m);
  bind_sphere_locator(m);
  bind_surface_locator(m);
}
