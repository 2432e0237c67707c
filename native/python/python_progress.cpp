#include "python_progress.h"

#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

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

}  // namespace cmaps::python
