/// @file library.cpp
/// @brief Python bindings: see common.hpp (bindLibrary) and python/lamina/__init__.pyi.
#include "python/src/common.hpp"

namespace lamina::python {

void bindLibrary(py::module_& m) {
  // placeholders until bound; bound by the library work (python/lamina/__init__.pyi is the
  // contract)
  m.attr("Library") = py::none();
}

} // namespace lamina::python
