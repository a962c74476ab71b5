/// @file text_output_test.cpp
/// @brief What a person reads, through the built programs: numbers in
/// text with at most 6 significant digits, one unit per `materials show`
/// screen, `homogenize` naming the library that received its entry and
/// ending its progress line with the real CG counts, and a case whose
/// material is missing naming the command that makes it.

#include "program.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

using namespace lamina::test;

namespace {

/// @return the significant digits of the decimal number @p token
/// ("0.0008000000000000014" -> 16, "1.23457e-07" -> 6, "2000" -> 1)
int significantDigits(std::string token) {
  const std::size_t e = token.find_first_of("eE");
  if (e != std::string::npos)
    token.resize(e);
  std::string digits;
  for (char c : token)
    if (c >= '0' && c <= '9')
      digits += c;
  const std::size_t first = digits.find_first_not_of('0');
  if (first == std::string::npos)
    return 0;
  digits.erase(0, first);
  if (token.find('.') == std::string::npos) // an integer: trailing zeros are not digits shown
    digits.erase(digits.find_last_not_of('0') + 1);
  return static_cast<int>(digits.size());
}

/// @return the numbers of @p text that carry a fraction or an exponent
/// (counts and indices are integers, exact) with more than 6
/// significant digits
std::vector<std::string> longNumbers(const std::string& text) {
  static const std::regex number(R"([0-9]*\.[0-9]+(?:[eE][-+]?[0-9]+)?|[0-9]+[eE][-+]?[0-9]+)");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number);
       it != std::sregex_iterator(); ++it)
    if (significantDigits(it->str()) > 6)
      out.push_back(it->str());
  return out;
}

/// @return @p text with every occurrence of @p what replaced by "DIR"
std::string without(std::string text, const std::string& what) {
  for (std::size_t at; (at = text.find(what)) != std::string::npos;)
    text.replace(at, what.size(), "DIR");
  return text;
}

std::string bin(const std::string& program) {
  return (kBin / program).string();
}

} // namespace

// The checker itself: the issue's example (a summed 0.0008) is caught.
TEST(TextOutput, TheDigitCounterCatchesARawDouble) {
  EXPECT_EQ(significantDigits("0.0008000000000000014"), 16);
  EXPECT_EQ(significantDigits("1.23457e-07"), 6);
  EXPECT_EQ(longNumbers("max |w| 0.0008000000000000014 m, 40 steps, t = 1e-05"),
            std::vector<std::string>{"0.0008000000000000014"});
}

// `membrane run`'s text (the progress log and the summary line on stderr)
// prints every number with at most 6 significant digits. Case 1 for 40
// steps: its maximum deflection and energy balance are sums of many terms,
// full 17-digit doubles.
TEST(TextOutput, MembraneRunPrintsAtMostSixDigits) {
  ASSERT_TRUE(have("membrane"));
  const fs::path dir = freshTestDir("lamina_text_output");
  const Result r = run(bin("membrane") + " run '" + (kCases / "membrane/case1.toml").string() +
                       "' --out '" + (dir / "out").string() + "' --set time.t_end=4e-4");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string text = without(r.output, dir.string());
  EXPECT_NE(text.find("max |w| "), std::string::npos) << text;
  EXPECT_EQ(longNumbers(text), std::vector<std::string>{}) << text;
  // the JSON keeps every digit: its max_abs_w reads back as the double the text rounded
  const Result j = run(bin("membrane") + " run '" + (kCases / "membrane/case1.toml").string() +
                       "' --out '" + (dir / "json").string() + "' --set time.t_end=4e-4 --json");
  ASSERT_EQ(j.code, 0) << j.output;
  const double w = nlohmann::json::parse(slurp(dir / "json" / "summary.json")).at("max_abs_w");
  char six[32];
  std::snprintf(six, sizeof six, "max |w| %.6g m", w);
  EXPECT_NE(text.find(six), std::string::npos) << six << " not in " << text;
  fs::remove_all(dir);
}

// `materials show` states its stiffness unit once per line, GPa for C and
// for the engineering constants alike (the catalog's e-glass: E = 72.4 GPa).
TEST(TextOutput, MaterialsShowUsesOneStiffnessUnit) {
  ASSERT_TRUE(have("materials"));
  const fs::path dir = freshTestDir("lamina_text_output");
  const std::string materials =
      bin("materials") + " --library '" + (dir / "lib.toml").string() + "'";
  ASSERT_EQ(run(materials + " add glass --from-catalog e-glass").code, 0);
  const Result r = run(materials + " show glass");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("C (GPa"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("E1 72.4  E2 72.4  E3 72.4 GPa"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(" Pa\n"), std::string::npos) << "a line in Pa: " << r.output;
  EXPECT_EQ(longNumbers(r.output), std::vector<std::string>{}) << r.output;
  fs::remove_all(dir);
}

// `homogenize --json` names the library file that received the entry (its
// absolute path), the text says "added 'NAME' to LIBRARY", and the
// progress log on stderr ends with the CG iterations of the six load
// cases, the same counts the JSON reports.
TEST(TextOutput, HomogenizeNamesTheLibraryAndTheRealIterations) {
  ASSERT_TRUE(have("homogenize"));
  const fs::path dir = freshTestDir("lamina_text_output");
  const fs::path lib = dir / "lib.toml";
  const std::string cell = (kCases / "cells/sphere.toml").string();
  const Result r = run("cd '" + dir.string() + "' && " + bin("homogenize") + " '" + cell +
                       "' --name s --resolution 8 --library lib.toml --json");
  ASSERT_EQ(r.code, 0) << r.output;
  nlohmann::json j; // the one line of JSON on stdout (the progress log is on stderr)
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] == '{')
      j = nlohmann::json::parse(line);
  ASSERT_TRUE(j.is_object()) << r.output;
  // absolute: the working directory made absolute, as the shell's cd left it
  EXPECT_EQ(j.at("library").get<std::string>(), (fs::canonical(dir) / "lib.toml").string());
  std::string counts;
  for (int it : j.at("iterations").get<std::vector<int>>())
    counts += " " + std::to_string(it);
  EXPECT_NE(r.output.find("CG iterations per load case:" + counts), std::string::npos)
      << counts << " not in " << r.output;
  EXPECT_NE(r.output.find("load case 6/6: "), std::string::npos) << r.output;
  const Result text = run(bin("homogenize") + " '" + cell +
                          "' --name t --resolution 8 --library '" + lib.string() + "'");
  ASSERT_EQ(text.code, 0) << text.output;
  EXPECT_NE(text.output.find("added 't' to " + lib.string()), std::string::npos) << text.output;
  EXPECT_EQ(longNumbers(without(text.output, dir.string())), std::vector<std::string>{})
      << text.output;
  fs::remove_all(dir);
}

// The micro-inertia case needs a homogenized entry; with an empty library
// its error names the library searched and the command that makes the
// entry from the cell file the case names (material_from).
TEST(TextOutput, AMissingEntryNamesTheCommandThatMakesIt) {
  ASSERT_TRUE(have("membrane"));
  const fs::path dir = freshTestDir("lamina_text_output");
  const fs::path lib = dir / "empty.toml";
  const Result r =
      run(bin("membrane") + " run '" + (kCases / "membrane/laminate-pulse.toml").string() +
          "' --library '" + lib.string() + "' --out '" + (dir / "out").string() + "'");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("steel-pu-laminate"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not in library " + lib.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("make it with: homogenize " + (kCases / "cells/laminate.toml").string() +
                          " --name steel-pu-laminate --library " + lib.string()),
            std::string::npos)
      << r.output;
  fs::remove_all(dir);
}
