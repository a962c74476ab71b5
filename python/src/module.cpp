/// @file module.cpp
/// @brief The extension module lamina._lamina: registers the error
/// translation and calls each binder. Users import `lamina`
/// (python/lamina/__init__.py), which re-exports what is public here.
#include "python/src/common.hpp"

PYBIND11_MODULE(_lamina, m) {
  m.doc() = "lamina's C++ libraries (use the package `lamina`, not this module)";
  m.attr("__version__") = LAMINA_VERSION;
  lamina::python::registerErrors(m);
  lamina::python::bindCell(m);
  lamina::python::bindHomogenize(m);
  lamina::python::bindLibrary(m);
  lamina::python::bindLaws(m);
  lamina::python::bindMembrane(m);
  lamina::python::bindPackage(m);
}
