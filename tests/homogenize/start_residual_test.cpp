// The right-hand side of a load case, b = -D^T C E, as the solver forms it
// (start_residual.hpp: only node rows next to an interface): zero wherever
// the 8 voxels around a node share a phase (the divergence of a uniform
// stress), summing to zero over the periodic cell (the nodal forces of a
// periodic stress field balance), with the average stress equal to the
// phase-fraction-weighted phase stresses, and equal to the cell operator's
// D^T C (-E) at u = 0.

#include "homogenize/cell_operator.hpp"
#include "homogenize/start_residual.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <random>

namespace lamina::test {
namespace {

using materials::Stiffness;

// 10 x 12 x 14 voxels of unequal edges: an isotropic matrix with a block of
// a second isotropic phase and, on its face, a few voxels of a generic
// anisotropic phase (as composite voxels are); the rows away from the block
// are uniform, those through it are not, and one voxel sits on the
// periodic boundary in z.
struct Cell {
  homogenize::Grid grid;
  std::vector<std::int32_t> phase;
  std::vector<Stiffness> C{Stiffness::isotropic(156e6, 0.494), Stiffness::isotropic(890e6, 0.491)};
  Cell() {
    grid.n = {10, 12, 14};
    grid.h = {0.1, 0.08, 0.07};
    phase.assign(grid.size(), 0);
    for (int i = 3; i < 7; ++i)
      for (int j = 2; j < 9; ++j)
        for (int k = 5; k < 12; ++k)
          phase[index(i, j, k)] = 1;
    // a symmetric positive definite 6x6: diagonally dominant
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e7, 1e7);
    materials::Matrix6 A;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b <= a; ++b)
        A(a, b) = A(b, a) = a == b ? 5e8 + u(rng) : u(rng);
    C.emplace_back(A);
    for (int k = 5; k < 9; ++k)
      phase[index(3, 4, k)] = 2;
    phase[index(6, 8, 11)] = 2;
    // an interface across the periodic z boundary (node 0 takes voxel n2 - 1)
    phase[index(1, 10, 13)] = 1;
  }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * static_cast<std::size_t>(grid.n[1]) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(grid.n[2]) +
           static_cast<std::size_t>(k);
  }
  /// @return true if the 8 voxels around node (i, j, k) (its lower corner
  /// voxels along each axis, periodic) share one phase
  bool surroundedByOnePhase(int i, int j, int k) const {
    const std::int32_t p = phase[index(i, j, k)];
    for (int di = 0; di < 2; ++di)
      for (int dj = 0; dj < 2; ++dj)
        for (int dk = 0; dk < 2; ++dk) {
          const int a = (i - di + grid.n[0]) % grid.n[0], b = (j - dj + grid.n[1]) % grid.n[1],
                    c = (k - dk + grid.n[2]) % grid.n[2];
          if (phase[index(a, b, c)] != p)
            return false;
        }
    return true;
  }
};

// A general strain: all six components, of both signs.
const std::array<double, 6> kE{1.3e-3, -2.1e-3, 0.7e-3, 3.1e-3, -1.1e-3, 2.3e-3};

TEST(StartResidual, ZeroAwayFromInterfacesAndBalanced) {
  const Cell cell;
  const auto dist = homogenize::Distribution::serial(cell.grid);
  const homogenize::StartResidual start(cell.grid, cell.phase, cell.C, dist);
  const std::size_t N = cell.grid.size();
  std::vector<double> b(3 * N, std::nan(""));
  std::array<double, 6> average{};
  start.apply(kE, b.data(), average);
  int zero_nodes = 0, interface_nodes = 0;
  double sum[3] = {0, 0, 0}, magnitude = 0;
  for (int i = 0; i < cell.grid.n[0]; ++i)
    for (int j = 0; j < cell.grid.n[1]; ++j)
      for (int k = 0; k < cell.grid.n[2]; ++k) {
        const std::size_t v = cell.index(i, j, k);
        const bool uniform = cell.surroundedByOnePhase(i, j, k);
        zero_nodes += uniform;
        interface_nodes += !uniform;
        for (int c = 0; c < 3; ++c) {
          const double f = b[static_cast<std::size_t>(c) * N + v];
          ASSERT_TRUE(std::isfinite(f)) << "node " << i << " " << j << " " << k;
          // the stencil's differences of equal stresses are exact zeros
          if (uniform) {
            EXPECT_EQ(f, 0.0) << "node " << i << " " << j << " " << k << " component " << c;
          }
          sum[c] += f;
          magnitude += std::abs(f);
        }
      }
  ASSERT_GT(zero_nodes, 0);
  ASSERT_GT(interface_nodes, 0);
  // each nodal force enters its sum once and carries a relative round-off
  // of a few 1e-16: 1e-13 of the sum of magnitudes is round-off with margin
  for (double s : sum)
    EXPECT_NEAR(s, 0.0, 1e-13 * magnitude);
  // <C E> = sum over phases of (voxel fraction) C_p E: a sum of N terms in
  // a different order, so round-off of N * 1e-16 relative to max |C E|
  std::vector<double> count(cell.C.size(), 0.0);
  for (std::int32_t p : cell.phase)
    count[static_cast<std::size_t>(p)] += 1;
  Eigen::Matrix<double, 6, 1> E, expected = Eigen::Matrix<double, 6, 1>::Zero();
  for (int a = 0; a < 6; ++a)
    E(a) = kE[static_cast<std::size_t>(a)];
  for (std::size_t p = 0; p < cell.C.size(); ++p)
    expected += count[p] / static_cast<double>(N) * (cell.C[p].matrix() * E);
  const double scale = expected.cwiseAbs().maxCoeff();
  for (int a = 0; a < 6; ++a)
    EXPECT_NEAR(average[static_cast<std::size_t>(a)], expected(a), 1e-16 * N * scale) << a;
}

// The solver used the cell operator at u = 0 before (D^T C (-E), its
// average negated); the rows formed next to interfaces use the same stencil
// functions, so with one thread (one summation order) the two agree bit for
// bit, and the single-precision b is the double one rounded.
TEST(StartResidual, EqualsTheCellOperatorAtZeroDisplacement) {
  const Cell cell;
  const auto dist = homogenize::Distribution::serial(cell.grid);
  const homogenize::StartResidual start(cell.grid, cell.phase, cell.C, dist);
  const homogenize::CellOperator A(cell.grid, cell.phase, cell.C, dist);
  const std::size_t n = 3 * cell.grid.size();
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  std::vector<double> b(n), f(n);
  std::vector<float> b_single(n);
  std::array<double, 6> average{}, operator_average{}, single_average{};
  start.apply(kE, b.data(), average);
  start.apply(kE, b_single.data(), single_average);
  const std::array<double, 6> minus_E{-kE[0], -kE[1], -kE[2], -kE[3], -kE[4], -kE[5]};
  A.apply(nullptr, minus_E, f.data(), &operator_average);
  omp_set_num_threads(saved);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(b[i], f[i]) << "entry " << i;
    ASSERT_EQ(b_single[i], static_cast<float>(f[i])) << "entry " << i;
  }
  for (std::size_t a = 0; a < 6; ++a) {
    EXPECT_EQ(average[a], -operator_average[a]) << a;
    EXPECT_EQ(single_average[a], average[a]) << a;
  }
}

} // namespace
} // namespace lamina::test
