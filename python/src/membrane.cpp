/// @file membrane.cpp
/// @brief Python bindings: see common.hpp (bindMembrane) and python/lamina/__init__.pyi.
#include "python/src/common.hpp"

namespace lamina::python {

void bindMembrane(py::module_& m) {
  // placeholders until bound; bound by the membrane work (python/lamina/__init__.pyi is the
  // contract)
  m.attr("blast") = py::none();
  m.attr("_membrane_run") = py::none();
}

} // namespace lamina::python
