#include "python/src/convert.hpp"

#include <sstream>

namespace lamina::python {

namespace {

std::string joinKey(const std::string& where, const std::string& key) {
  return where.empty() ? key : where + "." + key;
}

/// A numpy scalar or array as plain Python (item() / tolist()), else @p o.
py::object plain(py::handle o) {
  if (py::hasattr(o, "dtype") && py::hasattr(o, "tolist"))
    return o.attr("tolist")();
  return py::reinterpret_borrow<py::object>(o);
}

void insertNode(toml::table& table, const std::string& name, py::handle value,
                const std::string& key);

toml::array toArray(py::handle list, const std::string& key) {
  toml::array array;
  std::size_t i = 0;
  for (py::handle item : list) {
    toml::table holder;
    insertNode(holder, "v", item, key + "[" + std::to_string(i++) + "]");
    array.push_back(std::move(*holder.get("v")));
  }
  return array;
}

void insertNode(toml::table& table, const std::string& name, py::handle value_in,
                const std::string& key) {
  const py::object value = plain(value_in);
  if (py::isinstance<py::bool_>(value))
    table.insert_or_assign(name, value.cast<bool>());
  else if (PyLong_Check(value.ptr())) {
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0)
      throwInput("integer out of range: " + std::string(py::str(value)), key);
    table.insert_or_assign(name, static_cast<std::int64_t>(v));
  } else if (PyFloat_Check(value.ptr()))
    table.insert_or_assign(name, value.cast<double>());
  else if (py::isinstance<py::str>(value))
    table.insert_or_assign(name, value.cast<std::string>());
  else if (py::isinstance<py::dict>(value))
    table.insert_or_assign(name, toToml(value, key));
  else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value))
    table.insert_or_assign(name, toArray(value, key));
  else
    throwInput("a value of type " + typeName(value) +
                   " has no TOML form (bool, int, float, str, dict, list)",
               key);
}

std::string tomlValueText(const toml::table& holder) {
  std::ostringstream os;
  os << holder; // "v = VALUE"
  std::string text = os.str();
  const auto eq = text.find('=');
  text = text.substr(eq + 1);
  const auto first = text.find_first_not_of(" \t");
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

} // namespace

toml::table toToml(py::handle dict, const std::string& where) {
  if (!py::isinstance<py::dict>(dict))
    throwInput("expected a dict, got " + typeName(dict), where);
  toml::table table;
  for (auto item : py::reinterpret_borrow<py::dict>(dict)) {
    if (!py::isinstance<py::str>(item.first))
      throwInput("keys must be str, got " + typeName(item.first) + " " +
                     std::string(py::repr(item.first)),
                 where);
    const std::string name = item.first.cast<std::string>();
    insertNode(table, name, item.second, joinKey(where, name));
  }
  return table;
}

std::vector<std::string> toOverrides(py::handle set) {
  std::vector<std::string> overrides;
  if (set.is_none())
    return overrides;
  if (!py::isinstance<py::dict>(set))
    throwInput("set must be a dict {\"key.path\": value}, got " + typeName(set), "set");
  for (auto item : py::reinterpret_borrow<py::dict>(set)) {
    if (!py::isinstance<py::str>(item.first))
      throwInput("keys must be str (dotted key paths)", "set");
    const std::string key = item.first.cast<std::string>();
    toml::table holder;
    insertNode(holder, "v", item.second, "set[" + key + "]");
    overrides.push_back(key + "=" + tomlValueText(holder));
  }
  return overrides;
}

py::object toPython(const nlohmann::json& j) {
  switch (j.type()) {
  case nlohmann::json::value_t::object: {
    py::dict d;
    for (const auto& [k, v] : j.items())
      d[py::str(k)] = toPython(v);
    return std::move(d);
  }
  case nlohmann::json::value_t::array: {
    py::list l;
    for (const auto& v : j)
      l.append(toPython(v));
    return std::move(l);
  }
  case nlohmann::json::value_t::string:
    return py::str(j.get<std::string>());
  case nlohmann::json::value_t::boolean:
    return py::bool_(j.get<bool>());
  case nlohmann::json::value_t::number_integer:
    return py::int_(j.get<std::int64_t>());
  case nlohmann::json::value_t::number_unsigned:
    return py::int_(j.get<std::uint64_t>());
  case nlohmann::json::value_t::number_float:
    return py::float_(j.get<double>());
  default:
    return py::none();
  }
}

} // namespace lamina::python
