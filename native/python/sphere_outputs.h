// Maps onto the sphere as Python sees them: a stats dict and, for constrained
// maps (also every member of a consistent set), (sphere, stats, extras).
#pragma once

#include <pybind11/pybind11.h>

#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/stretch_metric.h"

namespace cmaps::python {

namespace py = pybind11;

// Adds the stretch and bijectivity measures of a spherical map to `d`.
void add_map_report(py::dict& d, const cmaps::SphericalMapReport& r);

// A constrained map as Python sees it: (sphere, stats, extras). `seconds` is the
// wall time of the computation it came from.
py::tuple constrained_outputs(const cmaps::TriangleMesh& mesh, const cmaps::ConstrainedResult& result,
                              double seconds);

}  // namespace cmaps::python
