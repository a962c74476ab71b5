// Element and assembly: patch test, rigid motions, isotropic decoupling.
#include "helpers.hpp"
#include "membrane/integrators/step_solver.hpp"
#include "membrane/model/assembly.hpp"
#include "membrane/model/block_matrix.hpp"
#include "membrane/model/mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

using namespace lamina::membrane;

namespace {

/// A fully populated symmetric positive definite 6x6 (couples every strain).
lamina::materials::Matrix6 generalD() {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> d(-1, 1);
  lamina::materials::Matrix6 B;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      B(i, j) = d(gen);
  return 1e9 * (B * B.transpose() + 6 * lamina::materials::Matrix6::Identity());
}

/// generalD() without the terms that couple the in-plane and normal strains
/// (xx, yy, zz, xy; lamina order 0-3) with the transverse shears (yz, xz;
/// 4, 5): a monoclinic law whose flat membrane has no block coupling u, v
/// with w.
lamina::materials::Matrix6 monoclinicD() {
  lamina::materials::Matrix6 D = generalD();
  for (int i : {0, 1, 2, 3})
    for (int j : {4, 5})
      D(i, j) = D(j, i) = 0;
  return D;
}

/// 4x4 squares with interior nodes moved off the grid: an irregular mesh.
Mesh irregularMesh() {
  Mesh m = structuredRectangle(1.0, 1.0, 4, 4);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> d(-0.08, 0.08);
  for (int j = 1; j < 4; ++j)
    for (int i = 1; i < 4; ++i)
      m.nodes[j * 5 + i] += Eigen::Vector2d(d(gen), d(gen));
  finalizeMesh(m);
  return m;
}

/// The unit square in @p n x @p n squares, interior nodes moved by up to
/// @p amplitude in x and y (seeded @p seed): no two rows alike.
Mesh perturbedGrid(int n, double amplitude, unsigned seed) {
  Mesh m = structuredRectangle(1.0, 1.0, n, n);
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i)
      m.nodes[j * (n + 1) + i] += Eigen::Vector2d(d(gen), d(gen));
  finalizeMesh(m);
  return m;
}

Section section(const lamina::materials::Matrix6& D) {
  Section s;
  s.D = D;
  s.density = 1500;
  s.thickness = 2e-3;
  return s;
}

/// Plain blocks: both products (@p y interleaved, @p yi from the planar
/// one) equal bit for bit the scalar product of the CSR matrix @p K taken
/// block after block, y_c += K(c,0) x_0 + K(c,1) x_1 + K(c,2) x_2 (so the
/// vectorized kernel changes no result).
void expectBlockRowOrder(const SparseMatrix& K, const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                         const Eigen::VectorXd& yi) {
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* v = K.valuePtr();
  Eigen::VectorXd ref(K.rows());
  for (Eigen::Index i = 0; i < K.rows() / 3; ++i) {
    double s[3] = {0, 0, 0};
    for (int k = 0; k < (outer[3 * i + 1] - outer[3 * i]) / 3; ++k) {
      const double* xj = x.data() + inner[outer[3 * i] + 3 * k];
      for (int c = 0; c < 3; ++c) {
        const double* m = v + outer[3 * i + c] + 3 * k;
        s[c] += m[0] * xj[0] + m[1] * xj[1] + m[2] * xj[2];
      }
    }
    ref.segment<3>(3 * i) = Eigen::Vector3d(s[0], s[1], s[2]);
  }
  EXPECT_TRUE((y.array() == ref.array()).all());
  EXPECT_TRUE((yi.array() == ref.array()).all());
}
} // namespace

TEST(MembraneElement, PatchTestReproducesUniformStrainOnIrregularMesh) {
  const Mesh mesh = irregularMesh();
  const Section s = section(generalD());
  const auto g = assemble(mesh, {s}, false);
  const Eigen::MatrixXd K = Eigen::MatrixXd(g.K);
  // Linear field u = G [x, y]: exact strain [u_x, v_y, 0, u_y + v_x, w_y, w_x].
  Eigen::Matrix<double, 3, 2> G;
  G << 1e-3, -2e-3, 3e-3, 0.5e-3, -1e-3, 4e-3;
  const int n = mesh.numNodes();
  Eigen::VectorXd exact(3 * n);
  for (int i = 0; i < n; ++i)
    exact.segment<3>(3 * i) = G * mesh.nodes[i];
  std::vector<bool> boundary(3 * n, false);
  for (int i : mesh.node_sets.at("edges"))
    for (int c = 0; c < 3; ++c)
      boundary[3 * i + c] = true;
  std::vector<int> f, b;
  for (int k = 0; k < 3 * n; ++k)
    (boundary[k] ? b : f).push_back(k);
  Eigen::MatrixXd Kff(f.size(), f.size()), Kfb(f.size(), b.size());
  Eigen::VectorXd ub(b.size());
  for (size_t i = 0; i < f.size(); ++i) {
    for (size_t j = 0; j < f.size(); ++j)
      Kff(i, j) = K(f[i], f[j]);
    for (size_t j = 0; j < b.size(); ++j)
      Kfb(i, j) = K(f[i], b[j]);
  }
  for (size_t j = 0; j < b.size(); ++j)
    ub[j] = exact[b[j]];
  const Eigen::VectorXd uf = Kff.ldlt().solve(-Kfb * ub);
  Eigen::VectorXd u = exact;
  for (size_t i = 0; i < f.size(); ++i)
    u[f[i]] = uf[i];
  // Linear fields are in the element space: the solution is exact to round-off
  // (1e-12 relative to the 4e-3 field amplitude, condition number ~1e3).
  EXPECT_LT((u - exact).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::Matrix<double, 6, 1> eps;
  eps << G(0, 0), G(1, 1), 0, G(0, 1) + G(1, 0), G(2, 1), G(2, 0);
  const Eigen::Matrix<double, 6, 1> sig = s.D * eps;
  for (int e = 0; e < mesh.numElements(); ++e) {
    Eigen::Matrix<double, 9, 1> ae;
    for (int k = 0; k < 3; ++k)
      ae.segment<3>(3 * k) = u.segment<3>(3 * mesh.triangles[e][k]);
    const Eigen::Matrix<double, 6, 1> got = strainMatrix(mesh, e) * ae;
    EXPECT_LT((got - eps).norm(), 1e-12 * eps.norm()) << "element " << e;
    EXPECT_LT((s.D * got - sig).norm(), 1e-11 * sig.norm()) << "element " << e;
  }
}

TEST(MembraneElement, RigidMotionsGiveNoForceAndNoStrainEnergy) {
  const Mesh mesh = irregularMesh();
  const auto g = assemble(mesh, {section(generalD())}, false);
  const int n = mesh.numNodes();
  // Translations along x, y, z and the in-plane rotation u = -y, v = x.
  for (int mode = 0; mode < 4; ++mode) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * n);
    for (int i = 0; i < n; ++i) {
      if (mode < 3)
        u[3 * i + mode] = 1.0;
      else {
        u[3 * i] = -mesh.nodes[i].y();
        u[3 * i + 1] = mesh.nodes[i].x();
      }
    }
    const Eigen::VectorXd f = g.K * u;
    // Scale: |K| ~ 1e10 N/m times |u| ~ 1: forces cancel to round-off.
    EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-4) << "mode " << mode;
    EXPECT_LT(std::abs(0.5 * u.dot(f)), 1e-4) << "mode " << mode;
  }
}

TEST(MembraneElement, OutOfPlaneTiltIsTransverseShearNotRigid) {
  // In this model w = a x is strained: gamma_xz = w_x = a, energy
  // h Area D66 a^2 / 2 exactly (the model's out-of-plane stiffness).
  const Mesh mesh = irregularMesh();
  const Section s = section(generalD());
  lamina::materials::Matrix6 D = s.D;
  const auto g = assemble(mesh, {s}, false);
  const int n = mesh.numNodes();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * n);
  const double a = 1e-3;
  for (int i = 0; i < n; ++i)
    u[3 * i + 2] = a * mesh.nodes[i].x();
  const double U = 0.5 * u.dot(g.K * u);
  EXPECT_NEAR(U, 0.5 * s.thickness * 1.0 * D(5, 5) * a * a, 1e-12 * U);
}

TEST(MembraneElement, IsotropicInPlaneAndOutOfPlaneDecoupleExactly) {
  const Mesh mesh = irregularMesh();
  const auto g =
      assemble(mesh, {section(lamina::materials::Stiffness::isotropic(1e9, 0.3).matrix())}, false);
  // Every K and M entry coupling (u, v) with w is exactly zero.
  for (int r = 0; r < g.K.outerSize(); ++r)
    for (SparseMatrix::InnerIterator it(g.K, r); it; ++it)
      if ((r % 3 == 2) != (it.col() % 3 == 2)) {
        EXPECT_EQ(it.value(), 0.0);
      }
  // A normal strike moves nothing in-plane, an in-plane strike nothing out of plane.
  for (const char* dir : {"[0.0, 0.0, 1.0]", "[1.0, 0.0, 0.0]"}) {
    const Model m = test::modelFromText(test::isotropicSquare(10) + R"(
[time]
dt = 2.0e-5
t_end = 1.0e-3
[[fixed]]
nodes = "edges"
[[strike]]
at = [0.5, 0.5]
speed = 5.0
direction = )" + dir + "\n");
    Simulation sim(m);
    for (int s = 0; s < 30; ++s)
      sim.step();
    double inplane = 0, outplane = 0;
    for (int i = 0; i < m.mesh.numNodes(); ++i) {
      inplane = std::max({inplane, std::abs(sim.u()[3 * i]), std::abs(sim.u()[3 * i + 1])});
      outplane = std::max(outplane, std::abs(sim.u()[3 * i + 2]));
    }
    if (dir[1] == '0') {
      EXPECT_EQ(inplane, 0.0);
      EXPECT_GT(outplane, 0.0);
    } else {
      EXPECT_EQ(outplane, 0.0);
      EXPECT_GT(inplane, 0.0);
    }
  }
}

TEST(MembraneElement, MassMatrixCarriesTheMembraneMass) {
  // sum_ij M_ij over one component = rho h Area, consistent and lumped.
  const Mesh mesh = irregularMesh();
  const Section s = section(generalD());
  for (bool lumped : {false, true}) {
    const auto g = assemble(mesh, {s}, lumped);
    double total = 0;
    for (int r = 0; r < g.M.outerSize(); r += 3)
      for (SparseMatrix::InnerIterator it(g.M, r); it; ++it)
        total += it.value();
    EXPECT_NEAR(total, s.density * s.thickness * 1.0, 1e-12 * total);
  }
}

namespace {
/// The assembly of a monoclinic law (no in-plane/normal coupling: split
/// blocks) on a perturbed 30 x 30 grid, perturbation seed @p seed.
GlobalMatrices splitAssembly(unsigned seed) {
  return assemble(perturbedGrid(30, 0.006, seed), {section(monoclinicD())}, false);
}
} // namespace

TEST(MembraneElement, BlockProductsEqualTheAssembledMatrix) {
  // Shared rows (uniform structured mesh) and plain blocks (irregular mesh)
  // both reproduce K x; shared rows differ from their own by < 1e-14 of the
  // row's largest entry by construction, hence the 1e-13 relative bound.
  const Mesh irregular = perturbedGrid(40, 0.005, 5);
  const Mesh uniform = structuredRectangle(1.0, 1.0, 40, 40);
  for (const Mesh* m : {&uniform, static_cast<const Mesh*>(&irregular)}) {
    const auto g = assemble(*m, {section(generalD())}, false);
    const BlockMatrix B(g.K);
    EXPECT_FALSE(B.splitBlocks()); // generalD couples u, v with w
    if (m == &uniform)
      EXPECT_GT(B.sharedRows(), 0);
    else
      EXPECT_EQ(B.sharedRows(), 0);
    Eigen::VectorXd x = Eigen::VectorXd::Random(g.K.rows()), y;
    const Eigen::VectorXd ref = g.K * x;
    const double dot = B.multiplyDot(x, y);
    EXPECT_LT((y - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff());
    EXPECT_NEAR(dot, x.dot(ref), 1e-12 * std::abs(x.dot(ref)) + 1e-12 * ref.norm() * x.norm());
    // The planar product of the CG, on row ranges split anywhere (as the
    // threads split them: inside runs of shared rows too), same bounds.
    const int n = B.nodes();
    Eigen::VectorXd xp(3 * n), yp = Eigen::VectorXd::Constant(3 * n, 1e300), yi(3 * n);
    toPlanar(x.data(), xp.data(), n, 0, n);
    double pdot = 0;
    for (const auto& [b, e] : {std::pair{0, 17}, {17, 400}, {400, 401}, {401, n}})
      pdot += B.multiplyPlanar(xp.data(), yp.data(), b, e);
    fromPlanar(yp.data(), yi.data(), n, 0, n);
    EXPECT_LT((yi - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff());
    EXPECT_NEAR(pdot, x.dot(ref), 1e-12 * std::abs(x.dot(ref)) + 1e-12 * ref.norm() * x.norm());
    if (B.sharedRows() == 0)
      expectBlockRowOrder(g.K, x, y, yi);
  }
}

// A law without in-plane/transverse-shear coupling gives blocks with exact
// zeros between u, v and w; BlockMatrix then stores five numbers per block.
// Its products must equal bit for bit the scalar product of the CSR matrix
// block after block (the zeros add nothing), with either kernel and in both
// vector layouts, and the diagonal blocks must be those of the matrix.
TEST(BlockMatrix, SplitBlocksGiveTheBitsOfTheFullBlocks) {
  const auto g = splitAssembly(13);
  const BlockMatrix B(g.K), full(g.K, BlockStorage::Plain);
  ASSERT_TRUE(B.splitBlocks());
  ASSERT_FALSE(full.splitBlocks());
  const Eigen::VectorXd x = Eigen::VectorXd::Random(g.K.rows());
  const int n = B.nodes();
  Eigen::VectorXd xp(3 * n), y, yp(3 * n), yi(3 * n), yf;
  toPlanar(x.data(), xp.data(), n, 0, n);
  for (const BlockKernel kernel : {BlockKernel::Fastest, BlockKernel::Scalar}) {
    BlockMatrix::useKernel(kernel);
    const double dot = B.multiplyDot(x, y);
    const double pdot = B.multiplyPlanar(xp.data(), yp.data(), 0, n);
    fromPlanar(yp.data(), yi.data(), n, 0, n);
    expectBlockRowOrder(g.K, x, y, yi);
    EXPECT_EQ(dot, full.multiplyDot(x, yf));
    EXPECT_TRUE((yf.array() == y.array()).all());
    EXPECT_EQ(pdot, dot);
  }
  BlockMatrix::useKernel(BlockKernel::Fastest);
  for (int i = 0; i < n; i += 37)
    EXPECT_TRUE((B.diagonalBlock(i).array() == full.diagonalBlock(i).array()).all()) << i;
}

// Split blocks are stored in slices of four rows; a thread's share of the
// rows need not start or end on a slice. A product over two parts split
// inside a slice must give the whole product's rows, leave the rows outside
// its part untouched, and return the parts of x.y (summed in node order, so
// their sum equals the whole one to round-off: 1e-13 of sum |x_i y_i| over
// about 3000 terms, each rounding ~1e-16 of that sum).
TEST(BlockMatrix, SplitSlicesGiveTheRowsOfAnyPart) {
  const auto g = splitAssembly(17);
  const BlockMatrix B(g.K);
  ASSERT_TRUE(B.splitBlocks());
  const int n = B.nodes();
  const Eigen::VectorXd x = Eigen::VectorXd::Random(3 * n);
  for (const BlockKernel kernel : {BlockKernel::Fastest, BlockKernel::Scalar}) {
    BlockMatrix::useKernel(kernel);
    Eigen::VectorXd whole(3 * n);
    const double dot = B.multiplyPlanar(x.data(), whole.data(), 0, n);
    constexpr double kUntouched = 12345.0;
    // Rows [b, e) of y are the whole product's, the others kUntouched.
    auto expectPart = [&](const Eigen::VectorXd& y, int b, int e) {
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(y[c * n + i], i >= b && i < e ? whole[c * n + i] : kUntouched)
              << "part [" << b << ", " << e << "), row " << i;
    };
    for (const int cut : {1, 2, 3, 5, n / 2 + 1, n - 1}) {
      Eigen::VectorXd y = Eigen::VectorXd::Constant(3 * n, kUntouched);
      const double d1 = B.multiplyPlanar(x.data(), y.data(), 0, cut);
      expectPart(y, 0, cut);
      const double d2 = B.multiplyPlanar(x.data(), y.data(), cut, n);
      expectPart(y, 0, n);
      EXPECT_NEAR(d1 + d2, dot, 1e-13 * x.cwiseProduct(whole).cwiseAbs().sum()) << "cut " << cut;
    }
    for (const auto& [b, e] : {std::pair<int, int>{5, 7}, {9, 10}, {n - 3, n - 1}}) {
      Eigen::VectorXd y = Eigen::VectorXd::Constant(3 * n, kUntouched); // inside one slice
      B.multiplyPlanar(x.data(), y.data(), b, e);
      expectPart(y, b, e);
    }
  }
  BlockMatrix::useKernel(BlockKernel::Fastest);
}

// With split blocks, a vector without in-plane part has a product whose
// in-plane components are +0 and whose normal one is A(2,2) x_2; the
// products that compute the normal plane alone must give the full
// product's bits (sign of zero included) and its x.y, with either kernel,
// in both layouts and on parts that cut a slice; a vector with one in-plane
// component not zero must take the full product.
TEST(BlockMatrix, NormalPlaneAloneGivesTheBitsOfTheFullProduct) {
  const auto g = splitAssembly(19);
  const BlockMatrix B(g.K);
  ASSERT_TRUE(B.splitBlocks());
  const int n = B.nodes();
  Eigen::VectorXd x = Eigen::VectorXd::Random(3 * n); // interleaved
  for (int i = 0; i < n; ++i) {
    x[3 * i] = i % 2 ? 0.0 : -0.0; // zeros of both signs
    x[3 * i + 1] = i % 3 ? -0.0 : 0.0;
  }
  Eigen::VectorXd xp(3 * n);
  toPlanar(x.data(), xp.data(), n, 0, n);
  for (const BlockKernel kernel : {BlockKernel::Fastest, BlockKernel::Scalar}) {
    BlockMatrix::useKernel(kernel);
    // Interleaved: the product finds the zero in-plane part by itself.
    Eigen::VectorXd full, normal;
    BlockMatrix::usePlaneSkipping(PlaneSkipping::Never);
    const double dot_full = B.multiplyDot(x, full);
    BlockMatrix::usePlaneSkipping(PlaneSkipping::Automatic);
    const double dot_normal = B.multiplyDot(x, normal);
    EXPECT_TRUE(test::sameBits(full, normal));
    EXPECT_EQ(dot_full, dot_normal);
    for (int i = 0; i < n; ++i) // what the normal plane alone relies on
      ASSERT_TRUE(full[3 * i] == 0 && !std::signbit(full[3 * i]) && !std::signbit(full[3 * i + 1]))
          << "node " << i;
    // Planar, on two parts that cut a slice: y's in-plane planes hold +0;
    // the second part's rows are untouched by the first (threads share y).
    Eigen::VectorXd yf(3 * n), yn = Eigen::VectorXd::Zero(3 * n);
    const double pdot = B.multiplyPlanar(xp.data(), yf.data(), 0, n);
    const int cut = n / 2 + 1;
    constexpr double kUntouched = 12345.0;
    yn.tail(n - cut).setConstant(kUntouched); // plane 2 of rows [cut, n)
    const double d1 = B.multiplyPlanar(xp.data(), yn.data(), 0, cut, BlockPlanes::Normal);
    for (int i = cut; i < n; ++i)
      ASSERT_EQ(yn[2 * n + i], kUntouched) << "row " << i;
    const double d2 = B.multiplyPlanar(xp.data(), yn.data(), cut, n, BlockPlanes::Normal);
    EXPECT_TRUE(test::sameBits(yf, yn));
    // Each part sums its rows in node order, as the whole does: equal to
    // round-off (1e-13 of sum |x_i y_i| over about 3000 terms), and the
    // whole range gives the whole product's sum exactly.
    EXPECT_NEAR(d1 + d2, pdot, 1e-13 * xp.cwiseProduct(yf).cwiseAbs().sum());
    EXPECT_EQ(B.multiplyPlanar(xp.data(), yn.data(), 0, n, BlockPlanes::Normal), pdot);
    // One in-plane component not zero: the full product.
    Eigen::VectorXd x1 = x, y1, y1full;
    x1[3 * (n / 3) + 1] = 1e-300;
    B.multiplyDot(x1, y1);
    BlockMatrix::usePlaneSkipping(PlaneSkipping::Never);
    B.multiplyDot(x1, y1full);
    BlockMatrix::usePlaneSkipping(PlaneSkipping::Automatic);
    EXPECT_TRUE(test::sameBits(y1, y1full));
    EXPECT_NE(y1[3 * (n / 3) + 1], 0.0); // the diagonal block times 1e-300
  }
  BlockMatrix::useKernel(BlockKernel::Fastest);
}

// The CG on threads (above 30,000 rows; the product above 10,000 nodes):
// every thread checks its rows of x and r, all take the normal plane alone
// only when no thread found an in-plane part, and their products cut the
// slices of four rows at the threads' bounds. A = M + c K of a perturbed
// 110 x 110 grid (12,321 nodes, split blocks, no shared rows), b without
// in-plane part: the solution must be the full products' bit for bit, with
// the same iterations; one in-plane component in the last thread's rows
// must send every thread to the full products.
TEST(StepSolver, NormalPlaneAloneOnThreadsGivesTheBitsOfTheFullSolve) {
  const auto g = assemble(perturbedGrid(110, 0.002, 23), {section(monoclinicD())}, false);
  const SparseMatrix A = g.M + 1e-12 * g.K;
  ASSERT_TRUE(BlockMatrix(A).splitBlocks());
  ASSERT_EQ(BlockMatrix(A).sharedRows(), 0);
  const int n = static_cast<int>(A.rows());
  // the in-plane component: node n/3 - 1, in the last thread's rows
  test::expectNormalPlaneSolve(A, Eigen::VectorXd::Random(n), n - 3);
}

// The plain-block product has two kernels, AVX and the scalar loop a CPU
// without AVX runs; both do the same operations in the same order (AVX
// without FMA), so on an irregular mesh (plain storage) their products and
// dot products must be equal to the bit, in both vector layouts. On a CPU
// without AVX both runs take the scalar loop and the test still holds.
TEST(BlockMatrix, ScalarAndVectorKernelsGiveTheSameBits) {
  const Mesh irregular = perturbedGrid(30, 0.006, 11);
  const auto g = assemble(irregular, {section(generalD())}, false);
  const BlockMatrix B(g.K);
  ASSERT_EQ(B.sharedRows(), 0); // plain storage: the kernels under test
  const Eigen::VectorXd x = Eigen::VectorXd::Random(g.K.rows());
  const int n = B.nodes();
  Eigen::VectorXd xp(3 * n), y[2], yp[2];
  double dot[2], dotp[2];
  toPlanar(x.data(), xp.data(), n, 0, n);
  for (int k = 0; k < 2; ++k) {
    BlockMatrix::useKernel(k == 0 ? BlockKernel::Fastest : BlockKernel::Scalar);
    dot[k] = B.multiplyDot(x, y[k]);
    yp[k].resize(3 * n);
    dotp[k] = B.multiplyPlanar(xp.data(), yp[k].data(), 0, n);
  }
  BlockMatrix::useKernel(BlockKernel::Fastest);
  EXPECT_EQ(dot[0], dot[1]);
  EXPECT_EQ(dotp[0], dotp[1]);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    ASSERT_EQ(y[0][i], y[1][i]) << "dof " << i;
    ASSERT_EQ(yp[0][i], yp[1][i]) << "planar entry " << i;
  }
  // and both are K x (the bound of the product test above)
  const Eigen::VectorXd ref = g.K * x;
  EXPECT_LT((y[1] - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff());
}
