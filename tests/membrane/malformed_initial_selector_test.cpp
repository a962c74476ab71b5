// [initial] with a bad node selector: each error names the file, the
// [initial] table and the selector key.
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace lamina::membrane;

namespace {
const std::string kCase = test::isotropicSquare(4) +
                          "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n[[fixed]]\nnodes = \"edges\"\n"
                          "[initial]\nvelocity = [0.0, 0.0, -10.0]\n";

void expectNames(const std::string& e, const std::vector<std::string>& parts) {
  ASSERT_FALSE(e.empty()) << "accepted";
  EXPECT_NE(e.find("initial.toml"), std::string::npos) << e;
  for (const auto& p : parts)
    EXPECT_NE(e.find(p), std::string::npos) << "no '" << p << "' in: " << e;
}
} // namespace

TEST(MalformedInitialSelector, GoodSelectorsBuild) {
  for (const std::string sel : {"box = [0.25, 0.75, 0.25, 0.75]", "at = [0.5, 0.5]",
                                "nodes = \"edges\"", "all = true", "region = \"all\""})
    EXPECT_EQ(test::buildError(kCase + sel + "\n", "initial.toml"), "") << sel;
}

TEST(MalformedInitialSelector, BadSelectorIsNamed) {
  // A box off the mesh selects nothing; a point off the mesh is a typo.
  expectNames(test::buildError(kCase + "box = [2.0, 3.0, 2.0, 3.0]\n", "initial.toml"),
              {"initial.box", "selects no node"});
  expectNames(test::buildError(kCase + "at = [5.0, 0.5]\n", "initial.toml"),
              {"initial.at", "outside mesh"});
  expectNames(test::buildError(kCase + "box = [0.75, 0.25, 0.0, 1.0]\n", "initial.toml"),
              {"initial.box", "[xmin, xmax, ymin, ymax]"});
  expectNames(test::buildError(kCase + "nodes = \"rim\"\n", "initial.toml"),
              {"initial.nodes", "no node set 'rim'"});
  expectNames(test::buildError(kCase + "region = \"core\"\n", "initial.toml"),
              {"initial.region", "no region 'core'"});
  expectNames(test::buildError(kCase + "all = false\n", "initial.toml"),
              {"initial.all", "selects nothing"});
  // Two selectors: which one was meant is not for the reader to guess.
  expectNames(test::buildError(kCase + "at = [0.5, 0.5]\nbox = [0.0, 1.0, 0.0, 1.0]\n",
                               "initial.toml"),
              {"initial", "give exactly one of nodes, box, at, region, all"});
}
