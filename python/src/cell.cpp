/// @file cell.cpp
/// @brief Python bindings: see common.hpp (bindCell) and python/lamina/__init__.pyi.
#include "python/src/common.hpp"

namespace lamina::python {

void bindCell(py::module_& m) {
  // placeholders until bound; bound by the cell work (python/lamina/__init__.pyi is the contract)
  m.attr("Cell") = py::none();
}

} // namespace lamina::python
