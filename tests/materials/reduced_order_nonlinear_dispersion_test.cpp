/// @file reduced_order_nonlinear_dispersion_test.cpp
/// @brief The nonlinear dispersion of eq. 40 from the reduced-order law:
/// exactly zero when every phase is elastic (even with R, Q nonzero),
/// symmetric to the bit, and for a GVBO laminate with a synthetic positive R
/// equal to eq. 40 evaluated with d mu / d eps^c from central differences of
/// the partitions' eigenstrains mu = eps - L0^-1 sigma.

#include "reduced_order_cells.hpp"

#include "materials/gvbo_law.hpp"
#include "materials/reduced_order_law.hpp"

#include <gtest/gtest.h>

namespace lamina {
namespace {

namespace mat = materials;
using mat::Matrix6;
using mat::Vector6;

TEST(ReducedOrderNonlinearDispersion, ZeroWhenEveryPhaseIsElastic) {
  mat::LawSpec soft_elastic = test::hardElastic();
  soft_elastic.C = mat::Stiffness::isotropic(156e6, 0.494);
  const mat::ReducedOrderModel m =
      test::laminateCell({soft_elastic, test::hardElastic()}, {0, 1}, {0.81, 0.19}, true);
  ASSERT_GT(m.R.norm(), 0.0);
  const mat::ReducedOrderLaw law("elastic-laminate", m);
  mat::ReducedOrderStepInfo info;
  Vector6 sigma;
  mat::PointStep step;
  step.eps << 0.01, -0.02, 0.03, 0.01, 0.02, -0.01;
  law.updateWithInfo(step, nullptr, nullptr, sigma, nullptr, &info);
  EXPECT_EQ(info.dmu_deps.rows(), 0);
  EXPECT_EQ(law.nonlinearDispersion(info), Matrix6::Zero());
}

/// The eigenstrain mu^(a) = eps^(a) - L0^-1 sigma^(a) of the soft (GVBO)
/// partition 0 from the state layout (its strain, then the GVBO state with
/// its stress first).
Vector6 softEigenstrain(const mat::ReducedOrderLaw& law, const std::vector<double>& state) {
  const double* block = state.data() + law.stateOffset(0);
  const Vector6 eps = Eigen::Map<const Vector6>(block);
  const Vector6 sigma = Eigen::Map<const Vector6>(block + 6 + mat::GvboState::kSigma);
  return eps - test::softGvbo().C.matrix().inverse() * sigma;
}

// After a viscous loading, one step at dt = 1e-2 s: d mu / d eps^c of the
// law equals central differences of the soft partition's mu (h = 1e-8, the
// Newton at 1e-14: error ~1e-8 of max |d mu / d eps^c|, bound 1e-6), and
// D_nonlin equals M^T R M + Q M + (Q M)^T with that M to the same bound.
TEST(ReducedOrderNonlinearDispersion, IsEq40WithTheEigenstrainSensitivities) {
  const mat::ReducedOrderModel m = test::polyureaLaminate(true);
  const mat::ReducedOrderLaw law("polyurea-laminate", m, {1e-14, 25});
  ASSERT_EQ(law.nonlinearPartitions(), std::vector<int>{0});
  Vector6 E;
  E << 0.05, 0.01, 0.03, 0.04, 0.01, -0.03;
  std::vector<double> state;
  const Vector6 eps = test::loadAlong(law, E, 10, 1e-2, state);
  Vector6 sigma;
  Vector6 de;
  de << 0.002, -0.001, 0.0005, 0.003, -0.002, 0.001;
  const mat::PointStep step{eps, eps + de, 1 + eps.head<3>().sum(), 1 + (eps + de).head<3>().sum(),
                            1e-2};
  std::vector<double> out(state.size());
  mat::ReducedOrderStepInfo info;
  law.updateWithInfo(step, state.data(), out.data(), sigma, nullptr, &info);
  ASSERT_EQ(info.dmu_deps.rows(), 6);
  Matrix6 M;
  const double h = 1e-8;
  for (int j = 0; j < 6; ++j) {
    mat::PointStep sp = step, sm = step;
    sp.eps[j] += h;
    sm.eps[j] -= h;
    law.update(sp, state.data(), out.data(), sigma, nullptr);
    const Vector6 a = softEigenstrain(law, out);
    law.update(sm, state.data(), out.data(), sigma, nullptr);
    M.col(j) = (a - softEigenstrain(law, out)) / (2 * h);
  }
  const Matrix6 Mlaw = info.dmu_deps;
  EXPECT_LE((Mlaw - M).cwiseAbs().maxCoeff(), 1e-6 * M.cwiseAbs().maxCoeff());
  EXPECT_GT(M.cwiseAbs().maxCoeff(), 1e-3) << "the step is viscous: d mu / d eps^c is not zero";

  const Matrix6 R = m.R.block<6, 6>(0, 0), Q = m.Q.block<6, 6>(0, 0);
  const Matrix6 expect = M.transpose() * R * M + Q * M + (Q * M).transpose();
  const Matrix6 D = law.nonlinearDispersion(info);
  EXPECT_EQ(D, D.transpose()) << "symmetric to the bit";
  EXPECT_GT(D.cwiseAbs().maxCoeff(), 1e-3 * m.D_lin.cwiseAbs().maxCoeff()) << "nonzero";
  EXPECT_LE((D - expect).cwiseAbs().maxCoeff(), 1e-6 * expect.cwiseAbs().maxCoeff());
}

} // namespace
} // namespace lamina
