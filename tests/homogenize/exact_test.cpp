// Exact limits of the cell problem: homogeneous cells, identical phases,
// laminates (exact formula for all 21 constants), objectivity under a
// 90-degree rotation of the microstructure.

#include "oracles.hpp"

#include "micro/inclusion.hpp"
#include "micro/unit_cell.hpp"

namespace lamina::test {
namespace {

std::vector<std::int32_t> sphereMap(const std::array<int, 3>& n, double radius) {
  micro::Inclusion s;
  s.shape = micro::Shape::Sphere;
  s.phase = 1;
  s.semi.setConstant(radius);
  s.center = Eigen::Vector3d(0.5, 0.5, 0.5);
  return micro::voxelize({s}, n, Eigen::Vector3d::Ones());
}

// A homogeneous cell has no fluctuation: C must come back to round-off.
// 1e-10 relative leaves room for the summation order of the averages. Also
// at tol 1e-3, where the operator runs in float: r0 = D^T C (-E) is exactly
// zero there too (differences of equal stresses), CG takes no step, and C
// is <C E> from the double products.
TEST(Homogeneous, CellGivesPhaseStiffnessExactly) {
  std::mt19937 rng(3);
  const Stiffness C = randomStiffness(rng);
  const std::array<int, 3> n{8, 6, 10};
  const std::vector<std::int32_t> map(static_cast<std::size_t>(8 * 6 * 10), 0);
  for (double tol : {1e-8, 1e-3}) {
    const auto r = homogenizeMap(n, map, {C}, tol);
    EXPECT_EQ(r.precision,
              tol < 1e-6 ? homogenize::Precision::Double : homogenize::Precision::Single);
    EXPECT_LT(relDiff(r.C.matrix(), C.matrix()), 1e-10) << "tol " << tol;
    for (int k = 0; k < 6; ++k)
      EXPECT_EQ(r.cases[static_cast<std::size_t>(k)].iterations, 0) << "tol " << tol;
  }
}

// Two phases with the same law are one material: C exactly (1e-10).
TEST(Homogeneous, TwoIdenticalPhasesGiveThatStiffness) {
  std::mt19937 rng(5);
  const Stiffness C = randomStiffness(rng);
  const std::array<int, 3> n{12, 12, 12};
  const auto r = homogenizeMap(n, sphereMap(n, 0.3), {C, C}, 1e-8);
  EXPECT_LT(relDiff(r.C.matrix(), C.matrix()), 1e-10);
}

// Layers normal to `axis`: the rotated-grid solution is exact for a laminate
// of whole voxel layers (piecewise linear displacement across the layers is
// representable), so C equals the laminate formula to solver tolerance. With
// tol 1e-10 the constants agree to ~1e-9 of max|C| (error ~ tol times the
// stiffness contrast of the phases, about 3 here).
void checkLaminate(int axis) {
  std::mt19937 rng(11 + axis);
  const std::vector<Stiffness> C{randomStiffness(rng), randomStiffness(rng), randomStiffness(rng)};
  std::array<int, 3> n{4, 4, 4};
  n[static_cast<std::size_t>(axis)] = 12;
  // layers of 5, 4 and 3 voxels
  std::vector<std::int32_t> map(48 * 4 / 4 * 4, 0);
  map.assign(static_cast<std::size_t>(n[0] * n[1] * n[2]), 0);
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const int c = axis == 0 ? i : axis == 1 ? j : k;
        map[static_cast<std::size_t>((i * n[1] + j) * n[2] + k)] = c < 5 ? 0 : c < 9 ? 1 : 2;
      }
  const auto r = homogenizeMap(n, map, C, 1e-10);
  const Matrix6 exact =
      laminate({C[0].matrix(), C[1].matrix(), C[2].matrix()}, {5.0 / 12, 4.0 / 12, 3.0 / 12}, axis);
  EXPECT_LT(relDiff(r.C.matrix(), exact), 1e-8) << "axis " << axis << "\n"
                                                << r.C.matrix() << "\n\n"
                                                << exact;
  expectWithinVoigtReuss(r.C.matrix(), C, {5.0 / 12, 4.0 / 12, 3.0 / 12});
}

TEST(Laminate, NormalToXMatchesExactFormula) {
  checkLaminate(0);
}
TEST(Laminate, NormalToYMatchesExactFormula) {
  checkLaminate(1);
}
TEST(Laminate, NormalToZMatchesExactFormula) {
  checkLaminate(2);
}

// Rotating the microstructure by +90 degrees about z (voxel (i, j, k) ->
// (n-1-j, i, k): x' = -y, y' = x up to a periodic shift) must rotate C:
// C' = T C T^T, an exact signed permutation. The grid maps onto itself, so
// the two solves differ only by round-off and solver tolerance (1e-10).
TEST(Objectivity, QuarterTurnOfMicrostructurePermutesC) {
  const int N = 12;
  const std::array<int, 3> n{N, N, N};
  std::mt19937 rng(21);
  std::uniform_int_distribution<int> pick(0, 2);
  std::vector<std::int32_t> map(static_cast<std::size_t>(N * N * N)), rot(map.size());
  for (auto& p : map)
    p = pick(rng); // a fully anisotropic random microstructure
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < N; ++k)
        rot[static_cast<std::size_t>(((N - 1 - j) * N + i) * N + k)] =
            map[static_cast<std::size_t>((i * N + j) * N + k)];
  const std::vector<Stiffness> C{Stiffness::isotropic(1e9, 0.3), Stiffness::isotropic(3e9, 0.45),
                                 Stiffness::isotropic(10e9, 0.2)};
  const auto a = homogenizeMap(n, map, C, 1e-10);
  const auto b = homogenizeMap(n, rot, C, 1e-10);
  const Matrix6 expected = a.C.rotated(materials::axisRotation(2, M_PI / 2)).matrix();
  EXPECT_LT(relDiff(b.C.matrix(), expected), 1e-8);
  // and the rotation is not trivial for this microstructure
  EXPECT_GT(relDiff(a.C.matrix(), expected), 1e-4);
}

} // namespace
} // namespace lamina::test
