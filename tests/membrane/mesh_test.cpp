// Meshes (structured, gmsh with regions and boundary sets) and run outputs.
#include "helpers.hpp"
#include "membrane/io/gmsh_reader.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

using namespace lamina::membrane;

TEST(MembraneMesh, StructuredRectangleIsThePapersGrid) {
  const Mesh m = structuredRectangle(2.0, 1.0, 4, 2);
  EXPECT_EQ(m.numNodes(), 15);
  EXPECT_EQ(m.numElements(), 16); // two triangles per square
  double area = 0;
  for (int e = 0; e < m.numElements(); ++e)
    area += m.area(e);
  EXPECT_NEAR(area, 2.0, 1e-14);
  EXPECT_EQ(m.node_sets.at("edges").size(), 12u);
}

TEST(MembraneMesh, GmshGeoGivesRegionsAndBoundarySets) {
  const Mesh m = readGmsh(test::sourcePath("cases/meshes/circle.geo"));
  ASSERT_EQ(m.regions.size(), 1u);
  EXPECT_EQ(m.regions[0], "membrane");
  double area = 0;
  for (int e = 0; e < m.numElements(); ++e)
    area += m.area(e);
  // Inscribed polygon of a circle R = 0.05 with edge R/20: area within 0.5 %.
  const double exact = 3.14159265358979323846 * 0.05 * 0.05;
  EXPECT_NEAR(area, exact, 5e-3 * exact);
  for (int i : m.node_sets.at("edge"))
    EXPECT_NEAR(m.nodes[i].norm(), 0.05, 1e-9);
  // Every node belongs to a triangle (gmsh's circle centre point is dropped).
  std::vector<bool> used(m.numNodes(), false);
  for (const auto& t : m.triangles)
    for (int i : t)
      used[i] = true;
  for (bool u : used)
    EXPECT_TRUE(u);
}

TEST(MembraneMesh, TwoRegionsGetTheirOwnMaterials) {
  const Model m = test::modelFromText(R"(
[mesh]
type = "gmsh"
file = "two-materials.geo"
[[section]]
region = "soft"
E = 1.0e8
nu = 0.3
density = 1000.0
thickness = 1.0e-3
[[section]]
region = "stiff"
material = "table1-anisotropic"
thickness = 2.0e-3
[time]
dt = 1.0e-6
t_end = 1.0e-5
)",
                                      "two-regions.toml");
  ASSERT_EQ(m.sections.size(), 2u);
  for (const auto& s : m.sections) {
    if (s.name == "soft")
      EXPECT_DOUBLE_EQ(s.thickness, 1e-3);
    else
      EXPECT_DOUBLE_EQ(s.D(5, 5), 30e9); // Table 1 c66
  }
}

TEST(MembraneRun, WritesTheFilesScriptsRelyOn) {
  const Model m = test::modelFromText(test::isotropicSquare(6) + R"(
[time]
dt = 1.0e-5
t_end = 1.0e-4
[[fixed]]
nodes = "edges"
[[strike]]
at = [0.5, 0.5]
speed = 2.0
[[probe]]
name = "centre"
at = [0.5, 0.5]
[[probe]]
name = "side"
at = [0.2, 0.5]
[output]
field_every = 5
)",
                                      "outputs.toml");
  RunOptions opt;
  opt.out_dir = test::tempPath("lamina-membrane-outputs");
  opt.quiet = true;
  std::filesystem::remove_all(opt.out_dir);
  const auto s = runModel(m, opt);
  std::ifstream probes(opt.out_dir / "probes.csv");
  std::string header;
  std::getline(probes, header);
  EXPECT_EQ(header, "t,centre_ux,centre_uy,centre_uz,centre_vx,centre_vy,centre_vz,side_ux,"
                    "side_uy,side_uz,side_vx,side_vy,side_vz");
  for (const char* k : {"nodes", "elements", "steps", "dt", "t_end", "max_abs_w", "max_speed",
                        "energy", "probes", "wall_s", "assembly_s", "factor_s", "step_s"})
    EXPECT_TRUE(s.contains(k)) << k;
  EXPECT_EQ(s["steps"].get<long>(), 10);
  // The strike node moves at 2 m/s for 1e-4 s: w = 2e-4 m exactly.
  EXPECT_NEAR(s["max_abs_w"].get<double>(), 2e-4, 1e-16);
  for (const char* f :
       {"outputs.xdmf", "outputs.h5", "energy.csv", "reactions.csv", "summary.json"})
    EXPECT_TRUE(std::filesystem::exists(opt.out_dir / f)) << f;
  std::ifstream x(opt.out_dir / "outputs.xdmf");
  const std::string xdmf((std::istreambuf_iterator<char>(x)), std::istreambuf_iterator<char>());
  EXPECT_NE(xdmf.find("step2"), std::string::npos); // steps 0, 5, 10
  EXPECT_EQ(xdmf.find("step3"), std::string::npos);
  std::filesystem::remove_all(opt.out_dir);
}
