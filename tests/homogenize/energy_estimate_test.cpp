// The energy (Hill-Mandel) estimate of C: it equals the energy integral
// <eps_j : C : eps_k> of the six solutions, and its error obeys the a-priori
// bound that makes it quadratic in the solver's residuals, in double and in
// single-precision preconditioning.

#include "oracles.hpp"

#include "homogenize/cell_operator.hpp"
#include "micro/inclusion.hpp"
#include "micro/unit_cell.hpp"

#include <cmath>
#include <cstdio>

namespace lamina::test {
namespace {

// Two random ellipsoids of stiff isotropic material in a nearly
// incompressible matrix (the polyurea contrast), 16^3: no symmetry, so all
// 21 constants are generic.
struct Cell {
  std::array<int, 3> n{16, 16, 16};
  std::vector<std::int32_t> map;
  std::vector<Stiffness> C{Stiffness::isotropic(156e6, 0.494), Stiffness::isotropic(890e6, 0.491)};
  Cell() {
    micro::Inclusion a, b;
    a.shape = b.shape = micro::Shape::Ellipsoid;
    a.phase = b.phase = 1;
    a.semi = Eigen::Vector3d(0.3, 0.15, 0.2);
    a.center = Eigen::Vector3d(0.3, 0.4, 0.5);
    a.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    b.semi = Eigen::Vector3d(0.12, 0.25, 0.1);
    b.center = Eigen::Vector3d(0.75, 0.8, 0.2);
    b.R = Eigen::AngleAxisd(-0.4, Eigen::Vector3d(2, -1, 1).normalized()).toRotationMatrix();
    map = micro::voxelize({a, b}, n, Eigen::Vector3d::Ones());
  }
  homogenize::Grid grid() const {
    homogenize::Grid g;
    g.n = n;
    g.h = {1.0 / n[0], 1.0 / n[1], 1.0 / n[2]};
    return g;
  }
  homogenize::Result run(homogenize::Options o,
                         std::vector<std::vector<double>>* fields = nullptr) const {
    homogenize::Homogenizer h(grid(), map, C, {1000.0, 1000.0}, o);
    if (fields)
      h.setDisplacementSink(
          [&](int, const double* u) { fields->emplace_back(u, u + 3 * grid().size()); });
    return h.run();
  }
};

homogenize::Options options(double tol, homogenize::Precision p) {
  homogenize::Options o;
  o.tol = tol;
  o.precision = p;
  return o;
}

class EnergyEstimate : public ::testing::TestWithParam<homogenize::Precision> {};

// C_jk = <sigma_k>_j - x_j^T r_k / N is an identity for the energy form; the
// energy integral itself comes out of the operator's stress pass. By
// polarization, 2 N C_jk = W(E_j + E_k, x_j + x_k) - W(E_j, x_j) - W(E_k, x_k)
// with W(E, u) = sum over voxels of eps : C : eps. Both sides are sums of
// N terms of size max|C|: 1e-10 relative is double round-off with margin.
// In single precision the solver's operator, residual and displacements are
// float (unit round-off 6e-8; the residual is updated recursively over the
// iterations): 1e-6 relative, still 4 decades below the error a broken
// identity would leave (linear in the residual, 1e-2 here).
TEST_P(EnergyEstimate, EqualsTheEnergyIntegralOfTheSixSolutions) {
  const Cell cell;
  // loose tolerance: the identity holds at any iterate
  std::vector<std::vector<double>> x;
  const auto r = cell.run(options(1e-2, GetParam()), &x);
  ASSERT_EQ(x.size(), 6u);
  const auto g = cell.grid();
  const auto dist = homogenize::Distribution::serial(g);
  const homogenize::CellOperator A(g, cell.map, cell.C, dist);
  auto W = [&](const std::array<double, 6>& E, const std::vector<double>& u) {
    double w = 0;
    A.apply(u.data(), E, nullptr, nullptr, &w);
    return w;
  };
  const double N = static_cast<double>(g.size());
  const double scale = r.C.matrix().cwiseAbs().maxCoeff();
  for (int j = 0; j < 6; ++j)
    for (int k = j; k < 6; ++k) {
      std::array<double, 6> Ej{}, Ek{}, Ejk{};
      Ej[static_cast<std::size_t>(j)] = 1;
      Ek[static_cast<std::size_t>(k)] = 1;
      Ejk = Ej;
      Ejk[static_cast<std::size_t>(k)] += 1;
      const auto& xj = x[static_cast<std::size_t>(j)];
      const auto& xk = x[static_cast<std::size_t>(k)];
      std::vector<double> xjk(xj.size());
      for (std::size_t i = 0; i < xj.size(); ++i)
        xjk[i] = xj[i] + xk[i];
      const double Cjk = j == k ? W(Ej, xj) / N : (W(Ejk, xjk) - W(Ej, xj) - W(Ek, xk)) / (2 * N);
      const double rel = GetParam() == homogenize::Precision::Double ? 1e-10 : 1e-6;
      EXPECT_NEAR(r.C(j, k), Cjk, rel * scale) << "C(" << j << "," << k << ")";
    }
}

// A-priori bound: with the error e = x* - x, C_jk(x) - C_jk(x*) = e_j^T A e_k / N,
// and e^T A e = r^T A^+ r <= r^T K0^+ r / kappa because A >= kappa K0 with
// kappa = min over phases of min(K/K0, G/G0) (pointwise C >= kappa C0). The
// criterion gives r^T K0^+ r = res^2 N C0_kk, so
//   |C_jk(tol) - C_jk| <= res_j res_k sqrt(C0_jj C0_kk) / kappa,
// quadratic in the residuals (the average stress is off linearly). The
// reference at tol 1e-10 is itself exact to ~1e-20 relative by the same bound.
TEST_P(EnergyEstimate, ErrorIsBoundedByTheProductOfResiduals) {
  const Cell cell;
  const auto ref = cell.run(options(1e-10, homogenize::Precision::Double));
  for (double tol : {1e-2, 1e-3}) {
    const auto r = cell.run(options(tol, GetParam()));
    const Stiffness C0 = Stiffness::fromLame(r.lambda0, r.mu0);
    const double K0 = r.lambda0 + 2 * r.mu0 / 3;
    double kappa = 1e300;
    for (const auto& c : cell.C)
      kappa = std::min({kappa, materials::voigtBulk(c) / K0, materials::voigtShear(c) / r.mu0});
    double worst_ratio = 0; // of the error to its bound
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) {
        const double bound = r.cases[static_cast<std::size_t>(j)].residual *
                             r.cases[static_cast<std::size_t>(k)].residual *
                             std::sqrt(C0(j, j) * C0(k, k)) / kappa;
        const double err = std::abs(r.C(j, k) - ref.C(j, k));
        EXPECT_LE(err, bound) << "tol " << tol << " C(" << j << "," << k << ")";
        worst_ratio = std::max(worst_ratio, err / bound);
      }
    // and the bound is not vacuous: the error reaches a visible part of it
    EXPECT_GT(worst_ratio, 1e-3) << "tol " << tol;
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, EnergyEstimate,
                         ::testing::Values(homogenize::Precision::Double,
                                           homogenize::Precision::Single),
                         [](const auto& info) {
                           return info.param == homogenize::Precision::Double ? "Double" : "Single";
                         });

// The stress estimate is linear in the residual off the diagonal (on it,
// conjugate gradients make both estimates quadratic: x_k^T r_k = 0): at a
// loose tolerance its off-diagonal constants are an order of magnitude
// further from the converged ones (the reason the energy form is the
// default).
TEST(StressEstimate, IsLessAccurateOffTheDiagonal) {
  const Cell cell;
  const auto ref = cell.run(options(1e-10, homogenize::Precision::Double));
  homogenize::Options o = options(1e-3, homogenize::Precision::Double);
  const auto energy = cell.run(o);
  o.estimate = homogenize::Estimate::Stress;
  const auto stress = cell.run(o);
  auto offDiagonal = [&](const homogenize::Result& r) {
    double e = 0;
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k)
        if (j != k)
          e = std::max(e, std::abs(r.C(j, k) - ref.C(j, k)));
    return e;
  };
  EXPECT_LT(offDiagonal(energy), 0.1 * offDiagonal(stress))
      << offDiagonal(energy) << " vs " << offDiagonal(stress);
  std::printf("off-diagonal error at tol 1e-3: energy %.3g Pa, stress %.3g Pa\n",
              offDiagonal(energy), offDiagonal(stress));
}

} // namespace
} // namespace lamina::test
