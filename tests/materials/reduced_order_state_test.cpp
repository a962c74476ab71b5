/// @file reduced_order_state_test.cpp
/// @brief The state of the reduced-order law: its size is the documented
/// layout (per partition its strain, 6, then its law's state), restarting
/// from a copied state gives bit-identical stresses (also when the state
/// aliases the previous one), and the stored partition strains and stresses
/// average to the coarse strain and stress.

#include "reduced_order_cells.hpp"

#include "materials/gvbo_law.hpp"
#include "materials/reduced_order_law.hpp"

#include <gtest/gtest.h>

namespace lamina {
namespace {

namespace mat = materials;
using mat::Matrix6;
using mat::Vector6;

/// A laminate of @p per_phase GVBO and @p per_phase elastic layers (0.81 / 0.19).
mat::ReducedOrderModel cell(int per_phase) {
  std::vector<int> layer_phase;
  std::vector<double> c;
  for (int k = 0; k < per_phase; ++k) {
    layer_phase.insert(layer_phase.end(), {0, 1});
    c.insert(c.end(), {0.81 / per_phase, 0.19 / per_phase});
  }
  return test::laminateCell({test::softGvbo(), test::hardElastic()}, layer_phase, c);
}

TEST(ReducedOrderState, SizeIsTheDocumentedLayout) {
  for (int per_phase : {1, 8}) {
    const mat::ReducedOrderLaw law("cell", cell(per_phase));
    // per GVBO partition 6 + 20, per elastic partition 6 + 0
    EXPECT_EQ(law.stateSize(), per_phase * (6 + mat::GvboState::kSize) + per_phase * 6);
    int offset = 0;
    for (int a = 0; a < 2 * per_phase; ++a) {
      EXPECT_EQ(law.stateOffset(a), offset) << "partition " << a;
      offset += 6 + (a % 2 == 0 ? mat::GvboState::kSize : 0);
    }
  }
  EXPECT_EQ(mat::ReducedOrderLaw("cell", cell(1)).stateSize(), 32);
  EXPECT_EQ(mat::ReducedOrderLaw("cell", cell(8)).stateSize(), 256);
}

/// Steps @p law along a fixed strain history from @p state (in place) for
/// steps [from, to); @return the stresses.
std::vector<Vector6> run(const mat::ConstitutiveLaw& law, std::vector<double>& state, int from,
                         int to) {
  Vector6 dir;
  dir << -0.04, 0.01, 0.02, 0.05, -0.01, 0.03;
  std::vector<Vector6> out;
  for (int i = from; i < to; ++i) {
    const double e0 = std::sin(0.2 * i), e1 = std::sin(0.2 * (i + 1));
    const mat::PointStep s{dir * e0, dir * e1, 1 + dir.head<3>().sum() * e0,
                           1 + dir.head<3>().sum() * e1, 1e-3};
    std::vector<double> next(state.size());
    Vector6 sigma;
    law.update(s, state.data(), next.data(), sigma, nullptr);
    state = next;
    out.push_back(sigma);
  }
  return out;
}

TEST(ReducedOrderState, RestartFromACopiedStateIsBitIdentical) {
  const mat::ReducedOrderLaw law("cell", cell(2));
  std::vector<double> state(static_cast<std::size_t>(law.stateSize()));
  law.initState(state.data());
  std::vector<Vector6> whole = run(law, state, 0, 10);
  std::vector<double> copy = state; // a checkpoint at step 10
  const std::vector<Vector6> rest = run(law, state, 10, 30);
  const std::vector<Vector6> again = run(law, copy, 10, 30);
  ASSERT_EQ(rest.size(), again.size());
  for (std::size_t i = 0; i < rest.size(); ++i)
    EXPECT_EQ(rest[i], again[i]) << "step " << 10 + i;
  EXPECT_EQ(state, copy);
}

// The clustering scheme's state also carries its reference medium, refitted
// every step: a restart from a copy is bit-identical too.
TEST(ReducedOrderState, ClusteringRestartFromACopiedStateIsBitIdentical) {
  const mat::ReducedOrderLaw law("cell", test::clustering(cell(2)));
  ASSERT_EQ(law.stateSize(), 4 * (6 + mat::GvboState::kSize) / 2 + 4 * 6 / 2 + 1);
  std::vector<double> state(static_cast<std::size_t>(law.stateSize()));
  law.initState(state.data());
  EXPECT_EQ(state.back(), law.initialReference()[1]);
  run(law, state, 0, 10);
  std::vector<double> copy = state;
  EXPECT_NE(state.back(), law.initialReference()[1]); // the reference has moved
  const std::vector<Vector6> rest = run(law, state, 10, 30);
  const std::vector<Vector6> again = run(law, copy, 10, 30);
  for (std::size_t i = 0; i < rest.size(); ++i)
    EXPECT_EQ(rest[i], again[i]) << "step " << 10 + i;
  EXPECT_EQ(state, copy);
}

TEST(ReducedOrderState, StateMayAliasThePreviousState) {
  for (const mat::ReducedOrderModel& model : {cell(1), test::clustering(cell(1))}) {
    const mat::ReducedOrderLaw law("cell", model);
    std::vector<double> a(static_cast<std::size_t>(law.stateSize())), b(a.size());
    law.initState(a.data());
    law.initState(b.data());
    Vector6 dir;
    dir << 0.03, -0.01, 0.02, 0.05, 0.01, -0.02;
    for (int i = 0; i < 20; ++i) {
      const mat::PointStep s{dir * i / 20.0, dir * (i + 1) / 20.0,
                             1 + dir.head<3>().sum() * i / 20.0,
                             1 + dir.head<3>().sum() * (i + 1) / 20.0, 1e-2};
      std::vector<double> next(a.size());
      Vector6 sa, sb;
      Matrix6 Ta, Tb;
      law.update(s, a.data(), next.data(), sa, &Ta);
      a = next;
      law.update(s, b.data(), b.data(), sb, &Tb);
      EXPECT_EQ(sa, sb);
      EXPECT_EQ(Ta, Tb);
    }
    EXPECT_EQ(a, b);
  }
}

// The stored partition strains average to the coarse strain (sum c A = I and
// sum c P = 0 hold for any cell) up to the Newton residual, at most the
// tolerance times the Newton's scale (strains and eigenstrains); the stored partition stresses
// (GVBO: its state; elastic: L eps) average to the returned stress to round-off (1e-12 relative:
// both are the same sums of the accepted partition strains).
TEST(ReducedOrderState, PartitionStrainsAndStressesAverageToTheCoarseOnes) {
  const mat::ReducedOrderModel m = cell(2);
  const mat::ReducedOrderLaw law("cell", m);
  std::vector<double> state(static_cast<std::size_t>(law.stateSize()));
  law.initState(state.data());
  Vector6 dir;
  dir << 0.03, -0.01, -0.05, 0.05, 0.01, -0.02;
  Vector6 sigma;
  for (int i = 0; i < 10; ++i) {
    const Vector6 e0 = dir * i / 10.0, e1 = dir * (i + 1) / 10.0;
    law.update({e0, e1, 1 + e0.head<3>().sum(), 1 + e1.head<3>().sum(), 1e-2}, state.data(),
               state.data(), sigma, nullptr);
  }
  Vector6 eps_avg = Vector6::Zero(), sig_avg = Vector6::Zero();
  double scale = dir.cwiseAbs().maxCoeff(); // of the Newton: strains and eigenstrains
  for (int a = 0; a < m.partitions(); ++a) {
    const auto ua = static_cast<std::size_t>(a);
    const double* block = state.data() + law.stateOffset(a);
    const Vector6 ea = Eigen::Map<const Vector6>(block);
    const mat::LawSpec& spec = m.phases[static_cast<std::size_t>(m.partition_phase[ua])].law;
    const Vector6 sa = spec.gvbo
                           ? Vector6(Eigen::Map<const Vector6>(block + 6 + mat::GvboState::kSigma))
                           : Vector6(spec.C.matrix() * ea);
    eps_avg += m.fraction[ua] * ea;
    sig_avg += m.fraction[ua] * sa;
    const Vector6 mu = ea - spec.C.matrix().inverse() * sa;
    scale = std::max({scale, ea.cwiseAbs().maxCoeff(), mu.cwiseAbs().maxCoeff()});
  }
  EXPECT_LE((eps_avg - dir).cwiseAbs().maxCoeff(), law.options().tolerance * scale);
  EXPECT_LE((sig_avg - sigma).cwiseAbs().maxCoeff(), 1e-12 * sigma.cwiseAbs().maxCoeff());
}

} // namespace
} // namespace lamina
