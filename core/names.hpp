#pragma once
/// @file names.hpp
/// @brief What a name may be. Material names (library entries, catalog
/// materials, layups), case names and the names of probes and constraint
/// sets become file names (side files, <case>.h5/.xdmf), CSV column headers
/// and lines of Abaqus / LS-DYNA / CalculiX cards, so one rule holds for all:
///
///   1 to 100 characters from A-Z a-z 0-9 . _ + - , the first a letter or a
///   digit.
///
/// So a name never holds a path separator, a space, a quote, a comma or a
/// control character, never starts with '.' or '-' and is never "." or "..".

#include "core/error.hpp"

#include <string>
#include <string_view>

namespace lamina::core {

/// Longest name accepted.
inline constexpr std::size_t kMaxNameLength = 100;

/// @return whether @p name follows the rule above
bool isValidName(std::string_view name);

/// @return "" when @p name is valid, else why not (for messages)
std::string nameProblem(std::string_view name);

/// Throws lamina::Error with @p context when @p name is not valid; the
/// message says which @p what ("material name", "case name"...) and why.
void checkName(const std::string& name, const std::string& what, const ErrorContext& context = {});

} // namespace lamina::core
