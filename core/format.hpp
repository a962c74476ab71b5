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

/// Formats @p x with @p digits significant digits for humans ("%.*g"),
/// right-aligned in @p width characters (0: no padding). Every number a
/// person reads (stdout and stderr lines, tables, messages) goes through
/// this, with 4 to 6 digits; files a program reads (JSON, CSV, TOML, HDF5)
/// keep every digit (formatExact, or the writers' own full precision).
std::string formatShort(double x, int digits = 6, int width = 0);

/// @return @p text with & < > " ' replaced by XML entities (for attribute
/// values and text written into XDMF files)
std::string xmlEscape(const std::string& text);

/// @return the 6x6 matrix @p m (anything with m(i, j)) times @p scale as
/// text, one row per line: @p indent, then each value after a space,
/// formatShort(value, @p digits, @p width), a negative zero printed as 0
template <class Matrix>
std::string formatMatrix6(const Matrix& m, double scale, int digits, int width,
                          const std::string& indent) {
  std::string out;
  for (int i = 0; i < 6; ++i) {
    out += indent;
    for (int j = 0; j < 6; ++j)
      out += " " + formatShort(m(i, j) * scale + 0.0, digits, width); // + 0.0: -0 becomes 0
    out += "\n";
  }
  return out;
}

/// @return @p word as one word of a shell command a message suggests:
/// unchanged when it holds only letters, digits and - _ . / + : = , @ %,
/// else in single quotes (a quote inside written as '\'')
std::string shellWord(const std::string& word);

/// Joins @p names with ", " (for messages that list what a file holds).
std::string joinNames(const std::vector<std::string>& names);

} // namespace lamina::core
