#include "core/pair_table.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <sstream>

namespace lamina::core {

std::vector<PairRow> readPairRows(const std::string& text, const std::string& path,
                                  const std::string& key, const std::string& columns) {
  std::istringstream in(text);
  std::vector<PairRow> rows;
  std::string line;
  int line_no = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos)
      line.erase(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    PairRow r;
    r.line = line_no;
    std::string rest;
    const bool numeric = static_cast<bool>(row >> r.first >> r.second) && !(row >> rest);
    if (!numeric && header_allowed) { // a header such as "time,pressure"
      header_allowed = false;
      continue;
    }
    header_allowed = false;
    if (!numeric)
      throw Error("expected two numbers " + columns, {path, line_no, key});
    rows.push_back(r);
  }
  return rows;
}

} // namespace lamina::core
