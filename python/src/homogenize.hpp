#pragma once
/// @file homogenize.hpp
/// @brief What the homogenize bindings give the library's: the entry of a
/// lamina.HomogenizeResult.

#include "python/src/common.hpp"

#include "materials/library.hpp"

#include <string>

namespace lamina::python {

/// Adds the homogenized @p result (a lamina.HomogenizeResult) to @p library
/// as entry @p name, with the provenance `homogenize --name` records, in one
/// locked, atomic write; an existing @p name is an error unless
/// @p overwrite. Raises lamina.InputError for anything else than a
/// HomogenizeResult.
void addHomogenized(py::handle result, materials::Library& library, const std::string& name,
                    bool overwrite);

} // namespace lamina::python
