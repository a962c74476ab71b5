#pragma once
// Shared helpers of the membrane tests: build a Model from TOML text with
// inline or catalog materials (never the user's library).
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"
#include "membrane/integrators/step_solver.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/model/block_matrix.hpp"
#include "membrane/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace lamina::membrane::test {

/// A path in the temp folder unique to this process (parallel test runs
/// and several build trees must not share files).
inline std::filesystem::path tempPath(const std::string& name) {
  return std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "-" + name);
}

/// Material sources for tests: an empty library in the temp folder and the
/// source tree's catalog.
inline MaterialSources testSources() {
  const auto lib = tempPath("lamina-membrane-test-no-library.toml");
  std::filesystem::remove(lib);
  return {lib.string(), std::string(LAMINA_SOURCE_DIR) + "/materials/catalog.toml"};
}

/// A 1 m square of nx x nx squares on the large-deflection model, one
/// isotropic section (E = 10 MPa, nu = 0.3, rho h = 1 kg/m^2); @p extra is
/// appended (more section keys, then other tables).
inline std::string elasticSquare(int nx, const std::string& extra) {
  return R"(
model = "large_deflection"
[mesh]
Lx = 1.0
nx = )" + std::to_string(nx) +
         R"(
[[section]]
E = 10.0e6
nu = 0.3
density = 1000.0
thickness = 1.0e-3
)" + extra;
}

/// Builds a model from case text (name "test.toml" in errors).
inline Model modelFromText(const std::string& text, const std::string& name = "test.toml") {
  const toml::table doc = core::parseTomlString(text, name);
  return buildModel(doc, std::filesystem::path(LAMINA_SOURCE_DIR) / "cases/membrane" / name,
                    testSources());
}

/// @return the message of the error that building case @p text (named
/// @p name) gives, "" when it is accepted
inline std::string buildError(const std::string& text, const std::string& name = "test.toml") {
  try {
    modelFromText(text, name);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// Builds a model from case text (name "test.toml" in errors) with the
/// library file @p library and the source tree's catalog.
inline Model modelWithLibrary(const std::string& text, const std::filesystem::path& library) {
  const toml::table doc = core::parseTomlString(text, "test.toml");
  return buildModel(doc, std::filesystem::path(LAMINA_SOURCE_DIR) / "cases/membrane/test.toml",
                    {library.string(), std::string(LAMINA_SOURCE_DIR) + "/materials/catalog.toml"});
}

/// Expects an error @p message (not "": refused) that contains every one of @p parts.
inline void expectHas(const std::string& message, const std::vector<std::string>& parts) {
  ASSERT_FALSE(message.empty()) << "accepted";
  for (const auto& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << "no '" << p << "' in: " << message;
}

/// Section keys of an inline GVBO law with the polyurea chapter's Table 5
/// (SI: MPa -> Pa, 1/MPa -> 1/Pa; density 1.1 g/cm^3), as in the catalog.
inline std::string gvboTable5Keys() {
  return "law = \"gvbo\"\nE = 278.0e6\nnu = 0.491\ndensity = 1100.0\n"
         "gvbo = { Et = 23.3e6, p = -6.0, a1 = 0.0, a2 = 10.0e6, a3 = 0.0, k1 = 17.0, "
         "k2 = 0.47e6, k3 = 1.47e6, k4 = 4.0, Em = 13600.0e6, A0 = 1.0e6, Ac = 0.0, Af = 0.0 }\n";
}

/// TOML of a clamped 0.1 m square sheet (4 x 4 squares, one region "all")
/// on model @p model whose one section has the keys @p section and a 1 mm
/// thickness; explicit to 10 us.
inline std::string sectionSheet(const std::string& section,
                                const std::string& model = "large_deflection") {
  return "model = \"" + model + "\"\n[mesh]\nLx = 0.1\nnx = 4\n[[section]]\nregion = \"all\"\n" +
         section +
         "thickness = 1.0e-3\n[time]\nintegrator = \"explicit\"\nt_end = 1.0e-5\n"
         "[[fixed]]\nnodes = \"edges\"\n";
}

/// TOML of a square of side @p L with nx x nx squares and the isotropic
/// section used throughout (E = 1 GPa, nu = 0.3, rho = 1000, h = 1 mm).
inline std::string isotropicSquare(int nx, double L = 1.0) {
  return "[mesh]\nLx = " + core::formatExact(L) + "\nnx = " + std::to_string(nx) +
         "\n[[section]]\nE = 1.0e9\nnu = 0.3\ndensity = 1000.0\nthickness = 1.0e-3\n";
}

/// TOML of an anisotropic circle (cases/meshes/circle.geo, gmsh, Table 1's
/// material, 1 mm), edge fixed, tau = 2e-7 s up to @p t_end; @p mesh_extra
/// adds keys to [mesh] (e.g. renumber).
inline std::string anisotropicCircle(double t_end, const std::string& mesh_extra = "") {
  return "[mesh]\ntype = \"gmsh\"\nfile = \"../meshes/circle.geo\"\n" + mesh_extra +
         "[[section]]\nregion = \"membrane\"\nmaterial = \"table1-anisotropic\"\n"
         "thickness = 1.0e-3\n[time]\ndt = 2.0e-7\nt_end = " +
         core::formatExact(t_end) + "\n[[fixed]]\nnodes = \"edge\"\n";
}

/// TOML of the blast tests' panel: a flat 1 m square of @p nx x nx squares
/// of the roof's coated vinyl (E = 580 MPa, nu = 0.3, 1280 kg/m^3, 0.53 mm,
/// tension only) on the large-deflection model, edges clamped, explicit to
/// @p t_end; the caller adds the [[blast]] table.
inline std::string blastPanel(int nx, double t_end) {
  return "model = \"large_deflection\"\n[mesh]\ntype = \"rectangle\"\nLx = 1.0\nnx = " +
         std::to_string(nx) +
         "\n[[section]]\nE = 580.0e6\nnu = 0.3\ndensity = 1280.0\nthickness = 0.53e-3\n"
         "tension_only = true\n[time]\nintegrator = \"explicit\"\nsafety = 0.5\nt_end = " +
         core::formatExact(t_end) + "\n[[fixed]]\nnodes = \"edges\"\n";
}

/// The [[blast]] of the blast panel's tests: 0.05 kg TNT 2 m below the
/// centre of the blastPanel() square, hemispherical.
inline const std::string kPanelBlast = R"(
[[blast]]
charge = 0.05
position = [0.5, 0.5, -2.0]
burst = "hemispherical"
)";

/// TOML of a rigid set tying the z of the nodes @p nodes (a selector value,
/// e.g. "right") together, on springs of @p stiffness N/m each in z.
inline std::string rigidOnSprings(const std::string& nodes, double stiffness) {
  return "[[rigid]]\nnodes = \"" + nodes + "\"\ncomponents = \"z\"\n[[spring]]\nnodes = \"" +
         nodes + "\"\ncomponents = \"z\"\nstiffness = " + core::formatExact(stiffness) + "\n";
}

/// A constraint moving every node of @p mesh with velocity (rx x, ry y, 0):
/// the uniform in-plane stretch F = diag(1 + rx t, 1 + ry t).
inline Constraint uniformStretch(const Mesh& mesh, double rx, double ry) {
  Constraint c;
  c.name = "stretch";
  for (int i = 0; i < mesh.numNodes(); ++i)
    for (int k = 0; k < 3; ++k) {
      c.dofs.push_back(3 * i + k);
      c.amplitude.push_back(k == 0 ? rx * mesh.nodes[i].x() : k == 1 ? ry * mesh.nodes[i].y() : 0);
    }
  return c;
}

/// Largest |balance| and the energy scale it is compared with.
struct BalanceTracker {
  double worst = 0; ///< max |E - E0 - W|
  double scale = 0; ///< max of T + U and |works|
  /// Records one step's energies.
  void add(const Energy& e) {
    worst = std::max(worst, std::abs(e.balance));
    scale = std::max({scale, e.kinetic + e.strain, std::abs(e.external_work),
                      std::abs(e.reaction_work), std::abs(e.drag_work)});
  }
};

/// Path of a file in the source tree.
inline std::filesystem::path sourcePath(const std::string& rel) {
  return std::filesystem::path(LAMINA_SOURCE_DIR) / rel;
}

/// True when @p a and @p b hold the same bits (the sign of a zero included).
inline bool sameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

/// Sets the process-wide plane skipping back to its default when it goes
/// out of scope (a failed assertion or an exception included).
struct SkippingRestored {
  ~SkippingRestored() { BlockMatrix::usePlaneSkipping(PlaneSkipping::Automatic); }
};

/// Solves A x = b by CG (tolerance 1e-10, from x = 0) for @p b with its
/// in-plane components zeroed, with the products skipping zero planes and
/// without: expects the normal plane alone in the first and the same
/// iterations (more than 2) and bits in both. Then sets b's component
/// @p inplane_dof (an in-plane one) to 1 and expects the full products and a
/// solution not zero there. @return the first solution and its b.
inline std::pair<Eigen::VectorXd, Eigen::VectorXd>
expectNormalPlaneSolve(const SparseMatrix& A, Eigen::VectorXd b, int inplane_dof) {
  const int n = static_cast<int>(A.rows());
  for (int i = 0; i < n; i += 3)
    b[i] = b[i + 1] = 0;
  const SkippingRestored restore;
  Eigen::VectorXd x[2];
  int iterations[2];
  for (int k = 0; k < 2; ++k) {
    BlockMatrix::usePlaneSkipping(k == 0 ? PlaneSkipping::Automatic : PlaneSkipping::Never);
    StepSolver solver(A, LinearSolverKind::Cg, 1e-10, 1000);
    x[k] = Eigen::VectorXd::Zero(n);
    iterations[k] = solver.solve(b, x[k]);
    EXPECT_EQ(solver.lastPlanes(), k == 0 ? BlockPlanes::Normal : BlockPlanes::All);
  }
  BlockMatrix::usePlaneSkipping(PlaneSkipping::Automatic);
  EXPECT_GT(iterations[0], 2); // the CG did iterate
  EXPECT_EQ(iterations[0], iterations[1]);
  EXPECT_TRUE(sameBits(x[0], x[1]));
  Eigen::VectorXd b1 = b;
  b1[inplane_dof] = 1.0;
  StepSolver solver(A, LinearSolverKind::Cg, 1e-10, 1000);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  solver.solve(b1, y);
  EXPECT_EQ(solver.lastPlanes(), BlockPlanes::All);
  EXPECT_NE(y[inplane_dof], 0.0);
  return {x[0], b};
}

} // namespace lamina::membrane::test
