/// @file homogenize.cpp
/// @brief Python bindings: see common.hpp (bindHomogenize) and python/lamina/__init__.pyi.
#include "python/src/homogenize.hpp"

namespace lamina::python {

void bindHomogenize(py::module_& m) {
  // placeholders until bound; bound by the homogenize work (python/lamina/__init__.pyi is the
  // contract)
  m.attr("HomogenizeResult") = py::none();
  m.attr("homogenize") = py::none();
  m.attr("homogenize_path") = py::none();
}

} // namespace lamina::python

namespace lamina::python {

void addHomogenized(py::handle result, materials::Library& library, const std::string& name,
                    bool overwrite) {
  (void)result, (void)library, (void)name, (void)overwrite;
  throwInput("lamina.Library.add: homogenized results are not bound yet", "result");
}

} // namespace lamina::python
