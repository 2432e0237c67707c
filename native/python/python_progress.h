// Long computations from Python: the GIL released while they run, their
// progress forwarded to a Python callable, Ctrl-C and Python errors in that
// callable turned into a cancellation and re-raised afterwards.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "consistent_maps/errors.h"
#include "consistent_maps/progress.h"
#include "consistent_maps/spherical_parameterization.h"

namespace cmaps::python {

namespace py = pybind11;

// Forwards progress to Python with the GIL held. It never lets an exception
// escape into the library (which may call it from a worker thread): a Python
// error or a pending Ctrl-C is stored and turned into a cancellation, and
// re-raised once the computation has unwound.
class PythonProgress {
 public:
  explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {}

  bool operator()(double fraction, const std::string& stage) {
    py::gil_scoped_acquire gil;
    if (stop_) return false;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback_.is_none() && callback_(fraction, stage).ptr() == Py_False) stop_ = true;
    } catch (py::error_already_set& e) {
      error_ = std::move(e);
      stop_ = true;
    }
    return !stop_;
  }

  // Call with the GIL held, after the computation.
  void rethrow_python_error() {
    if (error_) throw std::move(*error_);
  }

 private:
  py::object callback_;
  bool stop_ = false;  // guarded by the GIL
  std::optional<py::error_already_set> error_;
};

// Checks the keyword arguments shared by the parameterizations.
cmaps::SphereOptions sphere_options(std::uint64_t seed, int effort, int threads, const py::object& progress);

// Runs `compute(callback)` without the GIL, forwarding its progress to the
// Python callable; returns {its result, wall seconds}. A Python error raised
// by the callable is re-raised here in place of the cancellation it caused.
template <class Compute>
auto run_released(const py::object& progress, Compute&& compute) {
  PythonProgress forward(progress);
  const cmaps::ProgressCallback callback = [&forward](double fraction, const std::string& stage) {
    return forward(fraction, stage);
  };
  try {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    auto result = compute(callback);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::make_pair(std::move(result), seconds);
  } catch (const cmaps::Cancelled&) {
    forward.rethrow_python_error();
    throw;
  }
}

}  // namespace cmaps::python
