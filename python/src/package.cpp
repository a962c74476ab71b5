/// @file package.cpp
/// @brief Python bindings: see common.hpp (bindPackage). What the package
/// lamina (python/lamina/__init__.py) needs to find an installed catalog.
#include "python/src/common.hpp"

#include "materials/catalog.hpp"

namespace lamina::python {

void bindPackage(py::module_& m) {
  m.def(
      "_default_catalog", [] { return materials::Catalog::defaultPath().string(); },
      "The catalog the libraries read when no catalog is named: $LAMINA_CATALOG, else the "
      "compiled-in path (the source tree's materials/catalog.toml).");
}

} // namespace lamina::python
