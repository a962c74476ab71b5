#pragma once
/// @file format.hpp
/// @brief Number formatting shared by every text output of lamina.

#include <string>
#include <vector>

namespace lamina::core {

/// Formats @p x with 17 significant digits ("%.17g"): parsing the text back
/// gives exactly the same double. Always contains a '.', 'e', "inf" or "nan"
/// so that TOML reads it as a float.
std::string formatExact(double x);

/// Formats @p x with @p digits significant digits for humans ("%.*g").
std::string formatShort(double x, int digits = 6);

/// @return @p text with & < > " ' replaced by XML entities (for attribute
/// values and text written into XDMF files)
std::string xmlEscape(const std::string& text);

/// Joins @p names with ", " (for messages that list what a file holds).
std::string joinNames(const std::vector<std::string>& names);

} // namespace lamina::core
