#include "core/toml_reader.hpp"

#include "core/error.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace lamina::core {

namespace {

std::string typeName(const toml::node& n) {
  switch (n.type()) {
  case toml::node_type::table:
    return "table";
  case toml::node_type::array:
    return "array";
  case toml::node_type::string:
    return "string";
  case toml::node_type::integer:
    return "integer";
  case toml::node_type::floating_point:
    return "float";
  case toml::node_type::boolean:
    return "boolean";
  default:
    return "date/time";
  }
}

// A TOML number as a double: floats as they are, integers converted (a
// case file may write `nx = 4` or `E = 1e9` for any number).
std::optional<double> numberOf(const toml::node& n) {
  if (auto v = n.value_exact<double>())
    return *v;
  if (auto v = n.value_exact<std::int64_t>())
    return static_cast<double>(*v);
  return std::nullopt;
}

int lineOfNode(const toml::node& n) {
  return static_cast<int>(n.source().begin.line);
}

} // namespace

toml::table parseTomlFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error("cannot open file", {path.string(), 0, ""});
  std::stringstream ss;
  ss << in.rdbuf();
  return parseTomlString(ss.str(), path.string());
}

toml::table parseTomlString(std::string_view text, const std::string& source_name) {
  try {
    return toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw Error("malformed TOML: " + std::string(e.description()),
                {source_name, static_cast<int>(e.source().begin.line), ""});
  }
}

void applyOverride(toml::table& doc, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error("override must read key=value", {"--set", 0, assignment});
  const std::string key = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", value}};
  }
  toml::table* t = &doc;
  std::size_t start = 0;
  while (true) {
    const auto dot = key.find('.', start);
    std::string part = key.substr(start, dot == std::string::npos ? dot : dot - start);
    // "name[i]" addresses element i of an array of tables ([[name]]).
    long index = -1;
    if (const auto br = part.find('['); br != std::string::npos) {
      char* end = nullptr;
      index = std::strtol(part.c_str() + br + 1, &end, 10);
      if (index < 0 || *end != ']' || end[1] != '\0')
        throw Error("malformed array index in override", {"--set", 0, key});
      part = part.substr(0, br);
    }
    if (part.empty())
      throw Error("empty key component in override", {"--set", 0, key});
    if (index >= 0) {
      toml::array* arr = t->get(part) ? t->get(part)->as_array() : nullptr;
      if (!arr || static_cast<std::size_t>(index) >= arr->size() ||
          !(*arr)[static_cast<std::size_t>(index)].is_table())
        throw Error("override names a missing [[" + part + "]] element", {"--set", 0, key});
      toml::table* elem = (*arr)[static_cast<std::size_t>(index)].as_table();
      if (dot == std::string::npos)
        throw Error("override must name a key inside [[" + part + "]]", {"--set", 0, key});
      t = elem;
      start = dot + 1;
      continue;
    }
    if (dot == std::string::npos) {
      t->insert_or_assign(part, *parsed.get("v"));
      return;
    }
    toml::node* next = t->get(part);
    if (!next) {
      t->insert(part, toml::table{});
      next = t->get(part);
    }
    if (!next->is_table())
      throw Error("override goes through a non-table value", {"--set", 0, key});
    t = next->as_table();
    start = dot + 1;
  }
}

TableReader::TableReader(const toml::table& table, std::string file, std::string prefix)
    : table_(&table), file_(std::move(file)), prefix_(std::move(prefix)),
      record_(std::make_shared<Record>()) {}

std::string TableReader::path(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

int TableReader::lineOf(std::string_view key) const {
  if (const toml::node* n = table_->get(key))
    return lineOfNode(*n);
  return lineOfNode(*table_);
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  throw Error(message, {file_, lineOf(key), path(key)});
}

void TableReader::failHere(const std::string& message) const {
  throw Error(message, {file_, lineOfNode(*table_), prefix_});
}

bool TableReader::has(std::string_view key) const {
  return table_->contains(key);
}

std::vector<std::string> TableReader::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : *table_)
    out.emplace_back(k.str());
  return out;
}

void TableReader::mark(std::string_view key) const {
  record_->read.insert(path(key));
}

const toml::node& TableReader::require(std::string_view key) const {
  const toml::node* n = table_->get(key);
  if (!n)
    fail(key, "missing required key");
  mark(key);
  return *n;
}

double TableReader::getDouble(std::string_view key) const {
  const toml::node& n = require(key);
  if (auto v = numberOf(n))
    return *v;
  fail(key, "expected a number, got " + typeName(n));
}

double TableReader::getDouble(std::string_view key, double fallback) const {
  return has(key) ? getDouble(key) : fallback;
}

std::int64_t TableReader::getInt(std::string_view key) const {
  const toml::node& n = require(key);
  if (auto v = n.value_exact<std::int64_t>())
    return *v;
  fail(key, "expected an integer, got " + typeName(n));
}

std::int64_t TableReader::getInt(std::string_view key, std::int64_t fallback) const {
  return has(key) ? getInt(key) : fallback;
}

bool TableReader::getBool(std::string_view key, bool fallback) const {
  if (!has(key))
    return fallback;
  const toml::node& n = require(key);
  if (auto v = n.value_exact<bool>())
    return *v;
  fail(key, "expected true or false, got " + typeName(n));
}

std::string TableReader::getString(std::string_view key) const {
  const toml::node& n = require(key);
  if (auto v = n.value_exact<std::string>())
    return *v;
  fail(key, "expected a string, got " + typeName(n));
}

std::string TableReader::getString(std::string_view key, const std::string& fallback) const {
  return has(key) ? getString(key) : fallback;
}

std::vector<double> TableReader::getDoubleArray(std::string_view key) const {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a)
    fail(key, "expected an array of numbers, got " + typeName(n));
  std::vector<double> out;
  for (const toml::node& e : *a) {
    if (auto v = numberOf(e))
      out.push_back(*v);
    else
      fail(key, "expected an array of numbers, found a " + typeName(e));
  }
  return out;
}

std::vector<std::string> TableReader::getStringArray(std::string_view key) const {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a)
    fail(key, "expected an array of strings, got " + typeName(n));
  std::vector<std::string> out;
  for (const toml::node& e : *a) {
    if (auto v = e.value_exact<std::string>())
      out.push_back(*v);
    else
      fail(key, "expected an array of strings, found a " + typeName(e));
  }
  return out;
}

std::vector<std::vector<double>> TableReader::getMatrix(std::string_view key) const {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a)
    fail(key, "expected an array of rows, got " + typeName(n));
  std::vector<std::vector<double>> out;
  for (const toml::node& row : *a) {
    const toml::array* r = row.as_array();
    if (!r)
      fail(key, "expected an array of rows, found a " + typeName(row));
    std::vector<double> values;
    for (const toml::node& e : *r) {
      if (auto v = numberOf(e))
        values.push_back(*v);
      else
        fail(key, "expected numbers in every row, found a " + typeName(e));
    }
    out.push_back(std::move(values));
  }
  return out;
}

TableReader TableReader::table(std::string_view key) const {
  const toml::node& n = require(key);
  const toml::table* t = n.as_table();
  if (!t)
    fail(key, "expected a table, got " + typeName(n));
  TableReader sub(*t, file_, path(key));
  sub.record_ = record_;
  return sub;
}

std::optional<TableReader> TableReader::optionalTable(std::string_view key) const {
  if (!has(key))
    return std::nullopt;
  return table(key);
}

std::vector<TableReader> TableReader::tableArray(std::string_view key) const {
  std::vector<TableReader> out;
  if (!has(key))
    return out;
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a)
    fail(key, "expected an array of tables ([[" + path(key) + "]]), got " + typeName(n));
  std::size_t i = 0;
  for (const toml::node& e : *a) {
    const toml::table* t = e.as_table();
    if (!t)
      fail(key, "expected an array of tables, found a " + typeName(e));
    const std::string p = path(key) + "[" + std::to_string(i++) + "]";
    record_->read.insert(p);
    TableReader sub(*t, file_, p);
    sub.record_ = record_;
    out.push_back(std::move(sub));
  }
  return out;
}

const toml::node* TableReader::raw(std::string_view key) const {
  const toml::node* n = table_->get(key);
  if (n) {
    mark(key);
    record_->whole.insert(path(key));
  }
  return n;
}

void TableReader::checkUnread(const toml::table& t, const std::string& prefix) const {
  for (const auto& [k, v] : t) {
    const std::string p =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (record_->whole.count(p))
      continue;
    if (!record_->read.count(p))
      throw Error("unknown key (not part of this file's format)", {file_, lineOfNode(v), p});
    if (const toml::table* sub = v.as_table()) {
      checkUnread(*sub, p);
    } else if (const toml::array* arr = v.as_array()) {
      std::size_t i = 0;
      for (const toml::node& e : *arr) {
        if (const toml::table* et = e.as_table())
          checkUnread(*et, p + "[" + std::to_string(i) + "]");
        ++i;
      }
    }
  }
}

void TableReader::finish() const {
  checkUnread(*table_, prefix_);
}

} // namespace lamina::core
