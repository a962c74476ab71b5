#pragma once
// Helpers of the checkpoint/restart tests: a temporary folder, bit-for-bit
// comparison of two output folders, the `membrane` program's command line
// (run with the pipeline tests' helpers, ../pipeline/program.hpp).
#include "../pipeline/program.hpp"
#include "helpers.hpp"

#include "core/hdf5_file.hpp"
#include "membrane/io/case_file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace lamina::membrane::test {

/// The restart tests' case: a struck square, 30 Newmark steps, a probe,
/// reactions, and @p extra appended (e.g. an [output] table).
inline std::string strikeCase(const std::string& extra = "") {
  return isotropicSquare(4) +
         "[time]\ndt = 1.0e-5\nt_end = 3.0e-4\n[[fixed]]\nnodes = \"edges\"\n"
         "[[strike]]\nat = [0.5, 0.5]\nspeed = 1.0\n"
         "[[probe]]\nname = \"c\"\nat = [0.5, 0.5]\n" +
         extra;
}

/// The restart tests' case that runs twice (compare_without_drag): the
/// framed panel with and without drag, shrunk to 30 Newmark steps of a
/// 4 x 4 mesh (fields at steps 0, 20, 30).
inline Model dragComparisonCase() {
  return readCase(sourcePath("cases/membrane/impulsive-panel.toml"),
                  {"mesh.nx=4", "time.t_end=3.0e-3"}, testSources());
}

/// A fresh folder in the temp folder, removed at the end of the test.
struct Folder {
  /// Creates <tmp>/<pid>-<name> (emptied first).
  explicit Folder(const std::string& name) : path(tempPath(name)) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Folder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::filesystem::path path; ///< the folder
};

using lamina::test::slurp;

/// Expects @p a and @p b to hold the same doubles, bit for bit (memcmp).
inline void expectSameBits(const std::vector<double>& a, const std::vector<double>& b,
                           const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) {
      ADD_FAILURE() << what << ": value " << i << " differs: " << core::formatExact(a[i]) << " vs "
                    << core::formatExact(b[i]);
      return;
    }
}

/// The header and the numbers of a CSV table (each cell read with strtod,
/// which gives back the double exactly from its 17 digits).
inline std::pair<std::string, std::vector<double>> readTable(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ','))
      values.push_back(std::strtod(cell.c_str(), nullptr));
  }
  return {header, values};
}

/// Expects every number in the JSON @p a and @p b to be the same double,
/// bit for bit, and every other value equal; timings (keys ending in "_s")
/// and what says how the run ended are left out.
inline void expectSameJson(const nlohmann::json& a, const nlohmann::json& b,
                           const std::string& where) {
  static const std::set<std::string> skip = {"interrupted", "signal", "stopped_at_step"};
  if (a.is_object()) {
    ASSERT_TRUE(b.is_object()) << where;
    for (const auto& [key, value] : a.items()) {
      const bool timing = key.size() > 2 && key.compare(key.size() - 2, 2, "_s") == 0;
      if (timing || skip.count(key))
        continue;
      ASSERT_TRUE(b.contains(key)) << where << "/" << key;
      expectSameJson(value, b[key], where + "/" + key);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (size_t i = 0; i < a.size(); ++i)
      expectSameJson(a[i], b[i], where + "[" + std::to_string(i) + "]");
  } else if (a.is_number()) {
    ASSERT_TRUE(b.is_number()) << where;
    expectSameBits({a.get<double>()}, {b.get<double>()}, where);
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

/// Expects the output folders @p a and @p b of case @p stem to hold the
/// same results bit for bit: the tables, summary.json and every dataset
/// the field index names (the index itself byte for byte).
inline void expectSameOutputs(const std::filesystem::path& a, const std::filesystem::path& b,
                              const std::string& stem) {
  for (const char* table : {"probes.csv", "energy.csv", "reactions.csv"}) {
    if (!std::filesystem::exists(a / table))
      continue;
    const auto [ha, va] = readTable(a / table);
    const auto [hb, vb] = readTable(b / table);
    EXPECT_EQ(ha, hb) << table;
    EXPECT_GT(va.size(), 0u) << table;
    expectSameBits(va, vb, table);
    EXPECT_EQ(slurp(a / table), slurp(b / table)) << table; // no torn or duplicated row
  }
  expectSameJson(nlohmann::json::parse(slurp(a / "summary.json")),
                 nlohmann::json::parse(slurp(b / "summary.json")), "summary.json");
  const std::string index = slurp(a / (stem + ".xdmf"));
  if (index.empty())
    return;
  EXPECT_EQ(index, slurp(b / (stem + ".xdmf")));
  const core::H5File fa(a / (stem + ".h5"), core::H5File::Mode::ReadOnly);
  const core::H5File fb(b / (stem + ".h5"), core::H5File::Mode::ReadOnly);
  const std::regex dataset(R"(\.h5:(/steps/[^<]+)<)");
  int count = 0;
  for (std::sregex_iterator it(index.begin(), index.end(), dataset), end; it != end; ++it) {
    const std::string name = (*it)[1];
    std::vector<std::uint64_t> da, db;
    expectSameBits(fa.readDoubles(name, da), fb.readDoubles(name, db), name);
    EXPECT_EQ(da, db) << name;
    ++count;
  }
  EXPECT_GT(count, 0) << "no field dataset compared";
}

/// @return the command line of `membrane` with @p args (each quoted)
inline std::string membraneCommand(const std::vector<std::string>& args) {
  std::string c = "'" + (lamina::test::kBin / "membrane").string() + "'";
  for (const auto& a : args)
    c += " '" + a + "'";
  return c;
}

} // namespace lamina::membrane::test
