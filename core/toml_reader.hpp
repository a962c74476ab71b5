#pragma once
/// @file toml_reader.hpp
/// @brief Strict reading of TOML input (case files, cells, catalog, library).
///
/// Contract: every value is read through a TableReader, which records what it
/// read. After reading, the root reader's finish() walks the whole document
/// and throws lamina::Error for the first key that was never read, naming
/// the file, the line and the dotted key. Type errors and missing required
/// keys are reported the same way. Nothing is silently ignored.

#include "core/enum_names.hpp"

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lamina::core {

/// Largest TOML input read (bytes): a library of thousands of entries fits;
/// anything larger is refused before it is read into memory.
inline constexpr std::uintmax_t kMaxTomlBytes = 64u << 20;
/// Deepest nesting accepted: brackets and braces plus the components of a
/// dotted key. toml++ recurses once per level and has no limit of its own
/// for dotted keys, so deeper input could overflow the stack.
inline constexpr int kMaxTomlDepth = 64;

/// Refuses (lamina::Error naming @p source and the line) text larger than
/// kMaxTomlBytes or nested deeper than kMaxTomlDepth. Scans strings and
/// comments as TOML does, so brackets and dots inside them do not count.
void checkTomlLimits(std::string_view text, const std::string& source);

/// @return the whole content of the input file @p path; throws lamina::Error
/// naming the file when it cannot be opened, is not a regular file or is
/// larger than kMaxTomlBytes (checked before reading; see input_file.hpp).
std::string readInputFile(const std::filesystem::path& path);

/// Parses a TOML file. Throws lamina::Error naming the file (and the line of
/// a syntax error) when it cannot be read or parsed.
toml::table parseTomlFile(const std::filesystem::path& path);

/// Parses TOML text (checkTomlLimits first); @p source_name names it in
/// error messages.
toml::table parseTomlString(std::string_view text, const std::string& source_name);

/// Applies a command-line override "a.b.c=value" to @p doc. The value is
/// parsed as a TOML value (number, bool, string in quotes, array); a bare word
/// that is not valid TOML is taken as a string. Intermediate tables are
/// created; "name[i].key" addresses element i of an array of tables
/// (`[[name]]`). Throws lamina::Error on a malformed override. The values
/// it sets carry the assignment as their source: a later error about one
/// names "--set KEY=VALUE" instead of the file.
void applyOverride(toml::table& doc, const std::string& assignment);

/// Strict, recording view of one TOML table. Copies share the record of
/// what was read, so a reader for a sub-table marks keys of the whole
/// document. The viewed table must outlive the reader.
class TableReader {
public:
  /// @param table the table to read
  /// @param file file name used in error messages
  /// @param prefix dotted path of @p table in the document ("" for the root)
  TableReader(const toml::table& table, std::string file, std::string prefix = "");

  /// @return whether @p key is present (does not mark it read)
  bool has(std::string_view key) const;
  /// @return the keys present, in document order
  std::vector<std::string> keys() const;

  /// Required finite number (integer or float accepted; nan and inf are
  /// errors naming the key).
  double getDouble(std::string_view key) const;
  /// Optional number with a default.
  double getDouble(std::string_view key, double fallback) const;
  /// Required integer.
  std::int64_t getInt(std::string_view key) const;
  /// Optional integer with a default.
  std::int64_t getInt(std::string_view key, std::int64_t fallback) const;
  /// Required integer in [@p lo, @p hi]; an error names the range otherwise.
  std::int64_t getIntIn(std::string_view key, std::int64_t lo, std::int64_t hi) const;
  /// Optional integer in [@p lo, @p hi] with a default.
  std::int64_t getIntIn(std::string_view key, std::int64_t lo, std::int64_t hi,
                        std::int64_t fallback) const;
  /// Optional boolean with a default.
  bool getBool(std::string_view key, bool fallback) const;
  /// Required string.
  std::string getString(std::string_view key) const;
  /// Optional string with a default.
  std::string getString(std::string_view key, const std::string& fallback) const;
  /// Optional choice: the string at @p key (or @p fallback when absent)
  /// mapped through @p choices (name, value). Any other string is an error
  /// naming the key and listing the names. One vocabulary per choice: the
  /// enum the caller keeps, never the string.
  template <class E>
  E getChoice(std::string_view key, std::initializer_list<std::pair<std::string_view, E>> choices,
              E fallback) const {
    return getChoiceFrom(key, choices, fallback);
  }
  /// getChoice() with a name table kept by the enum's owner (a container of
  /// (name, value) pairs, e.g. a core::EnumNames table that the CLI shares).
  template <class E, class Choices>
  E getChoice(std::string_view key, const Choices& choices, E fallback) const {
    return getChoiceFrom(key, choices, fallback);
  }
  /// Required choice: as getChoice() with a name table, and a missing
  /// @p key is an error naming it.
  template <class Choices>
  auto getChoice(std::string_view key, const Choices& choices) const {
    return choiceOf(key, choices);
  }
  /// Required array of finite numbers.
  std::vector<double> getDoubleArray(std::string_view key) const;
  /// Required array of strings.
  std::vector<std::string> getStringArray(std::string_view key) const;
  /// Required array of arrays of finite numbers (a matrix, rows first).
  std::vector<std::vector<double>> getMatrix(std::string_view key) const;

  /// Required sub-table.
  TableReader table(std::string_view key) const;
  /// Optional sub-table.
  std::optional<TableReader> optionalTable(std::string_view key) const;
  /// Array of tables (`[[key]]`); empty if absent.
  std::vector<TableReader> tableArray(std::string_view key) const;

  /// Marks @p key and everything below it as read and returns the node
  /// (nullptr if absent). For free-form content such as provenance.
  const toml::node* raw(std::string_view key) const;

  /// Checks that every key of the whole document was read. Call on the root
  /// reader once reading is done. Throws lamina::Error on the first unknown key.
  void finish() const;

  /// Throws lamina::Error about @p key of this table (file, line, dotted key).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  /// Throws lamina::Error about this table itself.
  [[noreturn]] void failHere(const std::string& message) const;

  /// @return the dotted path of @p key in the document
  std::string path(std::string_view key) const;
  /// @return the file name given at construction
  const std::string& file() const { return file_; }
  /// @return the viewed table
  const toml::table& tomlTable() const { return *table_; }

private:
  /// getChoice()'s lookup over any container of (name, value) pairs.
  template <class E, class Choices>
  E getChoiceFrom(std::string_view key, const Choices& choices, E fallback) const {
    return has(key) ? choiceOf(key, choices) : fallback;
  }
  /// The value of the name at @p key (required) in @p choices; an error
  /// naming the key and listing the names otherwise.
  template <class Choices>
  auto choiceOf(std::string_view key, const Choices& choices) const {
    const std::string v = getString(key);
    std::vector<std::string_view> names;
    for (const auto& [name, value] : choices) {
      if (name == v)
        return value;
      names.push_back(name);
    }
    fail(key, "unknown value \"" + v + "\" (expected " + choiceList(names, '"') + ")");
  }
  struct Record {
    std::set<std::string> read;  // dotted paths read
    std::set<std::string> whole; // dotted paths accepted with their subtree
  };
  const toml::node& require(std::string_view key) const;
  double finite(std::string_view key, double v) const;
  void mark(std::string_view key) const;
  void checkUnread(const toml::table& t, const std::string& prefix) const;

  const toml::table* table_;
  std::string file_;
  std::string prefix_;
  std::shared_ptr<Record> record_;
};

} // namespace lamina::core
