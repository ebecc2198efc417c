#pragma once
// Calibration, simulator, map-maker and navigator for Python: the same results the CLI prints.

#include <pybind11/pybind11.h>

namespace neopipe::python {

void bind_reports(pybind11::module_& m);

}  // namespace neopipe::python
