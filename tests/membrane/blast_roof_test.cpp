// The blast on the large-deflection fabric: the energy balance closes with
// the blast's work included, and on the drag paper's roof (section 5, a
// coarse mesh) drag lowers both the peak deflection and the peak total
// support reaction, the direction of the paper's result (1.1 m vs 1.9 m,
// 150 kN vs 230 kN).
#include "helpers.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

using namespace lamina::membrane;

namespace {
nlohmann::json runText(const std::string& text, const std::string& out) {
  const Model model = test::modelFromText(text);
  RunOptions opt;
  opt.out_dir = test::tempPath(out);
  opt.quiet = true;
  const auto summary = runCase(model, opt);
  std::filesystem::remove_all(opt.out_dir);
  return summary;
}
} // namespace

// A 1 m square of fabric, clamped on its edges, 2 m above a 50 g charge
// (Z = 5.4 m/kg^(1/3)): the blast does work, the fabric moves, and
// T + U - W_blast - W_reactions stays within 1 % of the blast work (central
// differences conserve energy to O(dt^2); the trapezoidal work over the
// steps adds the same order; the 1 % bounds both at safety 0.5).
TEST(BlastRoof, EnergyBalanceClosesWithBlastWork) {
  const std::string text = test::blastPanel(8, 0.02) + R"(
[[blast]]
charge = 0.05
position = [0.5, 0.5, -2.0]
burst = "hemispherical"
[output]
fields = false
)";
  const auto s = runText(text, "blast-energy");
  const double W = s["energy"]["external_work"].get<double>();
  EXPECT_GT(W, 1.0); // the blast did work on the fabric (J)
  EXPECT_GT(s["max_abs_w"].get<double>(), 1e-3);
  EXPECT_LT(std::abs(s["energy"]["max_abs_balance"].get<double>()), 0.01 * W);
}

// The roof of the drag paper on a coarse mesh (lc = 1.5 m): with drag the
// peak vertical displacement and the peak total reaction are lower.
TEST(BlastRoof, DragLowersPeakDeflectionAndReaction) {
  std::ifstream in(test::sourcePath("cases/meshes/arched-roof.geo"));
  std::stringstream geo;
  geo << in.rdbuf();
  const std::string coarse = std::regex_replace(geo.str(), std::regex("lc = 0\\.5;"), "lc = 1.5;");
  const auto geo_path = test::tempPath("coarse-roof.geo");
  std::ofstream(geo_path) << coarse;
  std::ifstream case_in(test::sourcePath("cases/membrane/blast-roof.toml"));
  std::stringstream c;
  c << case_in.rdbuf();
  std::string text = std::regex_replace(c.str(), std::regex("\"\\.\\./meshes/arched-roof\\.geo\""),
                                        "\"" + geo_path.string() + "\"");
  text = std::regex_replace(text, std::regex("field_every = [0-9]+"), "fields = false");
  const auto s = runText(text, "blast-roof-coarse");
  std::filesystem::remove(geo_path);
  const auto& with = s["drag_comparison"]["with_drag"];
  const auto& without = s["drag_comparison"]["without_drag"];
  EXPECT_LT(with["max_abs_w"].get<double>(), without["max_abs_w"].get<double>());
  EXPECT_LT(with["peak_total_reaction"].get<double>(),
            without["peak_total_reaction"].get<double>());
  EXPECT_GT(with["max_abs_w"].get<double>(), 0.1); // the blast moved the roof
}
