#pragma once
/// @file pair_table.hpp
/// @brief Two-column text tables (a blast's pressure history, a yarn's
/// stress-strain curve): one reader, one set of messages.

#include <string>
#include <vector>

namespace lamina::core {

/// One data row of a two-column table, with its line in the file.
struct PairRow {
  double first = 0;  ///< first column
  double second = 0; ///< second column
  int line = 0;      ///< 1-based line of the file
};

/// @return the data rows of the two-column table @p text, the contents of
/// file @p path: '#' starts a comment, blank lines are skipped, columns are
/// separated by commas or blanks, and a first non-blank line that is not two
/// numbers is a header (skipped). Any later line that is not exactly two
/// numbers throws lamina::Error "expected two numbers @p columns" naming
/// @p path, its line and @p key. The values are not checked further.
std::vector<PairRow> readPairRows(const std::string& text, const std::string& path,
                                  const std::string& key, const std::string& columns);

} // namespace lamina::core
