#include "core/toml_reader.hpp"

#include "core/error.hpp"
#include "core/input_file.hpp"

#include <cmath>
#include <cstdlib>
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

/// The source name of a value a --set override put in a document: the
/// assignment itself, "--set KEY=VALUE", so an error about it names it.
constexpr std::string_view kOverrideSource = "--set ";

/// Where @p n (a value of @p file, or nullptr for a missing key of @p table)
/// comes from, for an error about @p key: the --set assignment that gave
/// the value, else the file and the line.
ErrorContext contextOf(const toml::node* n, const toml::node& table, const std::string& file,
                       std::string key) {
  const toml::node& at = n ? *n : table;
  if (const auto& source = at.source().path; source && source->rfind(kOverrideSource, 0) == 0)
    return {*source, 0, std::move(key)};
  return {file, lineOfNode(at), std::move(key)};
}

/// @return @p text parsed as the value of one key, its source the
/// assignment @p source (a bare word that is not TOML: a string)
toml::table overrideValue(const std::string& text, const std::string& source) {
  try {
    return toml::parse("v = " + text, source);
  } catch (const toml::parse_error&) {
    std::ostringstream quoted;
    quoted << toml::table{{"v", text}};
    return toml::parse(quoted.str(), source);
  }
}

/// Depth of TOML nesting along a scan: every open bracket or brace adds one
/// level, every component of a dotted key (or table header) another.
class DepthScanner {
public:
  DepthScanner(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  void scan() {
    for (i_ = 0; i_ < text_.size(); ++i_) {
      const char c = text_[i_];
      switch (c) {
      case '\n':
        ++line_;
        if (open_.empty()) { // a new top-level line: a key or a [header]
          in_key_ = true;
          dots_ = 0;
          if (in_header_)
            section_ = header_depth_;
          in_header_ = false;
        }
        break;
      case '#':
        while (i_ + 1 < text_.size() && text_[i_ + 1] != '\n')
          ++i_;
        break;
      case '"':
      case '\'':
        skipString(c);
        break;
      case '[':
      case '{':
        if (open_.empty() && in_key_ && c == '[') { // a [table] header starts from the root
          in_header_ = true;
          header_depth_ = 0;
        }
        open_.push_back({depth() + 1, c == '{'});
        dots_ = 0;
        check();
        in_key_ = c == '{' || in_header_;
        break;
      case ']':
      case '}':
        if (!open_.empty())
          open_.pop_back();
        in_key_ = false;
        break;
      case ',': // the next key of an inline table, or the next array value
        in_key_ = !open_.empty() && open_.back().brace;
        dots_ = 0;
        break;
      case '=':
        in_key_ = false;
        break;
      case '.':
        if (in_key_) {
          ++dots_;
          check();
        }
        break;
      default:
        break;
      }
    }
  }

private:
  int depth() const {
    if (!open_.empty())
      return open_.back().depth + dots_;
    return (in_header_ ? 0 : section_) + dots_;
  }
  void check() {
    const int d = depth();
    if (in_header_)
      header_depth_ = std::max(header_depth_, d);
    if (d > kMaxTomlDepth)
      throw Error("TOML nested deeper than " + std::to_string(kMaxTomlDepth) +
                      " levels (brackets, braces and dotted-key components); refusing to parse",
                  {source_, line_, ""});
  }
  void skipString(char q) {
    const bool triple = i_ + 2 < text_.size() && text_[i_ + 1] == q && text_[i_ + 2] == q;
    i_ += triple ? 3 : 1;
    for (; i_ < text_.size(); ++i_) {
      const char c = text_[i_];
      if (c == '\n')
        ++line_;
      if (q == '"' && c == '\\') {
        ++i_;
        if (i_ < text_.size() && text_[i_] == '\n')
          ++line_;
        continue;
      }
      if (c == q &&
          (!triple || (i_ + 2 < text_.size() && text_[i_ + 1] == q && text_[i_ + 2] == q))) {
        if (triple)
          i_ += 2;
        return;
      }
    }
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t i_ = 0;
  int line_ = 1;
  struct Open {
    int depth;  // depth reached by this bracket or brace
    bool brace; // an inline table (keys follow '{' and ',')
  };
  std::vector<Open> open_;
  int dots_ = 0;    // components so far of the key being read
  int section_ = 0; // depth of the current [table] header
  int header_depth_ = 0;
  bool in_key_ = true;
  bool in_header_ = false;
};

} // namespace

void checkTomlLimits(std::string_view text, const std::string& source) {
  if (text.size() > kMaxTomlBytes)
    throw Error("TOML input of " + std::to_string(text.size()) + " bytes exceeds the limit of " +
                    std::to_string(kMaxTomlBytes) + " bytes",
                {source, 0, ""});
  DepthScanner(text, source).scan();
}

std::string readInputFile(const std::filesystem::path& path) {
  return readWholeFile(path, kMaxTomlBytes, "TOML file");
}

toml::table parseTomlFile(const std::filesystem::path& path) {
  return parseTomlString(readInputFile(path), path.string());
}

toml::table parseTomlString(std::string_view text, const std::string& source_name) {
  checkTomlLimits(text, source_name);
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
  checkTomlLimits(assignment, "--set " + key);
  const std::string source = std::string(kOverrideSource) + assignment;
  toml::table parsed = overrideValue(value, source);
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
      t->insert_or_assign(part, std::move(*parsed.get("v"))); // moved: keeps its source
      return;
    }
    toml::node* next = t->get(part);
    if (!next) { // a new table, from the override too
      t->insert(part, std::move(*overrideValue("{}", source).get("v")));
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

void TableReader::fail(std::string_view key, const std::string& message) const {
  throw Error(message, contextOf(table_->get(key), *table_, file_, path(key)));
}

void TableReader::failHere(const std::string& message) const {
  throw Error(message, contextOf(table_, *table_, file_, prefix_));
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
    return finite(key, *v);
  fail(key, "expected a number, got " + typeName(n));
}

double TableReader::finite(std::string_view key, double v) const {
  if (!std::isfinite(v))
    fail(key, "expected a finite number, got " + std::string(std::isnan(v) ? "nan" : "inf"));
  return v;
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

std::int64_t TableReader::getIntIn(std::string_view key, std::int64_t lo, std::int64_t hi) const {
  const std::int64_t v = getInt(key);
  if (v < lo || v > hi)
    fail(key, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                  "], got " + std::to_string(v));
  return v;
}

std::int64_t TableReader::getIntIn(std::string_view key, std::int64_t lo, std::int64_t hi,
                                   std::int64_t fallback) const {
  return has(key) ? getIntIn(key, lo, hi) : fallback;
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
      out.push_back(finite(key, *v));
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
        values.push_back(finite(key, *v));
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
      throw Error("unknown key (not part of this file's format)", contextOf(&v, t, file_, p));
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
