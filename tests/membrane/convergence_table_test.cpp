// `membrane converge`'s text table: one table whose header and rows share
// their column positions (each value starts where its header does), with
// values of every width a study produces (a negative rate, 4-digit
// exponents, a 4-digit nx) and the rates as its last row.
#include "membrane/converge.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

using lamina::membrane::ConvergenceStudy;

namespace {

/// @return the start positions of the whitespace-separated words of @p line
std::vector<std::size_t> wordStarts(const std::string& line) {
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (line[i] != ' ' && (i == 0 || line[i - 1] == ' '))
      starts.push_back(i);
  return starts;
}

} // namespace

TEST(ConvergenceTable, HeaderAndRowsShareTheirColumns) {
  ConvergenceStudy s;
  s.nx = {10, 20, 40, 1280};
  s.dt = {2e-5, 1e-5, 5e-6, 1.5625e-7};
  s.du = {{1.234567e-4, 2.5e-4, 3.75e-3}, {6.1e-5, 1.0e-4, 1.9e-3}, {3.0e-5, 5.0e-5, 1.0e-3}};
  s.dv = {{0.12, 0.25, 1.5}, {0.061, 0.13, 0.8}, {0.03, 0.066, 0.41}};
  s.rate_u = {1.0234, 1.3, 0.95};
  s.rate_v = {-0.0123, 0.97, 1.1};
  std::istringstream in(s.toTable());
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  ASSERT_EQ(lines.size(), 1 + 1 + 4 + 1u) << s.toTable(); // legend, header, 4 levels, rates
  const std::string& header = lines[1];
  // the header's column starts, found by their names (two of them are "du L1"-like pairs)
  std::vector<std::size_t> columns;
  for (const char* name :
       {"level", "nx", "dt (s)", "du L1", "du L2", "du Linf", "dv L1", "dv L2", "dv Linf"}) {
    const std::size_t at = header.find(name, columns.empty() ? 0 : columns.back() + 1);
    ASSERT_NE(at, std::string::npos) << name << " not in: " << header;
    columns.push_back(at);
  }
  for (std::size_t k = 2; k < 6; ++k) // every level fills all nine columns
    EXPECT_EQ(wordStarts(lines[k]), columns) << header << "\n" << lines[k];
  // the rates: a label, then the six rates under the difference columns
  std::vector<std::size_t> rate_columns = {columns[0]};
  rate_columns.insert(rate_columns.end(), columns.begin() + 3, columns.end());
  EXPECT_EQ(wordStarts(lines[6]), rate_columns) << header << "\n" << lines[6];
  EXPECT_EQ(lines[6].substr(0, 4), "rate");
  EXPECT_NE(lines[6].find("-0.0123"), std::string::npos) << lines[6];
  EXPECT_EQ(lines[2].find('\t'), std::string::npos) << "no tabs: " << lines[2];
}
