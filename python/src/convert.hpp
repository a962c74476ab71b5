#pragma once
/// @file convert.hpp
/// @brief Python values to and from the formats lamina's readers and
/// writers use: dicts to TOML tables (a dict case, a phase's law keys, a
/// law), `set={...}` to the programs' --set assignments, JSON results to
/// Python objects. One conversion for every binding, so a dict is read by
/// the same reader, with the same messages, as the file it stands for.

#include "python/src/common.hpp"

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <string>
#include <vector>

namespace lamina::python {

/// @return the dict @p dict as a TOML table: str keys; values bool, int,
/// float (numpy scalars too), str, dict (a table), list or tuple (an array;
/// of tables when its items are dicts), numpy arrays (as nested lists).
/// Raises lamina.InputError naming the dotted key (under @p where, e.g.
/// "phases[2]") of a value of another type or a key that is not a str.
toml::table toToml(py::handle dict, const std::string& where);

/// @return one "KEY=VALUE" per item of @p set (a dict, or None: none), the
/// value written as TOML: the programs' `--set KEY=VALUE`
std::vector<std::string> toOverrides(py::handle set);

/// @return @p j as Python objects (dict, list, int, float, str, bool, None)
py::object toPython(const nlohmann::json& j);

} // namespace lamina::python
