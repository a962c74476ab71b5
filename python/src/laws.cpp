/// @file laws.cpp
/// @brief Python bindings: see common.hpp (bindLaws) and python/lamina/__init__.pyi.
#include "python/src/common.hpp"

namespace lamina::python {

void bindLaws(py::module_& m) {
  // placeholders until bound; bound by the laws work (python/lamina/__init__.pyi is the contract)
  m.attr("drive") = py::none();
}

} // namespace lamina::python
