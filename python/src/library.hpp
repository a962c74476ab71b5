#pragma once
/// @file library.hpp
/// @brief Arguments that lamina.Library and lamina.drive read alike: a
/// path (str or os.PathLike, or None) and a name (str).

#include "python/src/common.hpp"

#include <string>

namespace lamina::python {

/// @return @p path (a str or an os.PathLike) as a file name; None gives ""
/// (the caller's default). Raises lamina.InputError naming @p key for
/// another type or an empty path.
std::string pathArgument(py::handle path, const std::string& key);

/// @return @p name as a str; raises lamina.InputError naming @p key when it
/// is not a str
std::string strArgument(py::handle name, const std::string& key);

} // namespace lamina::python
