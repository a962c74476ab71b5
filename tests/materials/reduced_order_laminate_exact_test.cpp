/// @file reduced_order_laminate_exact_test.cpp
/// @brief For a laminate with one partition per layer the reduced-order
/// system is exact (laminate_reduced_order.hpp): the reduced-order law of a
/// GVBO soft / elastic hard laminate, driven by `materials drive`'s driver,
/// gives the stress of an independent laminate computation (each layer's law
/// driven directly, the out-of-plane layer strains found by Newton on
/// traction continuity and the average) along uniaxial strain, shear and
/// confined paths at two rates, loading and unloading.

#include "reduced_order_cells.hpp"

#include "materials/point_driver.hpp"
#include "materials/reduced_order_law.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>

namespace lamina {
namespace {

namespace mat = materials;
using mat::Vector6;

/// The laminate by its own equations: in-plane strains (xx, yy, xy) of every
/// layer equal the macro ones; the out-of-plane ones (zz, yz, xz) make the
/// out-of-plane stresses equal in all layers and average to the macro ones.
class LaminateOracle {
public:
  LaminateOracle(std::vector<mat::LawPtr> laws, std::vector<double> c)
      : laws_(std::move(laws)), c_(std::move(c)), eps_(laws_.size(), Vector6::Zero()),
        state_(laws_.size()) {
    for (std::size_t a = 0; a < laws_.size(); ++a) {
      state_[a].resize(static_cast<std::size_t>(laws_[a]->stateSize()));
      laws_[a]->initState(state_[a].data());
    }
  }

  /// One step of small-strain kinematics (J = 1 + tr eps per layer): @return
  /// the macro stress sum c_a sigma^(a).
  Vector6 step(const Vector6& E, double dt) {
    const std::size_t L = laws_.size();
    const auto n3 = static_cast<Eigen::Index>(3 * L);
    Eigen::VectorXd z(n3); // the layers' out-of-plane strains
    for (std::size_t a = 0; a < L; ++a)
      for (int i = 0; i < 3; ++i)
        z(static_cast<Eigen::Index>(3 * a) + i) = eps_[a](kN[i]);
    std::vector<Vector6> eps(L), sigma(L);
    std::vector<mat::Matrix6> T(L);
    std::vector<std::vector<double>> out = state_;
    for (int it = 0;; ++it) {
      EXPECT_LT(it, 50) << "the laminate oracle did not converge";
      if (it >= 50)
        break;
      for (std::size_t a = 0; a < L; ++a) {
        eps[a] = E;
        for (int i = 0; i < 3; ++i)
          eps[a](kN[i]) = z(static_cast<Eigen::Index>(3 * a) + i);
        const mat::PointStep s{eps_[a], eps[a], 1 + eps_[a].head<3>().sum(),
                               1 + eps[a].head<3>().sum(), dt};
        laws_[a]->update(s, state_[a].data(), out[a].data(), sigma[a], &T[a]);
      }
      Eigen::VectorXd r(n3);
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n3, n3);
      const Eigen::Index last = static_cast<Eigen::Index>(3 * (L - 1));
      for (std::size_t a = 0; a < L; ++a) {
        const auto ra = static_cast<Eigen::Index>(3 * a);
        for (int i = 0; i < 3; ++i) {
          if (a + 1 < L) { // traction continuity with the last layer
            r(ra + i) = sigma[a](kN[i]) - sigma[L - 1](kN[i]);
            for (int j = 0; j < 3; ++j) {
              K(ra + i, ra + j) += T[a](kN[i], kN[j]);
              K(ra + i, last + j) -= T[L - 1](kN[i], kN[j]);
            }
          }
          K(last + i, ra + i) = c_[a]; // the average
        }
      }
      for (int i = 0; i < 3; ++i) {
        r(last + i) = -E(kN[i]);
        for (std::size_t a = 0; a < L; ++a)
          r(last + i) += c_[a] * eps[a](kN[i]);
      }
      const Eigen::VectorXd dz = K.partialPivLu().solve(r);
      z -= dz;
      // quadratic convergence: stop at round-off of the strains
      if (dz.lpNorm<Eigen::Infinity>() <= 1e-15 * std::max(E.cwiseAbs().maxCoeff(), 1e-3))
        break;
    }
    Vector6 macro = Vector6::Zero();
    for (std::size_t a = 0; a < L; ++a) {
      macro += c_[a] * sigma[a];
      eps_[a] = eps[a];
    }
    state_ = out;
    return macro;
  }

private:
  static constexpr std::array<int, 3> kN{2, 4, 5}; // zz, yz, xz
  std::vector<mat::LawPtr> laws_;
  std::vector<double> c_;
  std::vector<Vector6> eps_;
  std::vector<std::vector<double>> state_;
};

/// max over the path of |sigma_rom - sigma_laminate| / max over the path of |sigma_laminate|.
double pathDifference(const mat::ConstitutiveLaw& law, const std::vector<mat::LawPtr>& layers,
                      const std::vector<double>& c, const mat::DriveOptions& o) {
  const std::vector<mat::DriveRow> rows = mat::drive(law, o);
  LaminateOracle oracle(layers, c);
  double diff = 0, scale = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const Vector6 s = oracle.step(rows[i].eps, rows[i].t - rows[i - 1].t);
    diff = std::max(diff, (rows[i].sigma - s).cwiseAbs().maxCoeff());
    scale = std::max(scale, s.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(scale, 1e5) << "the path loads the laminate (Pa)";
  return diff / scale;
}

// Agreement bound 100 x the Newton tolerance: the law stops its Newton at a
// strain residual of `tolerance` times the strain scale, the oracle at
// round-off. A strain error e moves the stress by at most K e, and the stress
// scale is at least 2 G |eps|: the ratio K / G of these nearly incompressible
// phases (nu = 0.494: 2 (1 + nu) / (3 (1 - 2 nu)) = 83) bounds the
// amplification. With the default tolerance (1e-10) that is 1e-8; with 1e-14
// (round-off) 1e-12, which shows the reduced system itself is exact.
TEST(ReducedOrderLaminate, MatchesTheLaminateAlongEveryPathAtTwoRates) {
  const mat::ReducedOrderModel model = test::polyureaLaminate();
  const std::vector<mat::LawPtr> layers{test::softGvbo().make(), test::hardElastic().make()};
  for (double tolerance : {mat::ReducedOrderOptions{}.tolerance, 1e-14}) {
    const mat::ReducedOrderLaw law("polyurea-laminate", model, {tolerance, 25});
    double worst = 0;
    for (mat::DrivePath path :
         {mat::DrivePath::UniaxialStrain, mat::DrivePath::Shear, mat::DrivePath::Confined})
      for (double rate : {1e-2, 1e3}) {
        mat::DriveOptions o;
        o.path = path;
        o.rate = rate;
        o.to = path == mat::DrivePath::Shear ? 0.3 : 0.15;
        o.unload = true;
        o.steps = 60;
        o.kinematics = mat::Kinematics::Small;
        const double d = pathDifference(law, layers, model.fraction, o);
        EXPECT_LE(d, 100 * tolerance) << mat::toString(path) << " at " << rate << " /s";
        worst = std::max(worst, d);
      }
    std::cout << "Newton tolerance " << tolerance
              << ": max relative stress difference, reduced-order law vs laminate " << worst
              << "\n";
  }
}

// Eight partitions per phase (the same laminate cut into 16 layers) give the
// same stress: sub-layers of one phase share their strain, so the finer
// reduced system is exact too (bound as above).
TEST(ReducedOrderLaminate, EightPartitionsPerPhaseAreExactToo) {
  std::vector<int> layer_phase;
  std::vector<double> c;
  for (int k = 0; k < 8; ++k) {
    layer_phase.insert(layer_phase.end(), {0, 1});
    c.insert(c.end(), {0.81 / 8, 0.19 / 8});
  }
  const mat::ReducedOrderModel model =
      test::laminateCell({test::softGvbo(), test::hardElastic()}, layer_phase, c);
  const mat::ReducedOrderLaw law("laminate-16", model);
  EXPECT_EQ(law.nonlinearPartitions().size(), 8u);
  const std::vector<mat::LawPtr> layers{test::softGvbo().make(), test::hardElastic().make()};
  mat::DriveOptions o;
  o.path = mat::DrivePath::Confined;
  o.rate = 1e3;
  o.to = 0.15;
  o.steps = 40;
  o.kinematics = mat::Kinematics::Small;
  const double d = pathDifference(law, layers, {0.81, 0.19}, o);
  EXPECT_LE(d, 1e-8);
  std::cout << "8 partitions per phase vs laminate: " << d << "\n";
}

} // namespace
} // namespace lamina
